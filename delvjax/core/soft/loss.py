"""The soft homing field and homing loss (docs/differentiable.md "Homing loss").

    loss = mean over the grid points x of 1 - cos(angle between H(x) and home - x),

H the soft homing vector (world frame) at x from the vector map's unit move (same keys, poses
and noise draws as `maps.vector_map`); a point where the method gives no direction counts 2
(an error of 180 degrees; a partly defined direction, validity v in (0, 1), counts
v (1 - cos) + 2 (1 - v)). Each grid point weighs `soft_included`: docs/model.md §5's rule
(farther than r + clearance from every landmark, not home) with edges EDGE_CM wide, so a
landmark moving over a grid point changes the loss continuously (docs/differentiable.md "A
continuous loss"). Noise enters pathwise: each sigma multiplies a fixed standard normal draw.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import rotate, safe_norm
from ..kernel import map_poses
from ..maps import stream_keys
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensor import Sensor
from ..types import PerPoint, Points, Real
from .methods import soft_direction
from .sensing import EDGE_CM, soft_home, soft_observe


def soft_field(
    env: Env,
    points: Array,
    headings: Array,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    tau: Array,
    sharpness: Array,
    visible: Array | None = None,
) -> tuple[Array, Array]:
    """Soft homing vectors in the world frame (P, 2) and validity (P,) at `points` (the vector map's
    unit moves ending there with `headings`, streams of `key`); `visible` (L,) the landmarks the
    current views see (occlusion; the home record sees all)."""
    k_home, k_views, _ = stream_keys(key)
    home = soft_home(env, k_home, sensor, sharpness)
    visible = jnp.ones(env.landmarks.shape[0], bool) if visible is None else visible

    def one(point, heading, index):
        poses = map_poses(point, heading, k_views, index, sensor)
        view = soft_observe(env, visible, poses, sensor, sharpness)
        vec, _, valid = soft_direction(method, home, view, tau)
        return rotate(vec, poses.heading_end), valid

    return jax.vmap(one)(points, headings, jnp.arange(points.shape[0]))


def soft_included(env: Env, points: Points, clearance: Real, edge: Real = EDGE_CM) -> PerPoint:
    """Weight of each grid point in [0, 1], (P,): prod over valid landmarks of
    sigmoid((|x - c_l| - r_l - clearance) / edge), times 1 - exp(-|x - home|^2 / edge^2)."""
    dist = safe_norm(points[:, None, :] - env.landmarks[None, :, :2])
    clear = jax.nn.sigmoid((dist - env.landmarks[None, :, 2] - clearance) / edge)
    away = 1.0 - jnp.exp(-jnp.sum((points - env.home) ** 2, axis=-1) / edge**2)
    return jnp.prod(jnp.where(env.valid[None, :], clear, 1.0), axis=1) * away


def alignment_loss(vectors: Array, valid: Array, points: Array, home: Array) -> Array:
    """Per point 1 - cos(angle between the vector and home - x), blended towards 2 as the validity
    `valid` (bool, or in [0, 1]) falls, (P,)."""
    to_home = home - points
    cos = jnp.sum(vectors * to_home, axis=-1) / jnp.maximum(safe_norm(vectors) * safe_norm(to_home), 1e-12)
    return jnp.where(valid > 0, valid * (1.0 - cos), 0.0) + (1.0 - valid) * 2.0


def soft_loss(
    env: Env,
    points: Array,
    included: Array,
    headings: Array,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    tau: Array,
    sharpness: Array,
    visible: Array | None = None,
) -> Array:
    """Mean `alignment_loss` of the soft field over the grid points weighted by `included` (bool or
    `soft_included`'s weights; lower is better)."""
    vec, valid = soft_field(env, points, headings, key, sensor, method, tau, sharpness, visible)
    loss = alignment_loss(vec, valid, points, env.home)
    included = jnp.asarray(included, jnp.float32)
    return jnp.sum(included * loss) / jnp.maximum(jnp.sum(included), 1e-6)
