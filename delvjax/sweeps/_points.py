"""Per-point errors of a vector-map sweep and per-point outcomes of a catchment sweep (docs/sweeps.md "Per-point
errors"): every cell's angular error, or successful trials, at every grid point, for numbers a sum cannot give
(error curves by distance from home, error or failure rates inside and outside a region such as the landmarks'
hull). The same cells, validation, padding and grouping as `run_sweep`; each group's cells in chunks of one
compiled program (`core.cells.map_cells_errors`, `core.rollouts.cells.catchment_cells_points`)."""

from __future__ import annotations

import jax
import numpy as np

from ..core.cells import map_cells_errors
from ..core.deprecation import refuse_unknown, renamed_keyword
from ..core.errors import InputError
from ..core.rollouts import DEFAULT_LANES
from ..core.rollouts.cells import catchment_cells_points
from ..evaluate import _vector_map as api
from ..options._setup import METHOD_SET_WHY
from ._kinds.catchment import catchment_inputs
from ._kinds.cells import idle_padding
from ._kinds.cells import traced as _traced
from ._kinds.vector_map import grid_inputs
from ._run import CELL_CHUNK, _envs, _plan, _setups
from ._spec import SweepSpec

QUANTUM = 8  # cells: a group smaller than a chunk is padded to a multiple of this


def point_errors(spec: SweepSpec, max_points: int = api.MAX_POINTS) -> dict:
    """The per-point errors of every cell of a vector-map sweep of one grid (one spacing, one arena):
    {"errors": (*spec.shape, P) degrees (invalid = 180, NaN where a point is not included), "points": (P, 2)
    cm, "homes": {env label: (2,) cm}, "landmarks": {env label: (L, 3) x, y, r cm}}. Chunks of CELL_CHUNK cells, the last padded to CELL_CHUNK, a group of
    fewer cells to a multiple of QUANTUM (sweeps whose counts differ by a few cells share their programs)."""
    if spec.kind != "vector-map":
        raise InputError("sweep.kind", str(spec.kind), 'must be "vector-map" for per-point errors')
    out = None

    def errors(setups: list[dict], traced: tuple) -> tuple[np.ndarray, dict]:
        (points,), traced = grid_inputs(setups, traced)
        return points, {"errors": np.asarray(map_cells_errors(traced[0], points, traced[-1], *traced[1:4]))}

    points, out, envs = _per_point(spec, max_points, errors, {"errors": np.nan})
    return {"errors": out["errors"], "points": points, **_scenes(envs)}


def point_outcomes(
    spec: SweepSpec,
    max_points: int = api.MAX_POINTS,
    lanes: int = DEFAULT_LANES,
    method_set: tuple[str, ...] | None = None,
    **legacy,
) -> dict:
    """The per-point outcomes of every cell of a catchment sweep of one grid (one spacing, one arena), the trials
    `run_sweep` sums: {"successes": (*spec.shape, P) successful trials of each grid point over the cell's masks,
    "untouched": those that never touched a landmark (the physical rules' successes, `rules.under_collisions`),
    "trials": (*spec.shape, P) trials run from each point (its masks; 0 where not included), "counted": (*spec.shape,
    P) the points the catchment counts, "points", "homes", "landmarks" as `point_errors`}. Chunks as `point_errors`.
    `method_set`: registry names compiled into one program with every cell's method, image methods too (one compiled
    program where the sweep's methods would make several; an image method's numbers may change in the last bit)."""
    method_set = renamed_keyword(legacy, "program", "method_set", method_set, METHOD_SET_WHY)
    refuse_unknown(legacy, "point_outcomes")
    if spec.kind != "catchment":
        raise InputError("sweep.kind", str(spec.kind), 'must be "catchment" for per-point outcomes')

    def outcomes(setups: list[dict], traced: tuple) -> tuple[np.ndarray, dict]:
        (points, max_steps), traced = catchment_inputs(setups, traced)
        cells, included, counted = traced
        ok, untouched = catchment_cells_points(cells, points, included, max_steps, lanes=lanes)
        masks = np.asarray(cells.n_masks)[:, None]
        return points, {
            "successes": np.asarray(ok),
            "untouched": np.asarray(untouched),
            "trials": np.asarray(included) * masks,
            "counted": np.asarray(counted) & np.asarray(included),
        }

    fill = {"successes": 0, "untouched": 0, "trials": 0, "counted": False}
    points, out, envs = _per_point(spec, max_points, outcomes, fill, rollouts=True, method_set=method_set)
    return {**out, "points": points, **_scenes(envs)}


def _per_point(spec: SweepSpec, max_points: int, run, fill: dict, rollouts: bool = False, method_set=None):
    """(points, {name: (*spec.shape, P)}, envs): `run(setups, traced)` -> (points, {name: (cells, P)}) on each
    chunk of each group, a chunk padded as `point_errors` says; rollout cells' masks padded to the sweep's most;
    `method_set` as `point_outcomes`'."""
    envs = _envs(spec)
    kept: dict[int, dict] = {}  # each cell validated once: the setups `_plan` made, kept for the chunks
    groups, _, rows = _plan(spec, envs, max_points, None, method_set, kept)
    grids = {(float(c["spacing"]), tuple(np.asarray(envs[c["env"]].arena).tolist())) for c in spec.cells()}
    if len(grids) > 1:
        raise InputError("axes", sorted(grids), "per-point numbers need one grid: one spacing and one arena")
    out: dict[str, np.ndarray] = {}
    points = None
    stack = lambda *xs: np.stack([np.asarray(x) for x in xs])  # noqa: E731
    for cells in groups:  # one program per group, a few chunks each
        for start in range(0, len(cells), CELL_CHUNK):
            chunk = cells[start : start + CELL_CHUNK]
            size = CELL_CHUNK if len(cells) > CELL_CHUNK else -(-len(chunk) // QUANTUM) * QUANTUM
            padded = chunk + [chunk[0]] * (size - len(chunk))
            setups = _setups(spec, envs, padded, kept, max_points, method_set)
            traced = jax.tree.map(stack, *[_traced(req, rows) if rollouts else _traced(req) for req in setups])
            traced = idle_padding(traced, len(chunk))  # the padding's rollouts run no trials
            points, res = run(setups, traced)
            for name, values in res.items():
                if name not in out:
                    out[name] = np.full((spec.n_cells, len(points)), fill[name], np.asarray(values).dtype)
                out[name][chunk] = values[: len(chunk)]
    shaped = {name: v.reshape(*spec.shape, -1) for name, v in out.items()}
    return np.asarray(points, float), shaped, envs


def _scenes(envs: dict) -> dict:
    """{"homes": {env label: (2,) cm}, "landmarks": {env label: (L, 3) x, y, r cm}} of the sweep's worlds."""
    return {
        "homes": {label: np.asarray(e.home, float) for label, e in envs.items()},
        "landmarks": {label: np.asarray(e.landmarks, float)[np.asarray(e.valid)] for label, e in envs.items()},
    }
