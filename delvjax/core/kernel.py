"""The per-point kernel shared by vector maps, rollouts and sensitivity (docs/model.md §3.3, §5).

One evaluation of a homing method at one pose: sense the unit move that ended there (only what
the method reads is rendered) and turn the method's agent-frame answer into a world direction.
Everything here is written for ONE point; callers `vmap` it.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from .geometry import wrap
from .methods.base import HomingMethod
from .scene import Env
from .sensing import MovePoses, UnitMove, observe_poses, unit_move_poses
from .sensor import Sensor
from .types import Direction


def sense(env: Env, visible: Array, poses: MovePoses, method: HomingMethod, sensor: Sensor) -> UnitMove:
    """The unit move `poses` as the agent senses it, rendering only what `method` reads."""
    return observe_poses(
        env, visible, poses, sensor, method.reads_start_view(), method.reads_gray(sensor.channel), method.reads_image()
    )


def world_direction(method: HomingMethod, home: UnitMove, view: UnitMove, heading_end: Array) -> Direction:
    """The method's homing direction in the world frame (rad; NaN where invalid) and its validity."""
    angle, valid = method(home, view)
    return jnp.where(valid, wrap(heading_end + angle), jnp.nan), valid


def direction_from(
    env: Env, visible: Array, poses: MovePoses, home: UnitMove, method: HomingMethod, sensor: Sensor
) -> Direction:
    """Sense `poses` and home: (world direction, valid)."""
    return world_direction(method, home, sense(env, visible, poses, method, sensor), poses.heading_end)


def map_poses(point: Array, heading: Array, key_views: Array, index: ArrayLike, sensor: Sensor) -> MovePoses:
    """The vector map's unit move at grid point `index` (docs/model.md §3.3): it ends at `point`
    with release heading `heading`, drawn from the point's own stream fold_in(key_views, index)."""
    return unit_move_poses(point, heading, jax.random.fold_in(key_views, index), sensor, end_at=point)
