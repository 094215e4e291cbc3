"""The validated setup every rollout of the Python API shares (docs/model.md §5): the config objects
(`Grid`, `Rules`, or the deprecated flat keywords they replace), the visibility masks, release
distances and start points."""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..core.checks import finite, is_traced, occlusion_count, positive, positive_int
from ..core.errors import InputError
from ..core.methods import HomingMethod
from ..core.rollouts import ARENA, LANDMARK, Grid, Rules, hidden_masks, legacy_config, occlusion_masks, position_status
from ..core.scene import Env
from ..core.sensor import Sensor
from ..options._limits import check_size
from ._progress import Progress, with_callbacks
from ._vector_map import Indices, Values, scene_request, visible_mask


class RolloutSetup(NamedTuple):
    """The validated setup every rollout shares (`rollout_setup`)."""

    env: Env
    method: HomingMethod
    sensor: Sensor
    key: Array


def configs(
    grid: Grid | None,
    rules: Rules | None,
    progress: Progress | Callable[[int, int], None] | None,
    options: dict,
    call: str,
) -> tuple[Grid, Rules, Progress]:
    """(`Grid`, `Rules`, `Progress`) of a public rollout call `call`: the objects given, or ones built from
    the flat keywords and the `announce=` callback of earlier releases in `options` (popped, each with a
    `DeprecationWarning` that points at the caller; `core.rollouts.config.legacy_config`, `with_callbacks`)."""
    return (
        legacy_config(Grid, grid, options),
        legacy_config(Rules, rules, options),
        with_callbacks(progress, options, call),
    )


def rollout_setup(env, method, grid: Grid, rules: Rules, seed: int, method_set, options: dict) -> RolloutSetup:
    """Validate what every rollout shares before any work (`_vector_map.scene_request`: method, sensor,
    environment, seed) and the success radius against the arena (the `Grid` and `Rules` checked their
    own fields when they were built)."""
    env, module, sensor, _, key, _ = scene_request(
        env, method, grid.clearance, grid.heading_deg, seed, method_set, **options
    )
    if not is_traced(env.arena) and not is_traced(env.home):
        arena, home = np.asarray(env.arena, np.float64), np.asarray(env.home, np.float64)
        farthest = float(np.max(np.hypot(arena[[0, 2]][:, None] - home[0], arena[[1, 3]][None, :] - home[1])))
        if rules.home_radius >= farthest:  # every release point would count as home: 100 % without a move
            raise InputError(
                "home_radius",
                rules.home_radius,
                f"must be < {farthest:.4g} cm, home's distance to the arena's farthest corner",
            )
    return RolloutSetup(env, module, sensor, key)


def _masks(env: Env, occlude: int | None, hidden: Indices | None) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """The visibility masks (M, L) of `occlude=k` (every choice of k hidden landmarks) or of `hidden`."""
    if occlude is not None and hidden is not None and len(hidden) > 0:
        raise InputError("occlude", occlude, "cannot be combined with hidden")
    if occlude is not None:
        return occlusion_masks(env, occlusion_count(occlude, env.n_landmarks))
    visible_mask(env, hidden)  # validates the indices
    return hidden_masks(env, hidden)


def _distances(env: Env, distances: Values, trials: int, max_points: int, copies: int = 1) -> tuple[list[float], int]:
    """Validated release distances (each < the farthest arena corner from home) and trials per distance."""
    trials = positive_int(trials, "trials")
    if isinstance(distances, (str, bytes)) or not hasattr(distances, "__len__") or len(distances) == 0:
        raise InputError("distances", distances, "must be a non-empty list of distances in cm")
    distances = [positive(v, "distances") for v in distances]
    repeated = [v for i, v in enumerate(distances) if v in distances[:i]]
    if repeated:  # two bins of one distance: the table's (distance, trial) keys would repeat
        raise InputError("distances", repeated[0], "is given twice: each distance is one bin of the table")
    check_size(len(distances) * trials * copies, max_points, "trials", trials, "trial")
    corners = np.asarray(env.arena, float)[[[0, 1], [2, 1], [2, 3], [0, 3]]]
    reach = float(np.max(np.hypot(*(corners - np.asarray(env.home, float)).T)))
    for v in distances:
        if v >= reach:
            raise InputError(
                "distances", v, f"must be < {reach:.0f} cm: no release point that far from home lies in the arena"
            )
    return distances, trials


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
