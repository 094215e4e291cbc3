"""Catchment area: a rollout from every grid point under every visibility mask (Figs 4.5, 5.5;
Tables 5.1-5.4; docs/model.md §5)."""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Sequence

import equinox as eqx
import jax
import numpy as np
from jax import Array

from ..batching import bucket, pad_rows
from ..deprecation import refuse_unknown
from ..errors import InputError
from ..maps import grid_included, grid_points, random_headings
from ..methods.base import HomingMethod
from ..metrics import RATES, angular_error_deg, error_point_rates
from ..scene import Env
from ..sensor import Sensor
from ..types import (
    GridFlag,
    GridFloat,
    GridPoints,
    MaskGridFlag,
    MaskGridFloat,
    MaskGridInt,
    MaskGridPoints,
    Masks,
    Real,
)
from .config import Grid, Rules, legacy_config
from .rules import (
    DEFAULT_FIRST_MOVE,
    EXCLUDED,
    NEAR_WALL,
    NO_CONTACT,
    OUTCOMES,
    SUCCESS,
    Outcomes,
    catchment_counted,
    outcome_names,
    rule_columns,
)
from .trials import MASK_ROWS, TRIAL_BLOCK, run_trials


def occlusion_masks(env: Env, k: int) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """All C(N, k) visibility masks (M, L) bool with k of the N landmarks hidden, and the hidden index tuples."""
    n = env.n_landmarks
    combos = list(itertools.combinations(range(n), k))
    masks = np.tile(np.asarray(env.valid, bool), (len(combos), 1))
    for m, hidden in enumerate(combos):  # input preparation: C(N, k) <= 20 small rows
        masks[m, list(hidden)] = False
    return masks, combos


def hidden_masks(env: Env, hidden: Sequence[int] | np.ndarray | None) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """The single mask (1, L) hiding `hidden` (or none; a list or array of indices)."""
    masks = np.asarray(env.valid, bool)[None, :].copy()
    hidden = tuple(int(i) for i in (() if hidden is None else hidden))
    masks[0, list(hidden)] = False
    return masks, [hidden]


class Catchment(Outcomes):
    """Catchment area of one method on the docs/model.md §5 grid under M visibility masks.

    points: (P, 2) all grid cells; included: (P,) grid points (released, and in the vector map);
    counted: (P,) the grid points whose rollout counts in the catchment (`rules.catchment_counted`:
    under first_move "release" at least d from every wall); heading: (P,) release heading rad;
    visible: (M, L) landmarks seen while homing; outcome, steps, invalid_steps: (M, P)
    (outcome EXCLUDED for cells that are not grid points, NEAR_WALL for grid points not counted); end: (M, P, 2); the vector map
    under each mask with the same headings and home record: direction (M, P) world rad
    (NaN where invalid), valid (M, P), error_deg (M, P); the first landmark contact of each rollout
    (`rules.under_collisions`): contact (M, P) its step (NO_CONTACT: none), contact_end (M, P, 2),
    contact_invalid (M, P); grid: the `Grid` it was computed on (None in a result built by hand).
    """

    points: GridPoints
    included: GridFlag
    counted: GridFlag
    heading: GridFloat
    visible: Masks
    outcome: MaskGridInt
    steps: MaskGridInt
    end: MaskGridPoints
    invalid_steps: MaskGridInt
    direction: MaskGridFloat
    valid: MaskGridFlag
    error_deg: MaskGridFloat
    contact: MaskGridInt
    contact_end: MaskGridPoints
    contact_invalid: MaskGridInt
    hidden: tuple = eqx.field(static=True, default=((),))
    first_move: str = eqx.field(static=True, default=DEFAULT_FIRST_MOVE)
    collisions: str = eqx.field(static=True, default="ignore")
    grid: Grid | None = eqx.field(static=True, default=None)

    def columns(self, method: str = "") -> dict:
        """Per grid point and mask, the catchment CSV's columns with the hidden landmarks (`catchment_columns`)."""
        return catchment_columns(self, with_hidden=True)

    def catchment_pct(self) -> np.ndarray:
        """% of grid points whose rollout succeeds, per mask (M,)."""
        inc = np.asarray(self.counted)
        return 100.0 * np.asarray(self.success)[:, inc].mean(axis=1)


