"""Ring images, landmark blobs and noisy unit movements (docs/model.md §2.2-2.5, §3.1).

Everything here is written for ONE viewpoint; maps and rollouts `vmap` it.
"""

from __future__ import annotations

import dataclasses

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from .cylinder_blobs import blobs_of_cylinders, cylinder_offsets, pixel_directions
from .geometry import TWO_PI, rotate, unit, wrap, wrap_positive
from .scene import Env
from .sensor import Sensor
from .types import Point, Real, Scalar, SnapBlobs, SnapFlags, SnapMask, SnapRing


class Snapshot(eqx.Module):
    """One omnidirectional view (docs/model.md §2.2-2.4).

    mask, gray: (n_pix,) ring images; bearing, width, valid: (B,) blobs sorted by bearing in
    [0, 2pi), padding last (width: apparent angular size, rad); channel: the sensor's image
    channel, read by the image methods as `image`; panorama, elevations: the whole gray
    panorama (rows, n_pix; uint8 luminance from the image pipeline) and its row-centre elevations
    (rows,) rad, where a method reads them
    (MinWarping, docs/model.md §4.7), else None.
    """

    mask: SnapMask  # a database holds a batch of snapshots
    gray: SnapRing
    bearing: SnapBlobs
    width: SnapBlobs
    valid: SnapFlags
    channel: str = eqx.field(static=True, default="mask")
    panorama: Array | None = None
    elevations: Array | None = None

    @property
    def image(self) -> Array:
        """The ring image of the sensor's channel (docs/model.md §2.2)."""
        return getattr(self, self.channel)


class UnitMove(eqx.Module):
    """Two snapshots of one unit movement (docs/model.md §3.1) and the agent's own readings.

    start, end: snapshots at P and C; d_hat: believed step (cm); psi_hat: believed turn
    (rad); compass: compass reading of the heading at C minus alpha_r (rad).
    """

    start: Snapshot
    end: Snapshot
    d_hat: Array
    psi_hat: Array
    compass: Array


def background_of_angle(phi: Array) -> Array:
    """docs/model.md §2.3 background intensity as a function of an angle (radians)."""
    return 0.45 + 0.25 * jnp.sin(3.0 * phi) + 0.15 * jnp.sin(7.0 * phi + 1.0)


def wall_coordinate(origin: Array, direction: Array, arena: Array) -> Array:
    """Perimeter fraction f in [0, 1) of the wall point a ray leaves the arena through (docs/model.md §2.3).

    origin: (2,); direction: (..., 2) unit vectors; s counted counter-clockwise from (xmin, ymin).
    """
    xmin, ymin, xmax, ymax = arena[0], arena[1], arena[2], arena[3]
    w, h = xmax - xmin, ymax - ymin
    ux, uy = direction[..., 0], direction[..., 1]
    big = jnp.float32(1e30)
    safe_ux = jnp.where(ux == 0, 1.0, ux)
    safe_uy = jnp.where(uy == 0, 1.0, uy)
    tx = jnp.where(ux > 0, (xmax - origin[0]) / safe_ux, jnp.where(ux < 0, (xmin - origin[0]) / safe_ux, big))
    ty = jnp.where(uy > 0, (ymax - origin[1]) / safe_uy, jnp.where(uy < 0, (ymin - origin[1]) / safe_uy, big))
    t = jnp.maximum(jnp.minimum(tx, ty), 0.0)
    qx = jnp.clip(origin[0] + t * ux, xmin, xmax)
    qy = jnp.clip(origin[1] + t * uy, ymin, ymax)
    s_bottom = qx - xmin
    s_right = w + (qy - ymin)
    s_top = w + h + (xmax - qx)
    s_left = 2 * w + h + (ymax - qy)
    s = jnp.where(tx < ty, jnp.where(ux > 0, s_right, s_left), jnp.where(uy > 0, s_top, s_bottom))
    return jnp.mod(s / (2 * (w + h)), 1.0)


