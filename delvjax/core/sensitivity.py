"""Differentiable sensitivity studies with `jax.grad` (beyond the thesis; cf. its §3.2.2 remark
that bearing and odometry errors drive the distance estimates of Eq 3.2).

For a fixed scene and pose, the homing direction is a smooth function of the current
blob bearings and of the believed step d_hat once the discrete choices (blob partners,
cyclic shift, heading hypothesis) are fixed; `jax.grad` differentiates through exactly
that branch (argmin carries no gradient). The first-order direction error caused by
independent bearing noise of std sigma is then `gain * sigma` with
`gain = ||d direction / d bearings||_2`.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from .kernel import map_poses, sense
from .maps import stream_keys
from .methods.base import HomingMethod
from .scene import Env
from .sensing import UnitMove, record_home
from .sensor import Sensor
from .types import PerPoint, PerPointFlag, PointBlobFlags, PointBlobs, Points


def _perturbed(view: UnitMove, eps: Array) -> UnitMove:
    return eqx.tree_at(lambda v: v.end.bearing, view, view.end.bearing + eps)


@jax.jit
def bearing_jacobian(
    env: Env, points: Points, headings: PerPoint, key: Array, sensor: Sensor, method: HomingMethod
) -> tuple[PointBlobs, PointBlobFlags, PerPointFlag]:
    """d(direction)/d(current blob bearings) at every point: (jac (P, B), blob_valid (P, B), valid (P,)).

    Same keys and unit moves as `maps.homing_directions`; rad per rad; 0 where undefined.
    """
    k_home, k_views, _ = stream_keys(key)
    home = record_home(env, k_home, sensor)
    visible = jnp.ones(env.landmarks.shape[0], bool)

    def one(point, heading, index):
        view = sense(env, visible, map_poses(point, heading, k_views, index, sensor), method, sensor)

        def angle(eps):
            a, ok = method(home, _perturbed(view, eps))
            return jnp.where(ok, a, 0.0), ok

        jac, ok = jax.grad(angle, has_aux=True)(jnp.zeros_like(view.end.bearing))
        jac = jnp.where(ok & view.end.valid & jnp.isfinite(jac), jac, 0.0)
        return jac, view.end.valid, ok

    return jax.vmap(one)(points, headings, jnp.arange(points.shape[0]))


def bearing_noise_gain(
    env: Env, points: Points, headings: PerPoint, key: Array, sensor: Sensor, method: HomingMethod
) -> tuple[PerPoint, PerPointFlag]:
    """First-order std of the homing direction per unit std of independent bearing noise
    on the current view, (P,) deg per deg, and validity (P,)."""
    jac, _, ok = bearing_jacobian(env, points, headings, key, sensor, method)
    return jnp.linalg.norm(jac, axis=-1), ok
