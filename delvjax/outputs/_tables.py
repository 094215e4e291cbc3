"""One table schema per result type (docs/model.md §7), used by the CLI and the studies alike.

Each function turns a core result into the columns of its CSV file: degrees for angles, one
name per outcome (`outcome_names`), and the rollout rules as constant columns, so every file
names the rules it was made under.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError
from ..core.maps import VectorMap
from ..core.metrics import error_class
from ..core.rollouts import EXCLUDED, NEAR_WALL, OUTCOMES, RUNNING, Catchment, SuccessRate, Trajectories

OUTCOME_NAMES = {**dict(enumerate(OUTCOMES)), EXCLUDED: "not_placed", RUNNING: "running", NEAR_WALL: "near_wall"}


def outcome_names(codes) -> list[str]:
    """Outcome codes as names: success, timeout, landmark, arena; not_placed (a release point that
    could not be placed); running (never in a finished result)."""
    return [OUTCOME_NAMES[int(c)] for c in np.asarray(codes).reshape(-1).tolist()]


def rule_columns(rules: dict[str, str], n: int) -> dict[str, list[str]]:
    """The rollout rules as constant columns."""
    return {name: [value] * n for name, value in rules.items()}


def vector_map_columns(vm: VectorMap) -> dict[str, np.ndarray]:
    """Per grid point (grid points only): x, y, heading_deg, direction_deg (NaN where invalid),
    error_deg, valid, error_class."""
    inc = np.asarray(vm.included)
    pts = np.asarray(vm.points)[inc]
    return {
        "x": pts[:, 0],
        "y": pts[:, 1],
        "heading_deg": np.degrees(np.asarray(vm.heading)[inc]),
        "direction_deg": np.degrees(np.asarray(vm.direction)[inc]),
        "error_deg": np.asarray(vm.error_deg)[inc],
        "valid": np.asarray(vm.valid)[inc],
        "error_class": np.asarray(error_class(vm.error_deg))[inc],
    }


def catchment_columns(res: Catchment, with_hidden: bool = False) -> dict[str, object]:
    """Per grid point and mask: x, y, heading_deg, success, steps, outcome, end_x, end_y,
    invalid_steps, direction_deg, error_deg, valid, the rules, and (`with_hidden`) the hidden
    landmarks of the mask ("0 2")."""
    inc = np.asarray(res.included)
    n_masks = np.asarray(res.outcome).shape[0]
    pts = np.tile(np.asarray(res.points)[inc], (n_masks, 1))
    per = lambda a: np.asarray(a)[:, inc].reshape(-1)  # noqa: E731
    columns: dict[str, object] = {
        "x": pts[:, 0],
        "y": pts[:, 1],
        "heading_deg": np.tile(np.degrees(np.asarray(res.heading)[inc]), n_masks),
        "success": per(res.success),
        "steps": per(res.steps),
        "outcome": outcome_names(per(res.outcome)),
        "end_x": per(np.asarray(res.end)[..., 0]),
        "end_y": per(np.asarray(res.end)[..., 1]),
        "invalid_steps": per(res.invalid_steps),
        "direction_deg": np.degrees(per(res.direction)),
        "error_deg": per(res.error_deg),
        "valid": per(res.valid),
        **rule_columns(res.rules, pts.shape[0]),
    }
    if with_hidden:
        columns["hidden"] = [" ".join(map(str, h)) for h in res.hidden for _ in range(int(inc.sum()))]
    return columns


def success_rows(res: SuccessRate, method: str) -> list[dict]:
    """Per release distance: method, the bin statistics of `SuccessRate.table` and the rules."""
    return [{"method": method, **row, **res.rules} for row in res.table()]


def success_trial_columns(res: SuccessRate, method: str) -> dict[str, object]:
    """Per trial: method, distance_cm, trial, x, y, heading_deg, placed, success, steps, outcome, the rules."""
    placed = np.asarray(res.placed).reshape(-1)
    start = np.asarray(res.start).reshape(-1, 2)
    n_bins, n_tr = np.asarray(res.placed).shape
    return {
        "method": [method] * placed.size,
        "distance_cm": np.repeat(np.asarray(res.distances), n_tr),
        "trial": np.tile(np.arange(n_tr), n_bins),
        "x": start[:, 0],
        "y": start[:, 1],
        "heading_deg": np.degrees(np.asarray(res.heading).reshape(-1)),
        "placed": placed,
        "success": np.asarray(res.success).reshape(-1),
        "steps": np.asarray(res.steps).reshape(-1),
        "outcome": outcome_names(res.outcome),
        **rule_columns(res.rules, placed.size),
    }


def trajectory_columns(tr: Trajectories, method: str) -> dict[str, list]:
    """Per visited position: method, trial, step, x, y, release_heading_deg, success, steps, outcome, the rules."""
    path, steps = np.asarray(tr.path), np.asarray(tr.steps)
    heading, success, outcome = np.degrees(np.asarray(tr.heading)), np.asarray(tr.success), outcome_names(tr.outcome)
    t = np.repeat(np.arange(path.shape[0]), steps + 1)
    s = np.concatenate([np.arange(n + 1) for n in steps]) if steps.size else np.zeros(0, int)
    return {
        "method": [method] * t.size,
        "trial": t.tolist(),
        "step": s.tolist(),
        "x": path[t, s, 0].tolist(),
        "y": path[t, s, 1].tolist(),
        "release_heading_deg": heading[t].tolist(),
        "success": success[t].tolist(),
        "steps": steps[t].tolist(),
        "outcome": [outcome[i] for i in t],
        **rule_columns(tr.rules, t.size),
    }


def concat_columns(tables: list[dict]) -> dict[str, list]:
    """Columns of several tables of one schema, one after the other."""
    return {k: [v for c in tables for v in np.asarray(c[k], dtype=object).tolist()] for k in tables[0]}


def to_dataframe(result, method: str = ""):
    """A result as a pandas DataFrame with the columns of its CSV file (the schemas above): a `VectorMap`
    per grid point, a `Catchment` per grid point and mask (with the hidden landmarks), a `SuccessRate`
    per trial, `Trajectories` per visited position. `method` fills the method column where there is one."""
    import pandas as pd  # pandas (installed with xarray): loaded only when a table is asked for

    if isinstance(result, VectorMap):
        columns = vector_map_columns(result)
    elif isinstance(result, Catchment):
        columns = catchment_columns(result, with_hidden=True)
    elif isinstance(result, SuccessRate):
        columns = success_trial_columns(result, method)
    elif isinstance(result, Trajectories):
        columns = trajectory_columns(result, method)
    else:
        raise InputError("result", type(result).__name__, "must be a VectorMap, Catchment, SuccessRate or Trajectories")
    return pd.DataFrame({k: list(v) if not isinstance(v, np.ndarray) else v for k, v in columns.items()})
