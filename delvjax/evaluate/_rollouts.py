"""Python API of the rollouts (docs/model.md §5): catchment, success rate, trajectories; mirrors
the CLI (same names, same validation before any work)."""

from __future__ import annotations

from pathlib import Path
from collections.abc import Callable, Sequence
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ._vector_map import check_grid, scene_request, visible_mask
from ..core.errors import InputError
from ._config import GRID_DEFAULTS, RULES_DEFAULTS, Grid, Rules, unpack
from ..core.maps import CLEARANCE, SPACING
from ..core.methods import HomingMethod
from ..core.rollouts import (ARENA, DEFAULT_DISTANCES, DEFAULT_FIRST_MOVE, DEFAULT_LANES, HOME_RADIUS, LANDMARK, MAX_STEPS, N_STARTS, TRIALS_PER_DISTANCE, Catchment, SuccessRate, Trajectories, catchment_area, check_rules, hidden_masks, occlusion_masks, position_status, release_points, rollout_keys, success_rate_trials, trajectory_trials)
from ..core.scene import Env
from ..options._limits import MAX_POINTS, check_size
from ..options._settings import finite, occlusion_count, positive, positive_int



class RolloutSetup(NamedTuple):
    """The validated keywords every rollout shares (`_rollout_options`)."""

    env: Env
    method: HomingMethod
    sensor: object
    heading: float | None
    key: Array
    max_steps: int
    home_radius: float
    lanes: int
    clearance: float
    first_move: str
    collisions: str


def _rollout_options(env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed, options,
                     first_move=DEFAULT_FIRST_MOVE, collisions="ignore", program=None, grid: Grid | None = None,
                     rules: Rules | None = None) -> RolloutSetup:
    """Validate the shared keywords before any work (`api.scene_request` plus the rollout limits and
    rules), taking the grid's clearance and heading and the rules from `grid=` and `rules=` if given."""
    clearance, heading_deg, max_steps, home_radius, first_move, collisions, lanes = _configured(
        grid, rules, clearance=clearance, heading_deg=heading_deg, max_steps=max_steps, home_radius=home_radius,
        first_move=first_move, collisions=collisions, lanes=lanes)
    check_rules(first_move, collisions)
    env, module, sensor, heading, key, clearance = scene_request(env, method, clearance, heading_deg, seed, program,
                                                                 **options)
    max_steps = positive_int(max_steps, "max_steps")
    home_radius = positive(home_radius, "home_radius")
    lanes = positive_int(lanes, "lanes")
    return RolloutSetup(env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move,
                        collisions)


def _configured(grid: Grid | None, rules: Rules | None, **given) -> tuple:
    """The values of the grid and rule keywords `given` (in their order), from `grid=` and `rules=`
    where those are given (evaluate/_config.py)."""
    values = {**unpack(grid, Grid, {k: v for k, v in given.items() if k in GRID_DEFAULTS}, GRID_DEFAULTS),
              **unpack(rules, Rules, {k: v for k, v in given.items() if k in RULES_DEFAULTS}, RULES_DEFAULTS)}
    return tuple(values[k] for k in given)


def catchment(env: str | Path | Env, method: str | HomingMethod = "delv", spacing: float = SPACING, heading_deg: float | None = None,
              seed: int = 0, occlude: int | None = None, hidden: list[int] | None = None, max_steps: int = MAX_STEPS,
              home_radius: float = HOME_RADIUS, clearance: float = CLEARANCE, lanes: int = DEFAULT_LANES, first_move: str = DEFAULT_FIRST_MOVE,
              collisions: str | None = "ignore", program: Sequence[str] | None = None, announce: Callable[[], None] | None = None,
              max_points: int = MAX_POINTS, progress: Callable[[int, int], None] | None = None,
              grid: Grid | None = None, rules: Rules | None = None,
              **options) -> Catchment:
    """Catchment area of `method` (Figs 4.5, 5.5; Tables 5.3/5.4): a rollout from every docs/model.md §5 grid point.

    heading_deg fixes the release heading; otherwise it is random per point from `seed`
    (the headings of `vector_map` with the same seed). `occlude=k` evaluates every choice of
    k hidden landmarks (C(N, k) masks, one program; the home record sees all); `hidden`
    names one choice. `options`: noise sigmas as in `vector_map` plus motion_heading_noise_deg
    and motion_step_noise, or any other `api.vector_map` option (e.g. warping's n_alpha).
    `first_move` ("release", thesis Algorithm 2, | "homing") and `collisions` ("ignore" | "fail"): the rollout
    rules of `core.rollouts.rules` (defaults: docs/model.md §5). `program`: registry names compiled into
    one rollout program with this one (`registry.program`). `announce`: called once every option is
    valid, just before the work (the CLI prints its progress line there, so an error stays one line).
    More than `max_points` trials (grid points x masks) are refused with an estimate (`limits`).
    `progress(done, total)` is called after each block of trials.
    Returns a `Catchment` (see `catchment_summary`).
    """
    (spacing,) = _configured(grid, None, spacing=spacing)
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed, options, first_move,
                         collisions, program, grid, rules))
    spacing = positive(spacing, "spacing")
    masks, combos = _masks(env, occlude, hidden)
    check_grid(env, spacing, clearance, max_points, copies=len(masks), what="trial")
    _announce(announce)
    return catchment_area(env, module, sensor, spacing=spacing, heading=heading, key=key, clearance=clearance,
                          masks=masks, hidden=combos, home_radius=home_radius, max_steps=max_steps, lanes=lanes,
                          first_move=first_move, collisions=collisions, progress=progress)