def ray_hits(landmarks: Array, visible: Array, origin: Array, heading: Array, n_pix: int) -> Array:
    """Whether each pixel ray hits a visible cylinder (docs/model.md §2.2), (n_pix,) bool.

    Ray j leaves `origin` along heading + 2 pi j / n_pix. Landmark offsets are rotated
    into the agent frame once, so the per-pixel work is two dot products and compares;
    a ray starting inside a cylinder hits it.
    """
    rel, c2 = cylinder_offsets(landmarks, origin, heading)  # (L, 2) agent frame, (L,)
    b = jnp.asarray(pixel_directions(n_pix)) @ rel.T  # (n_pix, L)
    hit = visible & ((c2 <= 0) | ((b * b >= c2) & (b > 0)))
    return jnp.any(hit, axis=-1)


def distant_background(heading: Array, n_pix: int) -> Array:
    """docs/model.md §2.3 `distant` background of every pixel, by angle addition from constant tables."""
    a = 2.0 * np.pi * np.arange(n_pix) / n_pix
    c3, s3, c7, s7 = (jnp.asarray(f(k * a), jnp.float32) for k in (3, 7) for f in (np.cos, np.sin))
    sin3 = jnp.sin(3.0 * heading) * c3 + jnp.cos(3.0 * heading) * s3
    sin7 = jnp.sin(7.0 * heading + 1.0) * c7 + jnp.cos(7.0 * heading + 1.0) * s7
    return 0.45 + 0.25 * sin3 + 0.15 * sin7


def computed_if(flag: Array | bool, fn):
    """fn() where `flag`, else zeros of the same shapes. A Python bool decides when tracing; a
    traced flag at run time (`lax.cond`: unbatched under vmap, so the skipped branch costs nothing)."""

    def zeros():
        return jax.tree.map(lambda s: jnp.zeros(s.shape, s.dtype), jax.eval_shape(fn))

    if isinstance(flag, bool):
        return fn() if flag else zeros()
    return jax.lax.cond(flag, fn, zeros)


def render(
    env: Env, visible: Array, pos: Array, heading: Array, sensor: Sensor, with_gray: Array | bool = True
) -> tuple[Array, Array]:
    """Ring image at `pos` with `heading` (docs/model.md §2.2-2.3): (mask bool (n_pix,), gray (n_pix,)).

    Pixel j looks along world angle heading + 2*pi*j/n_pix; landmark = 1, else background.
    `with_gray` False leaves gray zero (`computed_if`; for methods that read only the mask).
    """
    n = sensor.n_pix
    mask = ray_hits(env.landmarks, visible & env.valid, pos, heading, n)

    def gray():
        directions = rotate(jnp.asarray(pixel_directions(n)), heading)
        walls = background_of_angle(TWO_PI * wall_coordinate(pos, directions, env.arena))
        code = jnp.asarray(sensor.background)  # traced: every setting shares one compiled program
        back = jnp.where(code == 0, distant_background(heading, n), jnp.where(code == 1, walls, 0.0))
        return jnp.where(mask, 1.0, back)

    return mask, computed_if(with_gray, gray)


def _run_indices(flags: Array, max_blobs: int) -> Array:
    """Pixel index of the k-th set flag for k < max_blobs (0 where absent): a short chain
    of argmax searches over the pixels (max_blobs is the landmark count, a handful)."""
    pixel = jnp.arange(flags.shape[0])
    found, last = [], -1
    for _ in range(max_blobs):
        candidate = flags & (pixel > last)
        i = jnp.argmax(candidate)
        ok = candidate[i]
        found.append(jnp.where(ok, i, 0))
        last = jnp.where(ok, i, flags.shape[0])
    return jnp.stack(found)


