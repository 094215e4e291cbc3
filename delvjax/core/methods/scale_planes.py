"""The scale-plane stack of 2D-warping (Möller 2009 §3; Möller, Krzykawski & Gerstmayr 2010 §3;
docs/model.md §4.7): the distance between every column of the home panorama and every column of the
current one, at every vertical scale factor.

A landmark point at height z seen from distance r appears at elevation atan(z / r). Seen from
distance sigma * r it appears at atan(tan(e) / sigma): the current view's columns are vertically
scaled by 1 / sigma against the snapshot's. Plane s of the stack compares the snapshot with the
current view under the hypothesis r' / r = sigma_s (sigma_s > 1: the current view is farther; it is
magnified by sigma_s before comparing; sigma_s < 1: the snapshot is magnified by 1 / sigma_s; always
a magnification, so no row is read outside the image while the horizon is inside it). Magnification
reads the nearest row (`magnify`).

Column distances (Möller et al. 2010 §3.3, 2014 §2): `nsad` sum |a - b| / (sum |a| + sum |b|),
`nssd` sum (a - b)^2 / (sum a^2 + sum b^2), `sad` and `ssd` their means over rows; by default on
the vertical edge images (the difference of neighbouring rows, the authors' preprocessing; it
removes one row and makes the distance blind to a brightness offset).

Layout: `stack[s, i, j]` is the distance of snapshot column i and current column j at plane s.
`arranged` re-orders it for the search (docs/model.md §4.7 "How it is fast").
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..types import Arrays

MEASURES = ("nsad", "nssd", "sad", "ssd")
EPS = 1e-6


def scale_factors(n_planes: int, max_scale: float) -> np.ndarray:
    """(n_planes,) float64: geometric steps from 1 / max_scale to max_scale with 1 in the middle
    (n_planes odd; the authors' symmetric scale factors, Möller et al. 2010 §3.2)."""
    c = (n_planes - 1) // 2
    return max_scale ** ((np.arange(n_planes) - c) / max(c, 1))


def plane_of(sigma: np.ndarray, scales: np.ndarray, threshold: float) -> np.ndarray:
    """Plane index of every sigma: the nearest scale factor, split at the midpoints of neighbouring
    factors; sigma above `threshold` (the largest allowed) gets -1."""
    bounds = np.append(0.5 * (scales[:-1] + scales[1:]), threshold)
    plane = np.searchsorted(bounds, sigma, side="left")
    return np.where(sigma <= threshold, plane, -1)


def magnify(image: Arrays, elevations: Arrays, m: Array) -> Array:
    """image (rows, cols) seen m >= 1 times closer: out(e) = image(atan(tan(e) / m)), the nearest row
    (`elevations` (rows,) rad, equally spaced, row 0 at the top). Nearest, as the authors read it: a
    linear read would blur the magnified edges and bias the search against the magnified planes
    (on the rendered env1 database: mean error 10.1 deg linear, 5.9 nearest)."""
    e = jnp.arctan(jnp.tan(elevations) / m)
    f = (elevations[0] - e) / (elevations[0] - elevations[1])  # fractional row
    row = jnp.clip(jnp.floor(f + 0.5), 0, image.shape[-2] - 1).astype(jnp.int32)
    return image[row]


def prepare(image: Arrays, edges: bool) -> Array:
    """The image the columns are compared on: the vertical edge image (row r + 1 minus row r) or
    the image itself."""
    return image[..., 1:, :] - image[..., :-1, :] if edges else image


def column_distances(a: Arrays, b: Arrays, measure: str) -> Array:
    """(..., cols_a, cols_b) distance of every column of a (..., rows, cols) with every column of b.

    The sums over rows are written row by row (one fused loop over the (cols, cols) outputs, ~10x
    faster on CPU than a reduction over a broadcast (rows, cols, cols) array)."""
    rows = a.shape[-2]
    if measure in ("nsad", "sad"):
        term = [jnp.abs(a[..., r, :, None] - b[..., r, None, :]) for r in range(rows)]
        ca, cb = jnp.sum(jnp.abs(a), -2), jnp.sum(jnp.abs(b), -2)
    else:
        term = [jnp.square(a[..., r, :, None] - b[..., r, None, :]) for r in range(rows)]
        ca, cb = jnp.sum(a * a, -2), jnp.sum(b * b, -2)
    if measure in ("sad", "ssd"):
        scale = jnp.full(ca.shape[:-1] + (1, 1), 1.0 / rows, jnp.float32)
    else:
        scale = 1.0 / (ca[..., :, None] + cb[..., None, :] + EPS)
    # the barrier keeps XLA from fusing the normalisation into the sum over rows (2.5x slower on CPU)
    scale = jax.lax.optimization_barrier(scale)
    return functools.reduce(jnp.add, term) * scale


def stack(ss: Arrays, cv: Arrays, elevations: Arrays, scales: np.ndarray, measure: str, edges: bool) -> Array:
    """(planes, cols, cols) float32: `stack[s, i, j]`, snapshot column i against current column j
    under r' / r = scales[s] (module docstring). The edge images are taken first and magnified
    after (as the authors do), so that magnification stretches an edge without weakening it."""
    ss, cv = prepare(jnp.asarray(ss, jnp.float32), edges), prepare(jnp.asarray(cv, jnp.float32), edges)
    elevations = jnp.asarray(elevations, jnp.float32)
    if edges:  # an edge row lies between its two rows
        elevations = 0.5 * (elevations[1:] + elevations[:-1])
    a = [magnify(ss, elevations, jnp.float32(1.0 / s)) if s < 1.0 else ss for s in scales]
    b = [magnify(cv, elevations, jnp.float32(s)) if s > 1.0 else cv for s in scales]
    return column_distances(jnp.stack(a), jnp.stack(b), measure)


def inverted(stk: Arrays) -> Array:
    """The stack with the two images' roles swapped (the current view as snapshot): plane s of
    the inverse compares at 1 / sigma_s, which is plane S - 1 - s of symmetric scale factors."""
    return jnp.swapaxes(stk[::-1], 1, 2)


def skewed(plane: Arrays) -> Array:
    """(w, w) -> (w, w): out[i, delta] = plane[i, (i + delta) mod w], by reshapes only (each row of
    the doubled plane read from one place further on)."""
    w = plane.shape[-1]
    flat = jnp.concatenate([plane, plane], 1).reshape(-1)
    return jnp.pad(flat, (0, w)).reshape(w, 2 * w + 1)[:, :w]


def arranged(stk: Arrays, n_alpha: int, n_psi: int, doubled: bool = False) -> Array:
    """The stack in the search's layout (docs/model.md §4.7 "How it is fast"):
    (planes, step_psi, 2 n_psi, step_alpha, n_alpha), entry [s, ry, t, rx, q] the distance of snapshot
    column theta = q step_alpha + rx and current column theta + delta, delta = ((-t) mod n_psi)
    step_psi + ry. A template entry (x, y) reads, for all n_psi x n_alpha hypotheses at once, the
    contiguous block [plane, ry(y), t0(y) : t0 + n_psi, rx(x), :] (its alpha axis rolled by
    qx(x); `doubled`: the q axis twice, 2 n_alpha, so that a block starting at qx is in the alpha
    frame)."""
    s, w = stk.shape[0], stk.shape[-1]
    sa, sp = w // n_alpha, w // n_psi
    e = jax.vmap(skewed)(stk).reshape(s, n_alpha, sa, n_psi, sp)  # [s, q, rx, qd, ry]
    e = e.transpose(0, 4, 3, 2, 1)  # [s, ry, qd, rx, q]
    rev = jnp.roll(e[:, :, ::-1], 1, axis=2)  # qd = (-t) mod n_psi for t = 0 .. n_psi - 1
    out = jnp.concatenate([rev, rev], 2)
    return jnp.concatenate([out, out], 4) if doubled else out