def success_rate(env: str | Path | Env, method: str | HomingMethod = "delv", distances: Sequence[float] = DEFAULT_DISTANCES,
                 trials: int = TRIALS_PER_DISTANCE, heading_deg: float | None = None, seed: int = 0, hidden: list[int] | None = None,
                 max_steps: int = MAX_STEPS, home_radius: float = HOME_RADIUS, clearance: float = CLEARANCE,
                 lanes: int = DEFAULT_LANES, first_move: str = DEFAULT_FIRST_MOVE,
                 collisions: str | None = "ignore", program: Sequence[str] | None = None,
                 announce: Callable[[], None] | None = None, max_points: int = MAX_POINTS, grid: Grid | None = None, rules: Rules | None = None,
              **options) -> SuccessRate:
    """Success rate vs release distance (Figs 4.10b, 5.7b): `trials` rollouts per distance from home.

    Each trial: a random direction from home at that distance and a random heading (seeded);
    a release point inside a landmark's r + clearance or outside the arena is redrawn
    (deterministically, up to 64 times; else the trial is not placed and not counted).
    `options`, `first_move`, `collisions`, `program`, `announce` and `max_points` as in `catchment`.
    """
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed, options, first_move,
                         collisions, program, grid, rules))
    distances, trials = _distances(env, distances, trials, max_points)
    visible = visible_mask(env, hidden)
    _announce(announce)
    return success_rate_trials(env, module, sensor, distances=distances, trials=trials, heading=heading, key=key,
                               clearance=clearance, visible=visible, home_radius=home_radius,
                               max_steps=max_steps, lanes=lanes, first_move=first_move, collisions=collisions)


def trajectories(env: str | Path | Env, method: str | HomingMethod = "delv", starts: Sequence[Sequence[float]] | None = None,
                 n_starts: int = N_STARTS, heading_deg: float | None = None, seed: int = 0, hidden: list[int] | None = None,
                 max_steps: int = MAX_STEPS, home_radius: float = HOME_RADIUS, clearance: float = CLEARANCE,
                 lanes: int = DEFAULT_LANES, first_move: str = DEFAULT_FIRST_MOVE,
                 collisions: str | None = "ignore", program: Sequence[str] | None = None,
                 announce: Callable[[], None] | None = None, max_points: int = MAX_POINTS, grid: Grid | None = None, rules: Rules | None = None,
              **options) -> Trajectories:
    """Homing paths (Figs 4.11, 5.8) from `starts` [(x, y), ...] or `n_starts` seeded random release points.

    Random release points are uniform in the arena, at least d from the walls, farther than
    r + clearance + d from every landmark (so that under first_move="release" the first move,
    along the random release heading, cannot end the trial) and at least 2 * home_radius
    from home; headings are
    random per trial from `seed` unless heading_deg is given. The same seed gives the same
    release points for every method. `options`, `first_move`, `collisions`, `program` and `announce` as in
    `catchment`. Every position is kept: more than 100 x `max_points` of them (trials x (max_steps + 1)) are refused.
    """
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed, options, first_move,
                         collisions, program, grid, rules))
    visible = visible_mask(env, hidden)
    _, _, k_start = rollout_keys(key)
    count = positive_int(n_starts, "n_starts") if starts is None else len(starts) if hasattr(starts, "__len__") else 0
    check_size(count, max_points, "starts" if starts is not None else "n_starts", count, "trial")
    check_size(count * (max_steps + 1), 100 * positive_int(max_points, "max_points"), "max_steps", max_steps,
               "path point")
    if starts is None:
        pts, heads, placed = release_points(env.arrays(), k_start, count, None, clearance, 2.0 * home_radius, sensor.d)
        if not bool(np.all(np.asarray(placed))):
            raise InputError("n_starts", n_starts, "could not place release points clear of landmarks")
    else:
        pts = _check_starts(env, starts)
        _, heads, _ = release_points(env.arrays(), k_start, pts.shape[0], None, clearance)
    if heading is not None:
        heads = jnp.full(pts.shape[0], heading, jnp.float32)
    _announce(announce)
    return trajectory_trials(env, module, sensor, pts, heads, key=key, visible=visible, home_radius=home_radius,
                             max_steps=max_steps, lanes=lanes, first_move=first_move, collisions=collisions)


