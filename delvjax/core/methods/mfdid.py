"""Matched-filter descent in image distances, MFDID (Möller & Vardy 2006; docs/model.md §4.5).

Source: R. Möller, A. Vardy, "Local visual homing by matched-filter descent in image
distances", Biological Cybernetics 95:413-430 (2006), specialised to 1D ring images and
a compass (the images are compared in the alpha_r frame).

The image distance is the sum of squared differences D(x) = sum_j (C_j(x) - S(t_j))^2,
t_j = c + 2 pi j / n the world angle (alpha_r frame) of current pixel j, c the compass
reading of h - alpha_r. Its spatial gradient is estimated from the current image alone:
under the equal-distance assumption (every feature at one distance r) a translation dx
moves the feature seen at t by dt = (sin t dx - cos t dy) / r, so the image changes by
dC_j = -C'_j dt (the matched filters are the flow templates (sin t, -cos t) of the two
translations), and

    grad D = (2 / r) sum_j (C_j - S(t_j)) C'_j (-sin t_j, cos t_j).

The home vector is minus the gradient, H = sum_j (S(t_j) - C_j) C'_j (-sin t_j, cos t_j);
r only scales it. C'_j = (C_{j+1} - C_{j-1}) / 2 (circular central difference, per pixel);
S is read at t_j by circular linear interpolation. Invalid (NaN) when H = 0.

Möller & Vardy work on low-pass filtered images: the first-order flow model holds only
for image structure wider than the displacement's flow. `MFDID.blur_deg` (default 0:
the raw images) blurs both images with a circular Gaussian first; on env1 with the `mask`
channel it takes the mean angular error from ~112 deg (raw) to ~35 deg (40 deg blur).
"""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..geometry import TWO_PI, angle_of, safe_norm, wrap
from ..sensing import UnitMove
from ..settings import setting
from ..types import Real
from .base import HomingMethod
from .heading import Compass, HeadingSource


def sample_ring(image: Array, angle: Array) -> Array:
    """Circular linear interpolation of a ring image (pixel j at 2 pi j / n) at `angle` (radians)."""
    n = image.shape[-1]
    x = jnp.mod(angle * (n / TWO_PI), n)
    i0 = jnp.floor(x)
    w = x - i0
    i0 = i0.astype(jnp.int32) % n
    return (1.0 - w) * image[i0] + w * image[(i0 + 1) % n]


def low_pass(image: Array, sigma_pix: Real) -> Array:
    """Circular Gaussian blur of a ring image, std `sigma_pix` pixels (0 = unchanged), by FFT:
    the wrapped Gaussian's spectrum is exp(-2 pi^2 sigma^2 f^2 / n^2). Differentiable in sigma."""
    n = image.shape[-1]
    f = jnp.arange(n // 2 + 1, dtype=jnp.float32)
    gain = jnp.exp(-2.0 * (jnp.pi * sigma_pix * f / n) ** 2)
    return jnp.fft.irfft(jnp.fft.rfft(image) * gain, n=n).astype(jnp.float32)


def home_vector(home_image: Array, view_image: Array, heading: Array, blur_pix: Array = 0.0) -> Array:
    """H = -grad D / (2 / r) in the alpha_r frame, (2,); images (n_pix,), heading = h - alpha_r;
    both images low-passed by a Gaussian of `blur_pix` pixels first."""
    c = low_pass(view_image.astype(jnp.float32), blur_pix)
    n = c.shape[-1]
    t = heading + TWO_PI * jnp.arange(n, dtype=jnp.float32) / n
    s = sample_ring(low_pass(home_image.astype(jnp.float32), blur_pix), t)
    dc = 0.5 * (jnp.roll(c, -1) - jnp.roll(c, 1))
    weight = (s - c) * dc
    return jnp.stack([jnp.sum(-weight * jnp.sin(t)), jnp.sum(weight * jnp.cos(t))])


class MFDID(HomingMethod):
    """Matched-filter descent in image distances on the sensor's channel (docs/model.md §4.5).

    blur_deg: Gaussian low-pass of both images, degrees (0 = the raw images).
    """

    blur_deg: Real = setting(
        0.0, check="non_negative", unit="deg", formerly="mfdid_blur_deg", help="Gaussian low-pass of both images"
    )
    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        blur_pix = self.blur_deg * view.end.mask.shape[-1] / 360.0
        h = home_vector(home.start.image, view.end.image, heading, blur_pix)
        valid = safe_norm(h) > 0
        return jnp.where(valid, wrap(angle_of(h) - heading), jnp.nan), valid

    def reads_image(self) -> bool:
        return True

    def reads_gray(self, channel: str) -> bool:
        return channel == "gray" or self.heading.reads_gray
