"""The omnidirectional image pipeline as array programs (docs/images.md §5; thesis §4.4.1):
camera noise, unwrapping a donut into a panorama, RGB -> HSV, threshold segmentation, band
averaging into a 1D ring, and blob extraction into the `Snapshot` every homing method reads.
Written for ONE image; callers `vmap` it.
"""

from __future__ import annotations

import dataclasses
import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array
from jax.scipy.ndimage import map_coordinates

from ..sensing import Snapshot, blob_runs
from ..settings import setting
from ..types import Real
from .world import Camera, Catadioptric


def _lowbias32(x: Array) -> Array:
    """A 32-bit integer hash with good avalanche (C. Wellons' lowbias32)."""
    x = x ^ (x >> 16)
    x = x * jnp.uint32(0x7FEB352D)
    x = x ^ (x >> 15)
    x = x * jnp.uint32(0x846CA68B)
    return x ^ (x >> 16)


def pixel_normals(key: Array, shape: tuple[int, ...]) -> Array:
    """Approximately standard normal draws, one per element of `shape` (docs/images.md §5.1): the
    Irwin-Hall sum of the four bytes of a counter-based hash of (element index, a 32-bit seed drawn
    from `key`), centred and scaled to unit variance (bounded at +-3.45). Eight times faster than
    `jax.random.normal` on the CPU, where it dominated the cost of a rendered database."""
    seed = jax.random.bits(key, (), jnp.uint32)
    h = _lowbias32(jax.lax.iota(jnp.uint32, math.prod(shape)).reshape(shape) * jnp.uint32(0x9E3779B9) + seed)
    total = (h & 255) + ((h >> 8) & 255) + ((h >> 16) & 255) + (h >> 24)
    return (total.astype(jnp.float32) - 510.0) * jnp.float32(1.0 / np.sqrt(4 * (256.0**2 - 1) / 12))


def camera_noise(key: Array, image: Array, sigma: Real, gain_sigma: Real = 0.0) -> Array:
    """docs/images.md §5.1: a global brightness gain 1 + N(0, gain_sigma) (flicker, exposure) and
    independent noise of standard deviation sigma per pixel and channel (`pixel_normals`), clipped to [0, 1]."""
    k_gain, k_pix = jax.random.split(key)
    gain = 1.0 + gain_sigma * jax.random.normal(k_gain, dtype=jnp.float32)
    return jnp.clip(image * gain + sigma * pixel_normals(k_pix, image.shape), 0.0, 1.0)


def to_uint8(image: Array) -> Array:
    """8-bit quantization, as stored in a PNG (round half up)."""
    return jnp.floor(jnp.clip(image, 0.0, 1.0) * 255.0 + 0.5).astype(jnp.uint8)


def unwrap(image: Array, mirror: Catadioptric, camera: Camera) -> Array:
    """Donut (S, S, 3) -> panorama (camera.rows, camera.cols, 3) by bilinear sampling
    (`map_coordinates`, order 1) at the donut pixel of every panorama pixel (docs/images.md §2)."""
    elevation, azimuth = camera.elevations(), camera.azimuths()
    rho = mirror.radius_px(elevation)[:, None]  # (rows, 1)
    theta = azimuth[None, :] + jnp.pi / 2
    c = (mirror.size - 1) / 2.0
    rows, cols = c - rho * jnp.sin(theta), c + rho * jnp.cos(theta)
    channel = lambda ch: map_coordinates(ch, [rows, cols], order=1, mode="constant", cval=0.0)  # noqa: E731
    return jax.vmap(channel, in_axes=-1, out_axes=-1)(image.astype(jnp.float32))


def rgb_to_hsv(rgb: Array) -> Array:
    """(..., 3) RGB in [0, 1] -> (..., 3) HSV: hue in [0, 1) (red 0), saturation, value (the usual hexcone)."""
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    v = jnp.max(rgb, -1)
    c = v - jnp.min(rgb, -1)
    s = jnp.where(v > 0, c / jnp.where(v > 0, v, 1.0), 0.0)
    safe = jnp.where(c > 0, c, 1.0)
    h = jnp.where(v == r, (g - b) / safe, jnp.where(v == g, 2.0 + (b - r) / safe, 4.0 + (r - g) / safe))
    h = jnp.where(c > 0, jnp.mod(h / 6.0, 1.0), 0.0)
    return jnp.stack([h, s, v], -1)