def catchment_area(
    env: Env,
    method: HomingMethod,
    sensor: Sensor,
    grid: Grid | None = None,
    rules: Rules | None = None,
    *,
    key: Array | None = None,
    masks: np.ndarray | None = None,
    hidden: Sequence[tuple[int, ...]] = ((),),
    progress: Callable[[int, int], None] | None = None,
    **legacy,
) -> Catchment:
    """Rollouts from every point of `grid` under every mask in `masks` (M, L) by `rules`, one program
    (docs/model.md §5; `Grid`: core/grid.py, `Rules`: core/rollouts/config.py, defaults `Grid()`, `Rules()`).

    Headings: the grid's fixed heading or per point from `key` as in `maps.random_headings`. The trial
    of grid cell i uses noise stream i under every mask (common random numbers across masks).
    The vector map under each mask comes from the same program (each trial's first direction).
    `progress(done, total)` after each block of trials. The result carries its grid. The flat
    keywords of earlier releases (spacing=, max_steps=, ...) still work, deprecated (`legacy_config`).
    """
    grid, rules = legacy_config(Grid, grid, legacy), legacy_config(Rules, rules, legacy)
    refuse_unknown(legacy, "catchment_area")
    spacing, heading, clearance, first_move = grid.spacing, grid.heading, grid.clearance, rules.first_move
    key = jax.random.PRNGKey(0) if key is None else key
    masks = np.asarray(env.valid, bool)[None, :] if masks is None else np.asarray(masks, bool)
    # input preparation on the host (NumPy): eager device ops would compile once per shape; the grid's
    # programs (headings, grid mask, errors) run on it padded to a shape bucket (`batching.bucket`), so
    # grids of many sizes share them (a cell's heading and mask depend only on its index and position)
    points = grid_points(env.arena, spacing)
    n_cells = points.shape[0]
    padded, headings, included = bucketed_grid(env, points, key, heading, clearance)
    size = padded.shape[0]
    counted = catchment_counted(env.arena, points, included, first_move, sensor.d)
    cells = np.flatnonzero(included)  # which cells are released
    if cells.size == 0:
        raise InputError("spacing", spacing, "leaves no grid point clear of the landmarks (r + clearance) but home")
    if not counted.any():
        raise InputError(
            "d",
            float(np.max(np.asarray(sensor.d))),
            "leaves no grid point at least d from every wall "
            '(the catchment under first_move "release" counts only those)',
        )
    n_masks, n_inc = masks.shape[0], cells.size
    trial_cell = np.tile(cells, n_masks).astype(np.int32)
    trial_mask = np.repeat(np.arange(n_masks, dtype=np.int32), n_inc)
    trials = run_trials(
        env,
        points[trial_cell],
        headings[trial_cell],
        trial_cell,
        trial_mask,
        masks,
        key,
        sensor,
        method,
        rules,
        progress=progress,
    )

    def per_cell(values, fill, width=n_cells):  # NumPy (M, width, ...): the trials' values on the grid
        values = np.asarray(values)
        full = np.full((n_masks, width) + values.shape[1:], fill, values.dtype)
        full[:, cells] = values.reshape((n_masks, n_inc) + values.shape[1:])
        return full

    put = jax.device_put  # host to device without an eager op (no compile per shape)
    direction = per_cell(trials.first_direction, np.nan, size)  # the vector map under each mask, padded
    valid = per_cell(trials.first_valid, False, size)
    error = mask_errors(direction, valid, padded, env.home)[:, :n_cells]
    outcome = np.where((counted | ~included)[None, :], per_cell(trials.outcome, EXCLUDED), NEAR_WALL)
    direction, valid = direction[:, :n_cells], valid[:, :n_cells]
    return Catchment(
        points=jax.device_put(points),
        included=jax.device_put(included),
        counted=jax.device_put(counted),
        heading=jax.device_put(headings),
        visible=jax.device_put(masks),
        outcome=put(outcome),
        steps=put(per_cell(trials.steps, 0)),
        end=put(per_cell(trials.end, np.nan)),
        invalid_steps=put(per_cell(trials.invalid_steps, 0)),
        direction=put(direction),
        valid=put(valid),
        error_deg=put(error),
        contact=put(per_cell(trials.contact, NO_CONTACT)),
        contact_end=put(per_cell(trials.contact_end, np.nan)),
        contact_invalid=put(per_cell(trials.contact_invalid, 0)),
        hidden=tuple(tuple(int(i) for i in h) for h in hidden),
        first_move=first_move,
        collisions=rules.collisions,
        grid=grid,
    )


def bucketed_grid(env: Env, points, key: Array, heading: float | None, clearance: Real) -> tuple:
    """(padded points, headings, included) of a grid: the points padded to a shape bucket
    (`batching.bucket`), each point's release heading (fixed, or random from `key` as `maps.random_headings`)
    and whether it is clear of the landmarks, computed on the padded grid so that grids of many sizes share
    one program (a point's heading and flag depend only on its index and position); the last two unpadded."""
    points = np.asarray(points, np.float32)
    n = points.shape[0]
    size = bucket(n, max(n, TRIAL_BLOCK))
    padded = pad_rows(points, size)
    headings = np.asarray(random_headings(key, size) if heading is None else np.full(size, heading, np.float32))
    return padded, headings[:n], np.asarray(grid_included(env, padded, clearance))[:n]


