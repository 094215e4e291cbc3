"""Analytic landmark views: bearings, angular widths and a soft visibility from the geometry
(docs/differentiable.md "Analytic views"), beside the pixel path of `core.sensing`.

The pixel path renders a ring and extracts blobs: bearings are multiples of half a pixel and
overlapping cylinders merge into one blob, so nothing is differentiable with respect to the
scene. Here each landmark is its own blob:

    bearing_l = angle(c_l - x) - heading,  width_l = 2 asin(r_l / |c_l - x|),

and a landmark whose view overlaps that of a nearer one fades out with the overlap,

    weight_l = prod_{m nearer} (1 - sigmoid((w_l / 2 + w_m / 2 - |wrap(b_l - b_m)|) / s)),

with `s` the visibility width (rad). Where no two landmarks touch in view (the pixel path's
blobs are then single landmarks) the bearings agree with the pixel path to half a pixel, and
every weight is 1 up to sigmoid tails; `tests/gradients/test_loss.py` checks both on random scenes. A blob
counts as seen (valid) where its weight exceeds 1/2. Bearing noise is added as in
`sensing.snapshot`: one draw per sorted slot from the same key, so a noise sigma is
differentiable pathwise (fixed standard normal draws times sigma).
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


class SoftSnapshot(eqx.Module):
    """One analytic view: bearing, width, weight (soft visibility in [0, 1]) and valid (weight >
    1/2), (B,) each, sorted by bearing in [0, 2 pi) with the unseen slots last (their weight 0)."""

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
    """Per landmark (unsorted): bearing in the agent frame (rad), angular width (rad) and soft
    visibility weight; invalid, hidden or enclosing (pos inside the cylinder) landmarks weigh 0."""
    rel = env.landmarks[:, :2] - pos
    dist = safe_norm(rel)
    r = env.landmarks[:, 2]
    outside = dist > r
    ratio = jnp.where(outside, r / jnp.where(outside, dist, 1.0), 0.5)  # inside: a finite stand-in (no NaN gradient)
    half = jnp.where(outside, jnp.arcsin(jnp.minimum(ratio, 1.0 - 1e-6)), jnp.pi)
    bearing = wrap_positive(angle_of(rel) - heading)
    seen = env.valid & visible & outside
    gap = jnp.abs(wrap(bearing[:, None] - bearing[None, :]))  # (l, m)
    overlap = half[:, None] + half[None, :] - gap
    nearer = (dist[None, :] < dist[:, None]) & seen[None, :]
    cover = jnp.where(nearer, jax.nn.sigmoid(overlap / sharpness), 0.0)
    weight = jnp.where(seen, jnp.prod(1.0 - cover, axis=1), 0.0)
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
    """`analytic_blobs` sorted into slots, with the bearing noise of `sensing.snapshot`."""
    bearing, width, weight = analytic_blobs(env, visible, pos, heading, sharpness)
    bearing, width, weight = _sorted(bearing, weight > 0.5, width, weight)
    bearing = bearing + sensor.noise.bearing_errors(key, bearing.shape)
    bearing, width, weight = _sorted(bearing, weight > 0.5, width, weight)
    return SoftSnapshot(bearing=bearing, width=width, weight=weight, valid=weight > 0.5)


def _sorted(bearing: Array, valid: Array, *carried: Array) -> tuple[Array, ...]:
    """Slots sorted by bearing in [0, 2 pi), invalid last (their values 0): a permutation, so the
    gradient flows to each landmark's own slot."""
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
    """The same analytic views as a `sensing.UnitMove` (blobs with weight > 1/2, empty images), so
    the hard methods run on exactly what the soft ones see (the tau -> 0 comparison)."""

    def snap(s: SoftSnapshot) -> Snapshot:
        return Snapshot(
            mask=jnp.zeros(n_pix, bool),
            gray=jnp.zeros(n_pix, jnp.float32),
            bearing=s.bearing,
            width=s.width,
            valid=s.valid,
        )

    return UnitMove(
        start=snap(move.start), end=snap(move.end), d_hat=move.d_hat, psi_hat=move.psi_hat, compass=move.compass
    )
