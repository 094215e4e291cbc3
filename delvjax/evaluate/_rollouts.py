"""Python API of the rollouts (docs/model.md §5): catchment, success rate, trajectories; mirrors
the CLI (same names, same validation before any work)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import jax.numpy as jnp
import numpy as np

from ..core.errors import InputError
from ..core.maps import CLEARANCE, SPACING
from ..core.methods import HomingMethod
from ..core.rollouts import (
    DEFAULT_DISTANCES,
    DEFAULT_FIRST_MOVE,
    DEFAULT_LANES,
    HOME_RADIUS,
    MAX_STEPS,
    N_STARTS,
    TRIALS_PER_DISTANCE,
    Catchment,
    SuccessRate,
    Trajectories,
    catchment_area,
    release_points,
    rollout_keys,
    success_rate_trials,
    trajectory_trials,
)
from ..core.scene import Env
from ..options._checks import positive, positive_int
from ..options._limits import MAX_POINTS, check_moves, check_size, grid_count
from ._config import Grid, Rules
from ._progress import Progress
from ._rollout_setup import _announce, _check_starts, _configured, _distances, _masks, _rollout_options
from ._vector_map import Indices, PointList, Values, check_grid, visible_mask


def catchment(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    spacing: float = SPACING,
    heading_deg: float | None = None,
    seed: int = 0,
    occlude: int | None = None,
    hidden: Indices | None = None,
    max_steps: int = MAX_STEPS,
    home_radius: float = HOME_RADIUS,
    clearance: float = CLEARANCE,
    lanes: int = DEFAULT_LANES,
    first_move: str = DEFAULT_FIRST_MOVE,
    collisions: str | None = "ignore",
    program: Sequence[str] | None = None,
    announce: Callable[[], None] | None = None,
    max_points: int = MAX_POINTS,
    progress: Progress | Callable[[int, int], None] | None = None,
    grid: Grid | None = None,
    rules: Rules | None = None,
    **options,
) -> Catchment:
    """Catchment area of `method` (Figs 4.5, 5.5; Tables 5.3/5.4): a rollout from every docs/model.md §5 grid point.

    heading_deg fixes the release heading; otherwise it is random per point from `seed`
    (the headings of `vector_map` with the same seed). `occlude=k` evaluates every choice of
    k hidden landmarks (C(N, k) masks, one program; the home record sees all); `hidden`
    names one choice. `options`: noise sigmas as in `vector_map` plus motion_heading_noise_deg
    and motion_step_noise, or any other `evaluate.vector_map` option (e.g. warping's n_alpha).
    `first_move` ("release", thesis Algorithm 2, | "homing") and `collisions` ("ignore" | "fail"): the rollout
    rules of `core.rollouts.rules` (defaults: docs/model.md §5). `program`: registry names compiled into
    one rollout program with this one (`options._registry.program`).
    More than `max_points` trials (grid points x masks) are refused with an estimate (`options._limits`).
    `progress`: a `Progress` (evaluate/_progress.py): `progress.start(None)` once every option is valid,
    just before the work (the CLI prints its line there, so an error stays one line), then `progress(done,
    total)` after each block of trials (a plain `f(done, total)` also works). `announce()`: the older
    form of `progress.start`, still called.
    Returns a `Catchment` (see `catchment_summary`).
    """
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(**locals())
    )
    (spacing,) = _configured(grid, None, spacing=spacing)
    spacing = positive(spacing, "spacing")
    masks, combos = _masks(env, occlude, hidden)
    check_grid(env, spacing, clearance, max_points, copies=len(masks), what="trial")
    check_moves(grid_count(env.arena, spacing) * len(masks), max_steps, max_points)
    report = _announce(announce, progress, None)  # the core counts the trials: the bar opens at its first report
    return catchment_area(
        env,
        module,
        sensor,
        spacing=spacing,
        heading=heading,
        key=key,
        clearance=clearance,
        masks=masks,
        hidden=combos,
        home_radius=home_radius,
        max_steps=max_steps,
        lanes=lanes,
        first_move=first_move,
        collisions=collisions,
        progress=report,
    )


def success_rate(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    distances: Values = DEFAULT_DISTANCES,
    trials: int = TRIALS_PER_DISTANCE,
    heading_deg: float | None = None,
    seed: int = 0,
    hidden: Indices | None = None,
    max_steps: int = MAX_STEPS,
    home_radius: float = HOME_RADIUS,
    clearance: float = CLEARANCE,
    lanes: int = DEFAULT_LANES,
    first_move: str = DEFAULT_FIRST_MOVE,
    collisions: str | None = "ignore",
    program: Sequence[str] | None = None,
    announce: Callable[[], None] | None = None,
    max_points: int = MAX_POINTS,
    grid: Grid | None = None,
    rules: Rules | None = None,
    progress: Progress | None = None,
    **options,
) -> SuccessRate:
    """Success rate vs release distance (Figs 4.10b, 5.7b): `trials` rollouts per distance from home.

    Each trial: a random direction from home at that distance and a random heading (seeded);
    a release point inside a landmark's r + clearance or outside the arena is redrawn
    (deterministically, up to 64 times; else the trial is not placed and not counted).
    `options`, `first_move`, `collisions`, `program`, `announce` and `max_points` as in `catchment`;
    `progress.start(None)` just before the work (one program: no reports of chunks).
    """
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(**locals())
    )
    distances, trials = _distances(env, distances, trials, max_points)
    check_moves(len(distances) * trials, max_steps, max_points)
    visible = visible_mask(env, hidden)
    _announce(announce, progress, None)
    return success_rate_trials(
        env,
        module,
        sensor,
        distances=distances,
        trials=trials,
        heading=heading,
        key=key,
        clearance=clearance,
        visible=visible,
        home_radius=home_radius,
        max_steps=max_steps,
        lanes=lanes,
        first_move=first_move,
        collisions=collisions,
    )


def trajectories(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    starts: PointList | None = None,
    n_starts: int = N_STARTS,
    heading_deg: float | None = None,
    seed: int = 0,
    hidden: Indices | None = None,
    max_steps: int = MAX_STEPS,
    home_radius: float = HOME_RADIUS,
    clearance: float = CLEARANCE,
    lanes: int = DEFAULT_LANES,
    first_move: str = DEFAULT_FIRST_MOVE,
    collisions: str | None = "ignore",
    program: Sequence[str] | None = None,
    announce: Callable[[], None] | None = None,
    max_points: int = MAX_POINTS,
    grid: Grid | None = None,
    rules: Rules | None = None,
    progress: Progress | None = None,
    **options,
) -> Trajectories:
    """Homing paths (Figs 4.11, 5.8) from `starts` [(x, y), ...] or `n_starts` seeded random release points.

    Random release points are uniform in the arena, at least d from the walls, farther than
    r + clearance + d from every landmark (so that under first_move="release" the first move,
    along the random release heading, cannot end the trial) and at least 2 * home_radius
    from home; headings are
    random per trial from `seed` unless heading_deg is given. The same seed gives the same
    release points for every method. `options`, `first_move`, `collisions`, `program` and `announce` as in
    `catchment`, and `progress.start(None)` just before the work. Every position is kept: more than 100 x
    `max_points` of them (trials x (max_steps + 1)) are refused.
    """
    env, module, sensor, heading, key, max_steps, home_radius, lanes, clearance, first_move, collisions = (
        _rollout_options(**locals())
    )
    visible = visible_mask(env, hidden)
    _, _, k_start = rollout_keys(key)
    count = positive_int(n_starts, "n_starts") if starts is None else len(starts) if hasattr(starts, "__len__") else 0
    check_size(count, max_points, "starts" if starts is not None else "n_starts", count, "trial")
    check_size(
        count * (max_steps + 1), 100 * positive_int(max_points, "max_points"), "max_steps", max_steps, "path point"
    )
    if starts is None:
        pts, heads, placed = release_points(env, k_start, count, None, clearance, 2.0 * home_radius, sensor.d)
        if not bool(np.all(np.asarray(placed))):
            raise InputError("n_starts", n_starts, "could not place release points clear of landmarks")
    else:
        pts = _check_starts(env, starts)
        _, heads, _ = release_points(env, k_start, pts.shape[0], None, clearance)
    if heading is not None:
        heads = jnp.full(pts.shape[0], heading, jnp.float32)
    _announce(announce, progress, None)
    return trajectory_trials(
        env,
        module,
        sensor,
        pts,
        heads,
        key=key,
        visible=visible,
        home_radius=home_radius,
        max_steps=max_steps,
        lanes=lanes,
        first_move=first_move,
        collisions=collisions,
    )


def rollout_request(
    env: str | Path | Env,
    kind: str = "catchment",
    method: str | HomingMethod = "delv",
    spacing: float = SPACING,
    seed: int = 0,
    occlude: int | None = None,
    max_steps: int = MAX_STEPS,
    home_radius: float = HOME_RADIUS,
    clearance: float = CLEARANCE,
    first_move: str = DEFAULT_FIRST_MOVE,
    collisions: str | None = "ignore",
    distances: Values = DEFAULT_DISTANCES,
    trials: int = TRIALS_PER_DISTANCE,
    max_points: int = MAX_POINTS,
    program: Sequence[str] | None = None,
    **options,
) -> dict:
    """Validate one rollout configuration of a sweep (docs/sweeps.md) as `catchment` (kind "catchment")
    or `success_rate` (kind "success-rate", under every mask of `occlude`) validate theirs, before any
    work; release headings are random from `seed`. Returns the setup (env, method, sensor, key, masks,
    ...) that `core.rollouts.cells` evaluates."""
    env, module, sensor, _, key, max_steps, home_radius, _, clearance, _, _ = _rollout_options(**locals())
    masks, _ = _masks(env, occlude, None)
    if kind == "catchment":
        spacing = positive(spacing, "spacing")
        check_grid(env, spacing, clearance, max_points, copies=len(masks), what="trial")
        check_moves(grid_count(env.arena, spacing) * len(masks), max_steps, max_points)
    else:
        distances, trials = _distances(env, distances, trials, max_points, copies=len(masks))
        check_moves(len(distances) * trials * len(masks), max_steps, max_points)
    return dict(
        kind=kind,
        env=env,
        method=module,
        sensor=sensor,
        key=key,
        masks=masks,
        spacing=spacing,
        clearance=clearance,
        max_steps=max_steps,
        home_radius=home_radius,
        first_move=first_move,
        collisions=collisions,
        distances=tuple(distances),
        trials=trials,
    )