def segment(hsv: Array, hue_deg: Real, hue_width_deg: Real, sat_min: Real, val_min: Real) -> Array:
    """Landmark pixels (docs/images.md §5.3): hue within hue_width_deg / 2 of hue_deg (circularly),
    saturation >= sat_min, value >= val_min."""
    dh = jnp.abs(jnp.mod(hsv[..., 0] * 360.0 - hue_deg + 180.0, 360.0) - 180.0)
    return (dh <= hue_width_deg / 2) & (hsv[..., 1] >= sat_min) & (hsv[..., 2] >= val_min)


class Extractor(eqx.Module):
    """From a panorama to a `Snapshot` (docs/images.md §5; thesis §4.4.1). Numbers are traced leaves
    (a sweep or a gradient reaches them), the blob count and channel are static.

    hue_deg, hue_width_deg, sat_min, val_min: the HSV threshold (red landmarks by default);
    band_deg, band_height_deg: the band of rows averaged into the ring (centre elevation and
    height, deg; the thesis averaged 10 rows); fill: a ring pixel is landmark where at least this
    share of its band is; max_blobs: blob slots; channel: the ring the image methods read.
    """

    hue_deg: Real = setting(0.0, help="landmark hue (red 0)", unit="deg")
    hue_width_deg: Real = setting(40.0, help="width of the landmark hue window", unit="deg")
    sat_min: Real = setting(0.5, help="least saturation of a landmark pixel, 0-1")
    val_min: Real = setting(0.15, help="least value (brightness) of a landmark pixel, 0-1")
    band_deg: Real = setting(0.0, help="centre elevation of the band of rows averaged into the ring", unit="deg")
    band_height_deg: Real = setting(10.0, help="height of the band of rows averaged into the ring", unit="deg")
    fill: Real = setting(0.5, help="share of its band a ring pixel needs to count as landmark, 0-1")
    max_blobs: int = setting(8, static=True, help="landmark blob slots of a snapshot", check="positive_int", limit=64)
    channel: str = eqx.field(static=True, default="mask")
    panorama: bool = eqx.field(static=True, default=False)  # keep the gray panorama (MinWarping)

    def band_weights(self, camera: Camera) -> Array:
        """(rows,) 1 for the rows whose centre lies in the band, else 0 (at least the nearest row)."""
        e = jnp.degrees(camera.elevations())
        off = jnp.abs(e - self.band_deg)
        w = (off <= self.band_height_deg / 2).astype(jnp.float32)
        return jnp.where(jnp.sum(w) > 0, w, (off == jnp.min(off)).astype(jnp.float32))

    def rings(self, image: Array, camera: Camera) -> tuple[Array, Array]:
        """(landmark share of the band (cols,), mean value of the band (cols,)) of a panorama."""
        hsv = rgb_to_hsv(image.astype(jnp.float32))
        mask = segment(hsv, self.hue_deg, self.hue_width_deg, self.sat_min, self.val_min)
        w = self.band_weights(camera)[:, None]
        total = jnp.sum(w)
        return jnp.sum(w * mask, 0) / total, jnp.sum(w * hsv[..., 2], 0) / total

    def __call__(self, image: Array, camera: Camera) -> Snapshot:
        snap = ring_snapshot(*self.rings(image, camera), self)
        if not self.panorama:
            return snap
        return dataclasses.replace(snap, panorama=gray_bytes(image), elevations=camera.elevations())


def gray_bytes(image: Array) -> Array:
    """Luminance (Rec. 601) of a colour image in [0, 1] as bytes, as the authors' gray images (a database
    keeps N of them): (rows, cols, 3) -> (rows, cols) uint8."""
    lum = image.astype(jnp.float32) @ jnp.array([0.299, 0.587, 0.114])
    return jnp.round(jnp.clip(lum, 0.0, 1.0) * 255.0).astype(jnp.uint8)


def ring_snapshot(share: Array, gray: Array, extractor: Extractor) -> Snapshot:
    """The `Snapshot` of band rings: mask where the landmark share >= fill, blobs of that mask."""
    mask = share >= extractor.fill
    bearing, width, valid = blob_runs(mask, extractor.max_blobs)
    return Snapshot(mask=mask, gray=gray, bearing=bearing, width=width, valid=valid, channel=extractor.channel)