def _masks(env: Env, occlude: int | None, hidden: list[int] | None) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """The visibility masks (M, L) of `occlude=k` (every choice of k hidden landmarks) or of `hidden`."""
    if occlude is not None and hidden:
        raise InputError("occlude", occlude, "cannot be combined with hidden")
    if occlude is not None:
        return occlusion_masks(env, occlusion_count(occlude, env.n_landmarks))
    visible_mask(env, hidden)  # validates the indices
    return hidden_masks(env, hidden)


def _distances(env: Env, distances: Sequence[float], trials: int, max_points: int, copies: int = 1) -> tuple[list[float], int]:
    """Validated release distances (each < the farthest arena corner from home) and trials per distance."""
    trials = positive_int(trials, "trials")
    if isinstance(distances, (str, bytes)) or not hasattr(distances, "__len__") or len(distances) == 0:
        raise InputError("distances", distances, "must be a non-empty list of distances in cm")
    distances = [positive(v, "distances") for v in distances]
    check_size(len(distances) * trials * copies, max_points, "trials", trials, "trial")
    corners = np.asarray(env.arena, float)[[[0, 1], [2, 1], [2, 3], [0, 3]]]
    reach = float(np.max(np.hypot(*(corners - np.asarray(env.home, float)).T)))
    for v in distances:
        if v >= reach:
            raise InputError("distances", v, f"must be < {reach:.0f} cm: no release point that far from home lies "
                                             "in the arena")
    return distances, trials


def rollout_request(env: str | Path | Env, kind: str = "catchment", method: str | HomingMethod = "delv",
                    spacing: float = SPACING, seed: int = 0, occlude: int | None = None, max_steps: int = MAX_STEPS,
                    home_radius: float = HOME_RADIUS, clearance: float = CLEARANCE, first_move: str = DEFAULT_FIRST_MOVE,
                    collisions: str | None = "ignore", distances: Sequence[float] = DEFAULT_DISTANCES,
                    trials: int = TRIALS_PER_DISTANCE, max_points: int = MAX_POINTS, **options) -> dict:
    """Validate one rollout configuration of a sweep (docs/sweeps.md) as `catchment` (kind "catchment")
    or `success_rate` (kind "success-rate", under every mask of `occlude`) validate theirs, before any
    work; release headings are random from `seed`. Returns the setup (env, method, sensor, key, masks,
    ...) that `core.rollouts.cells` evaluates."""
    env, module, sensor, _, key, max_steps, home_radius, _, clearance, _, _ = _rollout_options(
        env, method, max_steps, home_radius, DEFAULT_LANES, clearance, None, seed, options, first_move, collisions)
    masks, _ = _masks(env, occlude, None)
    if kind == "catchment":
        spacing = positive(spacing, "spacing")
        check_grid(env, spacing, clearance, max_points, copies=len(masks), what="trial")
    else:
        distances, trials = _distances(env, distances, trials, max_points, copies=len(masks))
    return dict(kind=kind, env=env, method=module, sensor=sensor, key=key, masks=masks, spacing=spacing,
                clearance=clearance, max_steps=max_steps, home_radius=home_radius, first_move=first_move,
                collisions=collisions, distances=tuple(distances), trials=trials)


def _announce(announce: Callable[[], None] | None) -> None:
    if announce is not None:
        announce()


def _check_starts(env: Env, starts) -> Array:
    """Release points given by the user: a non-empty list of (x, y) inside the arena, outside every landmark."""
    if isinstance(starts, (str, bytes)) or not hasattr(starts, "__len__") or len(starts) == 0:
        raise InputError("starts", starts, "must be a non-empty list of (x, y) points")
    rows = []
    for i, s in enumerate(starts):
        if not hasattr(s, "__len__") or len(s) != 2:
            raise InputError(f"starts[{i}]", s, "must be an (x, y) pair")
        rows.append([finite(v, f"starts[{i}]") for v in s])
    pts = np.asarray(rows, np.float32)
    status = np.asarray(jax.vmap(lambda p: position_status(env, p, jnp.float32(0.0)))(jnp.asarray(pts)))
    for i, code in enumerate(status):
        if code in (LANDMARK, ARENA):
            raise InputError(f"starts[{i}]", starts[i], "must lie inside the arena and outside every landmark")
    return jnp.asarray(pts)