def under_release(result: Outcomes, arena, d) -> Outcomes:
    """A rollout result under first_move "homing" restated under "release" (the default), for a method
    that reads only the current view: such a method turns at once under either rule (docs/model.md
    §5), so the trials are the same. In a catchment only the cells that count change
    (`catchment_counted`; the others become NEAR_WALL); in a success rate every trial counts under
    either rule. The caller vouches for the method; `d` is the step distance."""
    if result.first_move != "homing":  # type: ignore[attr-defined]
        raise InputError("first_move", result.first_move, 'must be "homing" (the run to restate)')  # type: ignore[attr-defined]
    if not isinstance(result, Catchment):
        return dataclasses.replace(result, first_move="release")
    included = np.asarray(result.included)
    counted = catchment_counted(arena, np.asarray(result.points), included, "release", d)
    # NumPy, then one transfer: an eager `jnp.where` compiled a program per grid and mask count (2-3 s of a
    # cold `reproduce --quick`)
    outcome = np.where((counted | ~included)[None, :], np.asarray(result.outcome), NEAR_WALL)
    return dataclasses.replace(
        result, counted=jax.device_put(counted), outcome=jax.device_put(outcome), first_move="release"
    )


def mask_errors(direction: np.ndarray, valid: np.ndarray, points: np.ndarray, home) -> np.ndarray:
    """`angular_error_deg` of (M, P) first directions at the (P, 2) padded grid points, M > 1 padded to
    MASK_ROWS rows (the rollouts' own padding): one compiled program per grid bucket, not per mask count."""
    rows = direction.shape[0]
    size = rows if rows == 1 else MASK_ROWS
    return np.asarray(angular_error_deg(pad_rows(direction, size), pad_rows(valid, size), points[None], home))[:rows]


def catchment_summary(result: Catchment) -> dict:
    """Headline numbers: catchment % and error point rates per mask, and their mean, min and max (Tables 5.1-5.4)."""
    pct = result.catchment_pct()
    inc = np.asarray(result.included)
    counted = np.asarray(result.counted)
    outcome = np.asarray(result.outcome)[:, counted]
    steps = np.asarray(result.steps)[:, counted]
    per_mask = []
    for m, hidden in enumerate(result.hidden):  # M <= 20 rows of post-processing
        rates = error_point_rates(np.asarray(result.error_deg)[m], inc)
        ok = outcome[m] == SUCCESS
        per_mask.append(
            {
                "hidden": list(hidden),
                "catchment_pct": float(pct[m]),
                **rates,
                "invalid_pct": 100.0 * float((~np.asarray(result.valid)[m][inc]).mean()),
                "mean_steps_success": float(steps[m][ok].mean()) if ok.any() else float("nan"),
                **{f"{name}_count": int((outcome[m] == code).sum()) for code, name in enumerate(OUTCOMES)},
            }
        )

    def spread(field):
        v = np.array([row[field] for row in per_mask])
        return {"mean": float(v.mean()), "min": float(v.min()), "max": float(v.max())}

    return {
        "rules": result.rules,
        "points": int(inc.sum()),
        "catchment_points": int(counted.sum()),
        "masks": len(per_mask),
        "catchment_pct": spread("catchment_pct"),
        **{m.name: spread(m.name) for m in RATES},  # gt45_pct, gt90_pct
        "per_mask": per_mask,
    }


def catchment_columns(res: Catchment, with_hidden: bool = False) -> dict[str, object]:
    """Per grid point and mask: x, y, heading_deg, success (1/0; NaN where the point does not count), counted,
    steps, outcome, end_x, end_y, invalid_steps, direction_deg, error_deg, valid, the rules, and (`with_hidden`)
    the hidden landmarks of the mask ("0 2")."""
    inc, counted = np.asarray(res.included), np.asarray(res.counted)
    n_masks = np.asarray(res.outcome).shape[0]
    pts = np.tile(np.asarray(res.points)[inc], (n_masks, 1))
    per = lambda a: np.asarray(a)[:, inc].reshape(-1)  # noqa: E731
    columns: dict[str, object] = {
        "x": pts[:, 0],
        "y": pts[:, 1],
        "heading_deg": np.tile(np.degrees(np.asarray(res.heading)[inc]), n_masks),
        # NaN where the point does not count (near a wall under first_move "release"): `df.success.mean()` is the
        # catchment, as pandas skips NaN; `counted` says which rows count (issue 53: 70.5 % read for 98.46 %)
        "success": np.where(per(np.broadcast_to(counted, np.asarray(res.success).shape)), per(res.success), np.nan),
        "counted": per(np.broadcast_to(counted, np.asarray(res.success).shape)),
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
