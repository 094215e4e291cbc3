"""Many rollout configurations ("cells") of one shape as one program: catchment and success-rate
sweeps (docs/sweeps.md "Rollout sweeps").

As `core.cells.map_cells` does for vector maps, cells that share every static field are stacked
along a leading axis and run one after the other inside one compiled program (`lax.map`). Each
cell's trials run through the lane scheduler of `catchment_area` / `success_rate_trials`
(`lanes.run_block`, the same per-trial program), so a cell's outcomes are those of the single
run with the same options, and do not depend on which cells share its chunk or device.
"""

from __future__ import annotations

from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..maps import random_headings, stream_keys
from ..metrics import angular_error_deg, over_edges
from ..sensing import record_home
from .lanes import run_block
from .release import release_points
from .rules import ARENA, LANDMARK, NO_CONTACT, SUCCESS, TIMEOUT, rollout_keys
from .step import Rollout


class RolloutCell(eqx.Module):
    """One cell's traced setup (a sweep stacks C of them): the scene, method, sensor and seed key,
    the visibility masks (M, L) of which the first `n_masks` are used (cells with other occlusion
    counts share the program), the success radius and the two rules as flags."""

    env: object
    method: object
    sensor: object
    key: ArrayLike
    masks: ArrayLike
    n_masks: ArrayLike
    radius: ArrayLike
    homing_first: ArrayLike
    collide: ArrayLike


class CatchmentSums(eqx.Module):
    """Per-cell counts and sums, (C,) each: released grid points (per mask), trials (points x masks),
    the grid points and trials that count in the catchment (`rules.catchment_counted`: under first_move "release"
    grid points at least d from every wall), their successes in total and under the worst and best
    mask, the successes that never touched a landmark (those that also succeed under collisions "fail":
    `rules.under_collisions`), failures by outcome, moves of the successful trials, and the first directions'
    (the vector map under each mask, every released point) invalid count, errors > 45 and > 90 degrees
    (`metrics.over_edges`), sum and
    sum of squares of the errors (degrees; invalid = 180)."""

    points: Array
    trials: Array
    counted_points: Array
    counted: Array
    successes: Array
    successes_untouched: Array
    success_min: Array
    success_max: Array
    timeout: Array
    landmark: Array
    arena: Array
    steps_success: Array
    invalid: Array
    gt45: Array
    gt90: Array
    error_sum: Array
    error_sq_sum: Array


class SuccessSums(eqx.Module):
    """Per-cell, per-distance counts, (C, D) each: trials placed (over every mask) and successes."""

    placed: Array
    successes: Array


def _trials(cell: RolloutCell, starts, headings, key_index, mask_index, n_valid, max_steps: ArrayLike, lanes: int):
    """`run_trials`' block program for one cell's trials (the first `n_valid` are run)."""
    k_home, k_roll, _ = rollout_keys(cell.key)
    _, k_views, _ = stream_keys(cell.key)
    rollout = Rollout(
        env=cell.env,
        home=record_home(cell.env, k_home, cell.sensor),
        method=cell.method,
        sensor=cell.sensor,
        key_index=key_index,
        mask_index=mask_index,
        masks=cell.masks,
        k_roll=k_roll,
        k_views=k_views,
        radius=cell.radius,
        max_steps=max_steps,
        homing_first=cell.homing_first,
        collide=cell.collide,
    )
    return run_block(rollout, starts, headings, n_valid, lanes)


def _grid_trials(cell: RolloutCell, points: Array, inc: Array, max_steps: ArrayLike, lanes: int):
    """One cell's catchment trials: every included point of `points` under each of its masks (included points
    first, in grid order, mask after mask), random release headings per point from the cell's key. Returns
    (results, run, point index, mask index, trials run) per trial slot."""
    n_points = points.shape[0]
    rows = cell.masks.shape[0]
    n_inc = jnp.sum(inc).astype(jnp.int32)
    order = jnp.argsort(~inc, stable=True).astype(jnp.int32)  # included points first, in grid order
    t = jnp.arange(rows * n_points, dtype=jnp.int32)
    mask = t // jnp.maximum(n_inc, 1)
    point = order[t % jnp.maximum(n_inc, 1)]
    n_valid = cell.n_masks * n_inc
    headings = random_headings(cell.key, n_points)
    res = _trials(cell, points[point], headings[point], point, mask, n_valid, max_steps, lanes)
    return res, t < n_valid, point, mask, n_valid