def blob_runs(mask: Array, max_blobs: int) -> tuple[Array, Array, Array]:
    """Blobs of a ring mask (docs/model.md §2.4): (bearing (B,), width (B,), valid (B,)), sorted by
    bearing in [0, 2pi).

    A blob is a maximal circular run of mask pixels; its bearing is the circular midpoint
    of its first and last pixel, its width the run's angular size, (pixels) * 2 pi / n_pix.
    All pixels set: one blob at 0 of width 2 pi. Shapes are fixed: at most `max_blobs` blobs
    (a mask of L cylinders has at most L runs), padding marked invalid.
    """
    n = mask.shape[-1]
    starts = mask & ~jnp.roll(mask, 1)
    ends = mask & ~jnp.roll(mask, -1)
    count = jnp.minimum(jnp.sum(starts), max_blobs)
    start_idx = _run_indices(starts, max_blobs)
    end_idx = _run_indices(ends, max_blobs)
    # If the first run end precedes the first run start, a run wraps through pixel 0:
    # start k is closed by end k + 1.
    wraps = end_idx[0] < start_idx[0]
    slot = jnp.arange(max_blobs)
    end_idx = jnp.where(wraps, end_idx[(slot + 1) % jnp.maximum(count, 1)], end_idx)
    length = jnp.mod(end_idx - start_idx, n)
    # Midpoint in whole half-pixels, wrapped in integers: a blob centred on pixel 0 has
    # bearing exactly 0 however XLA reassociates the float arithmetic.
    half_pixels = jnp.mod(2 * start_idx + length, 2 * n)
    bearing = half_pixels.astype(jnp.float32) * jnp.float32(np.pi / n)
    width = (length + 1).astype(jnp.float32) * jnp.float32(2.0 * np.pi / n)
    valid = slot < count
    all_on = jnp.all(mask)
    bearing = jnp.where(all_on, 0.0, bearing)
    width = jnp.where(all_on, jnp.float32(2.0 * np.pi), width)
    valid = jnp.where(all_on, slot == 0, valid)
    bearing, valid, width = sort_blobs(bearing, valid, width)
    return bearing, width, valid


def extract_blobs(mask: Array, max_blobs: int) -> tuple[Array, Array]:
    """Blob bearings and validity of a ring mask (`blob_runs` without the widths)."""
    bearing, _, valid = blob_runs(mask, max_blobs)
    return bearing, valid


def sort_blobs(bearing: Array, valid: Array, *carried: Array) -> tuple[Array, ...]:
    """Sort blob bearings into [0, 2pi) ascending, invalid slots last (set to 0): (bearing, valid,
    *carried), each array of `carried` (per-blob values, e.g. widths) permuted alike. One variadic
    sort keyed on the bearings: XLA drops a carried operand that nothing reads."""
    key = jnp.where(valid, wrap_positive(bearing), jnp.inf)
    b, *rest = jax.lax.sort((key, *carried), num_keys=1)
    ok = jnp.isfinite(b)
    return (jnp.where(ok, b, 0.0), ok, *(jnp.where(ok, c, 0.0) for c in rest))


def snapshot(
    env: Env,
    visible: Array,
    pos: Array,
    heading: Array,
    key: Array,
    sensor: Sensor,
    with_gray: Array | bool = True,
    with_mask: Array | bool = True,
) -> Snapshot:
    """Render, extract blobs and add bearing noise (docs/model.md §2.5) for one viewpoint.

    The blobs come from the cylinders (`cylinder_blobs`: those of the rendered ring); the ring itself
    is rendered only for a method that reads it (`with_mask` or `with_gray`; otherwise zero). A sensor
    with a `panorama` renderer adds the gray panorama of the pose (MinWarping; docs/images.md §10).
    """
    plain = isinstance(with_mask, bool) and isinstance(with_gray, bool)
    needed = (with_mask or with_gray) if plain else jnp.logical_or(with_mask, with_gray)
    mask, gray = computed_if(needed, lambda: render(env, visible, pos, heading, sensor, with_gray))
    bearing, width, valid = blobs_of_cylinders(env.landmarks, visible & env.valid, pos, heading, sensor.n_pix)
    bearing, valid, width = sort_blobs(bearing + sensor.noise.bearing_errors(key, bearing.shape), valid, width)
    snap = Snapshot(mask=mask, gray=gray, bearing=bearing, width=width, valid=valid, channel=sensor.channel)
    if sensor.panorama is None:
        return snap
    gray_panorama, elevations = sensor.panorama(env, visible, pos, heading)  # docs/images.md §10
    return dataclasses.replace(snap, panorama=gray_panorama, elevations=elevations)


