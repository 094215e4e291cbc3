"""Analytic landmark views: bearings, angular widths and a soft visibility from the geometry
(docs/differentiable.md "Analytic views" and "A continuous loss"), beside the pixel path of
`core.sensing`.

The pixel path renders a ring and extracts blobs: bearings are multiples of half a pixel and
overlapping cylinders merge into one blob, so nothing is differentiable with respect to the
scene. Here each landmark is its own slot, in landmark order, in every view:

    bearing_l = angle(c_l - x) - heading,  width_l = 2 asin(min(r_l / |c_l - x|, 1)),

and a landmark fades out as a nearer one covers it and as the agent comes within a
centimetre of its surface,

    weight_l = sigmoid((|c_l - x| - r_l) / e) prod_{m != l} (1 - sigmoid((w_l/2 + w_m/2 - |wrap(b_l - b_m)|) / s)
                                                             sigmoid((|c_l - x| - |c_m - x|) / n)),

with `s` the visibility width (rad), `e` = EDGE_CM and `n` = NEARER_CM. Every quantity is a continuous function
of the landmarks, the pose and the noise (no slot appears, disappears or changes its noise
draw), so the homing loss is continuous and its Gaussian smoothing has an unbiased pathwise
gradient (docs/differentiable.md "Sensitivity at a stated scale"). Where no two landmarks touch
in view the bearings agree with the pixel path to half a pixel and every weight is 1 up to
sigmoid tails (`tests/gradients/test_loss.py`). A slot counts as seen by the hard methods
(`as_unit_move`) where its weight exceeds 1/2. Bearing noise: one draw per landmark slot, so
a noise sigma is differentiable pathwise (fixed standard normal draws times sigma).
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import angle_of, safe_norm, wrap, wrap_positive
from ..scene import Env
from ..sensing import MovePoses, Snapshot, UnitMove, unit_move_poses
from ..sensor import Sensor

VISIBILITY_WIDTH = 0.01  # rad: the soft visibility's sigmoid width s (about half a pixel of 360)
EDGE_CM = 1.0  # cm: e, the soft edge of a cylinder's surface (docs/differentiable.md)
NEARER_CM = 0.1  # cm: how close two distances are before "nearer" blends (only overlapping views use it)


class SoftSnapshot(eqx.Module):
    """One analytic view, one slot per landmark (landmark order): bearing in [0, 2 pi), width,
    weight (soft visibility in [0, 1]) and valid (the slot holds a landmark of the scene that
    this view may see: fixed for a scene, whatever the pose), (L,) each."""

    bearing: Array
    width: Array
    weight: Array
    valid: Array


class SoftMove(eqx.Module):
    """A unit movement seen analytically (the analogue of `sensing.UnitMove`)."""

    start: SoftSnapshot
    end: SoftSnapshot
    d_hat: Array
    psi_hat: Array
    compass: Array


def analytic_blobs(
    env: Env, visible: Array, pos: Array, heading: Array, sharpness: float | Array = VISIBILITY_WIDTH
) -> tuple[Array, Array, Array]:
    """Per landmark (landmark order): bearing in the agent frame (rad), angular width (rad) and soft
    visibility weight; invalid or hidden-by-rule (`visible` False) landmarks weigh 0."""
    rel = env.landmarks[:, :2] - pos
    dist = safe_norm(rel)
    r = env.landmarks[:, 2]
    half = jnp.arcsin(jnp.clip(r / jnp.maximum(dist, 1e-6), 0.0, 1.0 - 1e-6))  # pi/2 on and inside the surface
    bearing = wrap_positive(angle_of(rel) - heading)
    seen = env.valid & visible
    gap = jnp.abs(wrap(bearing[:, None] - bearing[None, :]))  # (l, m)
    overlap = half[:, None] + half[None, :] - gap
    nearer = jax.nn.sigmoid((dist[:, None] - dist[None, :]) / NEARER_CM)  # m in front of l
    others = seen[None, :] & ~jnp.eye(dist.shape[0], dtype=bool)
    cover = jnp.where(others, jax.nn.sigmoid(overlap / sharpness) * nearer, 0.0)
    outside = jax.nn.sigmoid((dist - r) / EDGE_CM)
    weight = jnp.where(seen, outside * jnp.prod(1.0 - cover, axis=1), 0.0)
    return bearing, 2.0 * half, weight


def soft_snapshot(
    env: Env,
    visible: Array,
    pos: Array,
    heading: Array,
    key: Array,
    sensor: Sensor,
    sharpness: float | Array = VISIBILITY_WIDTH,
) -> SoftSnapshot:
    """`analytic_blobs` with bearing noise (one draw per landmark slot from `key`)."""
    bearing, width, weight = analytic_blobs(env, visible, pos, heading, sharpness)
    bearing = wrap_positive(bearing + sensor.noise.bearing_errors(key, bearing.shape))
    return SoftSnapshot(bearing=bearing, width=width, weight=weight, valid=env.valid & visible)


def _sorted(bearing: Array, valid: Array, *carried: Array) -> tuple[Array, ...]:
    """Slots sorted by bearing in [0, 2 pi), invalid last (their values 0): the blob lists of the
    hard methods."""
    key = jnp.where(valid, wrap_positive(bearing), jnp.inf)
    order = jnp.argsort(key, stable=True)
    ok = valid[order]
    return (jnp.where(ok, wrap_positive(bearing[order]), 0.0), *(jnp.where(ok, c[order], 0.0) for c in carried))


def soft_observe(
    env: Env, visible: Array, poses: MovePoses, sensor: Sensor, sharpness: float | Array = VISIBILITY_WIDTH
) -> SoftMove:
    """`sensing.observe_poses` with analytic snapshots: the same keys, odometry and compass."""
    k_compass, k_start, k_end = sensor.noise.observation_keys(poses.key)
    compass = wrap(poses.heading_end - sensor.alpha_r + sensor.noise.compass_error(k_compass))
    return SoftMove(
        start=soft_snapshot(env, visible, poses.start, poses.heading_start, k_start, sensor, sharpness),
        end=soft_snapshot(env, visible, poses.end, poses.heading_end, k_end, sensor, sharpness),
        d_hat=jnp.asarray(sensor.d, jnp.float32),
        psi_hat=poses.psi_hat,
        compass=compass,
    )


def soft_home(env: Env, key: Array, sensor: Sensor, sharpness: float | Array = VISIBILITY_WIDTH) -> SoftMove:
    """The home record (docs/model.md §3.3) seen analytically: a unit move from home along alpha_r."""
    poses = unit_move_poses(env.home, jnp.asarray(sensor.alpha_r, jnp.float32), key, sensor)
    return soft_observe(env, jnp.ones(env.landmarks.shape[0], bool), poses, sensor, sharpness)


def as_unit_move(move: SoftMove, n_pix: int) -> UnitMove:
    """The same analytic views as a `sensing.UnitMove`: the slots with weight > 1/2 as sorted blob
    lists, empty images, so the hard methods run on exactly what the soft ones see (the tau -> 0
    comparison)."""

    def snap(s: SoftSnapshot) -> Snapshot:
        seen = s.valid & (s.weight > 0.5)
        bearing, width, valid = _sorted(s.bearing, seen, s.width, seen.astype(jnp.float32))
        return Snapshot(
            mask=jnp.zeros(n_pix, bool),
            gray=jnp.zeros(n_pix, jnp.float32),
            bearing=bearing,
            width=width,
            valid=valid > 0.5,
        )

    return UnitMove(
        start=snap(move.start), end=snap(move.end), d_hat=move.d_hat, psi_hat=move.psi_hat, compass=move.compass
    )
