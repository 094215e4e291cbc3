"""The soft homing field and homing loss (docs/differentiable.md "Homing loss").

    loss = mean over the grid points x of 1 - cos(angle between H(x) and home - x),

H the soft homing vector (world frame) at x from the vector map's unit move (same keys, poses
and noise draws as `maps.vector_map`); a point where the method gives no direction counts 2
(an error of 180 degrees). The grid points themselves (which cells are clear of the landmarks)
are held fixed. Noise enters pathwise: each sigma multiplies a fixed standard normal draw.
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
from .methods import soft_direction
from .sensing import soft_home, soft_observe


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


def alignment_loss(vectors: Array, valid: Array, points: Array, home: Array) -> Array:
    """Per point 1 - cos(angle between the vector and home - x); 2 where invalid, (P,)."""
    to_home = home - points
    cos = jnp.sum(vectors * to_home, axis=-1) / jnp.maximum(safe_norm(vectors) * safe_norm(to_home), 1e-12)
    return jnp.where(valid, 1.0 - cos, 2.0)


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
    """Mean `alignment_loss` of the soft field over the included grid points (lower is better)."""
    vec, valid = soft_field(env, points, headings, key, sensor, method, tau, sharpness, visible)
    loss = alignment_loss(vec, valid, points, env.home)
    return jnp.sum(jnp.where(included, loss, 0.0)) / jnp.maximum(jnp.sum(included), 1)