def observe_move(
    env: Env,
    visible: Array,
    start: Array,
    end: Array,
    heading_start: Array,
    heading_end: Array,
    d_hat: Real,
    psi_hat: Array,
    key: Array,
    sensor: Sensor,
    with_start: Array | bool = True,
    with_gray: Array | bool = True,
    with_mask: Array | bool = True,
) -> UnitMove:
    """Snapshots at `start` and `end` of a move already made (true poses given), plus the
    agent's readings: odometry (d_hat, psi_hat) and a compass reading of heading_end - alpha_r
    with N(0, noise.compass) error. Rollouts use this for the step just made.

    `with_start` False leaves the start snapshot zero (a method that reads only the current
    view), `with_gray` False the gray channels, `with_mask` and `with_gray` both False the ring
    images (`computed_if`; a traced flag skips the work at run time). No noise draw depends on them.
    """
    k_compass, k_start, k_end = sensor.noise.observation_keys(key)
    compass = wrap(heading_end - sensor.alpha_r + sensor.noise.compass_error(k_compass))
    return UnitMove(
        start=computed_if(
            with_start, lambda: snapshot(env, visible, start, heading_start, k_start, sensor, with_gray, with_mask)
        ),
        end=snapshot(env, visible, end, heading_end, k_end, sensor, with_gray, with_mask),
        d_hat=jnp.asarray(d_hat, jnp.float32),
        psi_hat=jnp.asarray(psi_hat, jnp.float32),
        compass=compass,
    )


class MovePoses(eqx.Module):
    """The true poses and odometry of one move, before sensing (docs/model.md §2.5, §3.1, §5).

    start, end: (2,) cm; heading_start: heading of the move; heading_end: heading at the end
    (after the body turn psi); psi_hat: the odometry's turn; key: the observation's key.
    """

    start: Point
    end: Point
    heading_start: Scalar
    heading_end: Scalar
    psi_hat: Scalar
    key: Array


def unit_move_poses(start: Array, heading: Array, key: Array, sensor: Sensor, end_at: Array | None = None) -> MovePoses:
    """The true poses and odometry of one unit movement (docs/model.md §2.5, §3.1), before sensing.

    The agent at P = `start` with `heading` moves d * (1 + N(0, noise.step)) along it and
    turns by psi ~ N(0, noise.turn); odometry reports d_hat = d and psi_hat = psi +
    N(0, noise.turn_odometry). If `end_at` is given the move ends there instead
    (P = end_at - step * u(heading)): the current view of a vector map (docs/model.md §3.3).
    """
    step, psi, psi_hat, k_obs = sensor.noise.unit_move(key, sensor.d)
    if end_at is not None:
        start = end_at - step * unit(heading)
    return MovePoses(start, start + step * unit(heading), heading, heading + psi, psi_hat, k_obs)


def observe_poses(
    env: Env,
    visible: Array,
    poses: MovePoses,
    sensor: Sensor,
    with_start: Array | bool = True,
    with_gray: Array | bool = True,
    with_mask: Array | bool = True,
) -> UnitMove:
    """`observe_move` of a `MovePoses` (the odometry reports d_hat = d)."""
    return observe_move(
        env,
        visible,
        poses.start,
        poses.end,
        poses.heading_start,
        poses.heading_end,
        sensor.d,
        poses.psi_hat,
        poses.key,
        sensor,
        with_start,
        with_gray,
        with_mask,
    )


def unit_move(
    env: Env,
    start: Array,
    heading: Array,
    key: Array,
    sensor: Sensor,
    visible: Array | None = None,
    end_at: Array | None = None,
) -> tuple[UnitMove, Array]:
    """Sense one unit movement (`unit_move_poses`); returns (UnitMove, true heading at the end)."""
    if visible is None:
        visible = jnp.ones(env.landmarks.shape[0], bool)
    poses = unit_move_poses(start, heading, key, sensor, end_at)
    return observe_poses(env, visible, poses, sensor), poses.heading_end


def record_home(env: Env, key: Array, sensor: Sensor) -> UnitMove:
    """The home record (docs/model.md §3.3): a unit movement from home along alpha_r, all landmarks seen."""
    move, _ = unit_move(env, env.home, jnp.asarray(sensor.alpha_r, jnp.float32), key, sensor)
    return move