@partial(jax.jit, static_argnames=("lanes",))
def catchment_cells(
    cells: RolloutCell, points: Array, included: Array, counted: Array, max_steps: ArrayLike, lanes: int
) -> CatchmentSums:
    """Catchment sums of C stacked cells (`catchment_area`'s trials: every included grid point of
    `points` (P, 2) under every mask, random release headings per point from each cell's key).
    `included`, `counted`: (C, P)."""

    def one(args):
        cell, inc, cnt = args
        rows = cell.masks.shape[0]
        res, run, point, mask, n_valid = _grid_trials(cell, points, inc, max_steps, lanes)
        err = angular_error_deg(res.first_dir, res.first_valid, points[point], cell.env.home)
        counts = run & cnt[point]
        ok = counts & (res.outcome == SUCCESS)
        per_mask = jax.ops.segment_sum(ok.astype(jnp.int32), jnp.where(run, mask, rows), rows + 1)[:rows]
        used = jnp.arange(rows) < cell.n_masks
        count = lambda m: jnp.sum(m & counts).astype(jnp.int32)  # noqa: E731
        e = jnp.where(run, err, 0.0)
        n_cnt = jnp.sum(inc & cnt).astype(jnp.int32)
        gt45, gt90 = over_edges(err)
        return CatchmentSums(
            points=jnp.sum(inc).astype(jnp.int32),
            trials=n_valid,
            counted_points=n_cnt,
            counted=cell.n_masks * n_cnt,
            successes=jnp.sum(per_mask),
            successes_untouched=jnp.sum(ok & (res.contact == NO_CONTACT)).astype(jnp.int32),
            success_min=jnp.min(jnp.where(used, per_mask, n_cnt)),
            success_max=jnp.max(jnp.where(used, per_mask, 0)),
            timeout=count(res.outcome == TIMEOUT),
            landmark=count(res.outcome == LANDMARK),
            arena=count(res.outcome == ARENA),
            steps_success=jnp.sum(jnp.where(ok, res.steps, 0)),
            invalid=jnp.sum(~res.first_valid & run).astype(jnp.int32),
            gt45=jnp.sum(gt45 & run).astype(jnp.int32),
            gt90=jnp.sum(gt90 & run).astype(jnp.int32),
            error_sum=jnp.sum(e),
            error_sq_sum=jnp.sum(e * e),
        )

    return jax.lax.map(one, (cells, included, counted))


@partial(jax.jit, static_argnames=("trials", "lanes"))
def success_cells(
    cells: RolloutCell, distances: Array, clearance: Array, trials: int, max_steps: ArrayLike, lanes: int
) -> SuccessSums:
    """Success-rate sums of C stacked cells: `success_rate_trials`' `trials` release points per
    distance (D,), each run under every mask of the cell (common random numbers across masks)."""
    n_bins = distances.shape[0]

    def one(cell):
        _, _, k_start = rollout_keys(cell.key)
        starts, heads, placed = jax.vmap(
            lambda b, r: release_points(cell.env, jax.random.fold_in(k_start, b), trials, r, clearance)
        )(jnp.arange(n_bins), distances)
        rows, n_items = cell.masks.shape[0], n_bins * trials
        t = jnp.arange(rows * n_items, dtype=jnp.int32)
        item = t % n_items
        n_valid = cell.n_masks * n_items
        res = _trials(
            cell,
            starts.reshape(n_items, 2)[item],
            heads.reshape(n_items)[item],
            item,
            t // n_items,
            n_valid,
            max_steps,
            lanes,
        )
        placed = placed.reshape(n_items)[item] & (t < n_valid)
        ok = placed & (res.outcome == SUCCESS)
        bins = item // trials
        return SuccessSums(
            placed=jax.ops.segment_sum(placed.astype(jnp.int32), bins, n_bins),
            successes=jax.ops.segment_sum(ok.astype(jnp.int32), bins, n_bins),
        )

    return jax.lax.map(one, cells)


@partial(jax.jit, static_argnames=("lanes",))
def catchment_cells_points(
    cells: RolloutCell, points: Array, included: Array, max_steps: ArrayLike, lanes: int
) -> tuple[Array, Array]:
    """Per-point outcomes of C stacked cells, the trials of `catchment_cells` (the same trials, outcome for
    outcome): (successes, untouched), (C, P) int32 each, the successful trials of each grid point summed over
    the cell's masks, and those of them that never touched a landmark (`rules.under_collisions`); 0 at a point
    not included. For numbers a sum cannot give (failures inside and outside the landmarks' hull)."""
    n_points = points.shape[0]

    def one(args):
        cell, inc = args
        res, run, point, _, _ = _grid_trials(cell, points, inc, max_steps, lanes)
        ok = run & (res.outcome == SUCCESS)
        per_point = lambda m: jax.ops.segment_sum(m.astype(jnp.int32), point, n_points)  # noqa: E731
        return per_point(ok), per_point(ok & (res.contact == NO_CONTACT))

    return jax.lax.map(one, (cells, included))
