"""Python API of the rollouts (docs/model.md §5): catchment, success rate, trajectories; mirrors
the CLI (same names, same validation before any work)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import jax.numpy as jnp
import numpy as np

from ..core.checks import positive_int
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.maps import CLEARANCE, SPACING
from ..core.methods import HomingMethod
from ..core.rollouts import (
    DEFAULT_DISTANCES,
    DEFAULT_FIRST_MOVE,
    HOME_RADIUS,
    MAX_STEPS,
    N_STARTS,
    TRIALS_PER_DISTANCE,
    Catchment,
    Grid,
    Rules,
    SuccessRate,
    Trajectories,
    catchment_area,
    release_points,
    rollout_keys,
    success_rate_trials,
    trajectory_trials,
)
from ..core.scene import Env
from ..options._limits import MAX_POINTS, check_moves, check_size
from ._progress import Progress
from ._rollout_setup import _check_starts, _distances, _masks, configs, rollout_setup
from ._vector_map import Indices, PointList, Values, check_grid, visible_mask

# the positional order of success_rate's and trajectories' later arguments before they were keyword-only
OLD_SHARED = ("heading_deg", "seed", "hidden", "max_steps", "home_radius", "clearance", "lanes", "first_move")
OLD_SHARED += ("collisions", "program", "announce", "max_points", "grid", "rules", "progress")


@keywords_after(
    2,
    (
        "spacing",
        "heading_deg",
        "seed",
        "occlude",
        "hidden",
        "max_steps",
        "home_radius",
        "clearance",
        "lanes",
        "first_move",
        "collisions",
        "program",
        "announce",
        "max_points",
        "progress",
        "grid",
        "rules",
    ),
)
def catchment(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    grid: Grid | None = None,
    rules: Rules | None = None,
    seed: int = 0,
    occlude: int | None = None,
    hidden: Indices | None = None,
    method_set: Sequence[str] | None = None,
    max_points: int = MAX_POINTS,
    progress: Progress | Callable[[int, int], None] | None = None,
    **options,
) -> Catchment:
    """Catchment area of `method` (Figs 4.5, 5.5; Tables 5.1-5.4): a rollout from every point of `grid`.

    `grid`: a `Grid` (spacing, clearance, heading_deg; default `Grid()`): with no fixed heading each
    point's release heading is random from `seed` (the headings of `vector_map` with the same seed).
    `rules`: a `Rules` (max_steps, home_radius, first_move "release" (thesis Algorithm 2) | "homing",
    collisions "ignore" | "fail", lanes; default `Rules()`; docs/model.md §5). Both travel unchanged to
    `core.rollouts.catchment_area`, and the result carries its grid. `occlude=k` evaluates every choice
    of k hidden landmarks (C(N, k) masks, one program; the home record sees all); `hidden` names one
    choice. `options`: the method, sensor and noise settings of `vector_map` (or `sensor=Sensor(...)`,
    `noise=Noise(...)`) plus motion_heading_noise_deg and motion_step_noise. `method_set`: registry names
    compiled into one rollout program with this one (`options.method_set`). More than
    `max_points` trials (grid points x masks) are refused with an estimate (`options._limits`).
    `progress`: a `Progress` (evaluate/_progress.py): `start(None)` once every option is valid, just
    before the work (the CLI prints its line there, so an error stays one line), then `progress(done,
    total)` after each block of trials (a plain `f(done, total)` also works).
    The flat keywords of earlier releases (spacing=, heading_deg=, clearance=, max_steps=, home_radius=,
    lanes=, first_move=, collisions=, announce=) still work for one release, with a DeprecationWarning.
    Returns a `Catchment` (see `catchment_summary`).
    """
    grid, rules, report = configs(grid, rules, progress, options, "catchment")
    setup = rollout_setup(env, method, grid, rules, seed, method_set, options)
    masks, combos = _masks(setup.env, occlude, hidden)
    points = check_grid(setup.env, grid, max_points, copies=len(masks), what="trial")
    check_moves(len(points) * len(masks), rules.max_steps, max_points)
    report.start(None)  # the core counts the trials: the bar opens at its first report
    env, module, sensor, key = setup
    return catchment_area(env, module, sensor, grid, rules, key=key, masks=masks, hidden=combos, progress=report)


@keywords_after(2, ("distances", "trials", *OLD_SHARED))
def success_rate(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    distances: Values = DEFAULT_DISTANCES,
    trials: int = TRIALS_PER_DISTANCE,
    grid: Grid | None = None,
    rules: Rules | None = None,
    seed: int = 0,
    hidden: Indices | None = None,
    method_set: Sequence[str] | None = None,
    max_points: int = MAX_POINTS,
    progress: Progress | None = None,
    **options,
) -> SuccessRate:
    """Success rate vs release distance (Figs 4.10b, 5.7b): `trials` rollouts per distance from home.

    Each trial: a random direction from home at that distance and a random heading (seeded; fixed by
    `Grid.heading_deg` if given); a release point inside a landmark's r + `Grid.clearance` or outside
    the arena is redrawn (deterministically, up to 64 times; else the trial is not placed and not
    counted); the grid's spacing is not used. `rules`, `options`, `method_set`, `max_points` and the
    deprecated flat keywords as in `catchment`; `progress.start(None)` just before the work (one
    program: no reports of chunks).
    """
    grid, rules, report = configs(grid, rules, progress, options, "success_rate")
    env, module, sensor, key = rollout_setup(env, method, grid, rules, seed, method_set, options)
    distances, trials = _distances(env, distances, trials, max_points)
    check_moves(len(distances) * trials, rules.max_steps, max_points)
    visible = visible_mask(env, hidden)
    report.start(None)
    return success_rate_trials(env, module, sensor, distances, trials, grid, rules, key=key, visible=visible)


@keywords_after(2, ("starts", "n_starts", *OLD_SHARED))
def trajectories(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    starts: PointList | None = None,
    n_starts: int = N_STARTS,
    grid: Grid | None = None,
    rules: Rules | None = None,
    seed: int = 0,
    hidden: Indices | None = None,
    method_set: Sequence[str] | None = None,
    max_points: int = MAX_POINTS,
    progress: Progress | None = None,
    **options,
) -> Trajectories:
    """Homing paths (Figs 4.11, 5.8) from `starts` [(x, y), ...] or `n_starts` seeded random release points.

    Random release points are uniform in the arena, at least d from the walls, farther than
    r + `Grid.clearance` + d from every landmark (so that under first_move="release" the first move,
    along the random release heading, cannot end the trial) and at least 2 * home_radius from home;
    headings are random per trial from `seed` unless `Grid.heading_deg` is given. The same seed gives
    the same release points for every method. `rules`, `options`, `method_set` and the deprecated flat
    keywords as in `catchment`, and `progress.start(None)` just before the work. Every position is
    kept: more than 100 x `max_points` of them (trials x (max_steps + 1)) are refused.
    """
    grid, rules, report = configs(grid, rules, progress, options, "trajectories")
    env, module, sensor, key = rollout_setup(env, method, grid, rules, seed, method_set, options)
    visible = visible_mask(env, hidden)
    _, _, k_start = rollout_keys(key)
    count = positive_int(n_starts, "n_starts") if starts is None else len(starts) if hasattr(starts, "__len__") else 0
    check_size(count, max_points, "starts" if starts is not None else "n_starts", count, "trial")
    max_steps = rules.max_steps
    check_size(
        count * (max_steps + 1), 100 * positive_int(max_points, "max_points"), "max_steps", max_steps, "path point"
    )
    if starts is None:
        pts, heads, placed = release_points(
            env, k_start, count, None, grid.clearance, 2.0 * rules.home_radius, sensor.d
        )
        if not bool(np.all(np.asarray(placed))):
            raise InputError("n_starts", n_starts, "could not place release points clear of landmarks")
    else:
        pts = _check_starts(env, starts)
        _, heads, _ = release_points(env, k_start, pts.shape[0], None, grid.clearance)
    if grid.heading is not None:
        heads = jnp.full(pts.shape[0], grid.heading, jnp.float32)
    report.start(None)
    return trajectory_trials(env, module, sensor, pts, heads, rules, key=key, visible=visible)


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
    method_set: Sequence[str] | None = None,
    **options,
) -> dict:
    """Validate one rollout configuration of a sweep (docs/sweeps.md) as `catchment` (kind "catchment")
    or `success_rate` (kind "success-rate", under every mask of `occlude`) validate theirs, before any
    work; release headings are random from `seed`. A sweep's axes are flat names (`spacing`,
    `max_steps`, ...): they become the `Grid` and `Rules` here. Returns the setup (env, method, sensor,
    key, masks, ...) that `core.rollouts.cells` evaluates."""
    rules = Rules(max_steps=max_steps, home_radius=home_radius, first_move=first_move, collisions=collisions)
    grid = Grid(spacing=spacing if kind == "catchment" else SPACING, clearance=clearance)
    env, module, sensor, key = rollout_setup(env, method, grid, rules, seed, method_set, options)
    masks, _ = _masks(env, occlude, None)
    if kind == "catchment":
        points = check_grid(env, grid, max_points, copies=len(masks), what="trial")
        check_moves(len(points) * len(masks), rules.max_steps, max_points)
    else:
        distances, trials = _distances(env, distances, trials, max_points, copies=len(masks))
        check_moves(len(distances) * trials * len(masks), rules.max_steps, max_points)
    return dict(
        kind=kind,
        env=env,
        method=module,
        sensor=sensor,
        key=key,
        masks=masks,
        spacing=grid.spacing if kind == "catchment" else spacing,
        clearance=grid.clearance,
        max_steps=rules.max_steps,
        home_radius=rules.home_radius,
        first_move=rules.first_move,
        collisions=rules.collisions,
        distances=tuple(distances),
        trials=trials,
    )
