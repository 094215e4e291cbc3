"""Landmark blobs straight from the cylinders (docs/model.md §2.2-2.4), without the ring image.

`blobs_of_cylinders` gives the blobs `sensing.blob_runs(sensing.ray_hits(...))` extracts from a
rendered ring, at a fraction of its cost: a cylinder at agent-frame bearing phi, distance D and
radius r is hit by exactly the pixel rays within asin(r / D) of phi, a contiguous run of pixels
whose two ends are found in closed form and then confirmed with the renderer's own per-pixel
test (so a ray that grazes the rim counts as the renderer counts it); the blobs are the runs of
the union of these per-cylinder runs. Written for ONE viewpoint; callers `vmap` it.
"""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np
from jax import Array

from .geometry import rotate


def pixel_directions(n_pix: int) -> np.ndarray:
    """Agent-frame unit vectors of the n_pix pixel rays (a trace-time constant), (n_pix, 2)."""
    a = 2.0 * np.pi * np.arange(n_pix) / n_pix
    return np.stack([np.cos(a), np.sin(a)], axis=-1).astype(np.float32)


def cylinder_offsets(landmarks: Array, origin: Array, heading: Array) -> tuple[Array, Array]:
    """Cylinder centres in the agent frame (L, 2) and |offset|^2 - r^2 (L,): what a pixel ray is tested
    against (`sensing.ray_hits`, and `_pixel_hits` here); c2 <= 0 where the viewpoint is inside."""
    rel = rotate(landmarks[:, :2] - origin, -heading)
    return rel, jnp.sum(rel * rel, axis=-1) - landmarks[:, 2] ** 2


def _pixel_hits(rel: Array, c2: Array, dirs: Array, j: Array) -> Array:
    """The renderer's test (`sensing.ray_hits`) of pixel j (any integer, taken mod n) against each cylinder, (L,)."""
    d = dirs[jnp.mod(j, dirs.shape[0])]  # (L, 2)
    b = jnp.diagonal(d @ rel.T)
    return (b > 0) & (b * b >= c2)


def cylinder_runs(
    landmarks: Array, visible: Array, origin: Array, heading: Array, n_pix: int
) -> tuple[Array, Array, Array]:
    """Per cylinder, the run of pixels it covers: (first pixel in [0, n), length in pixels, active).

    A cylinder containing the viewpoint covers the whole ring (first 0, length n); one that no
    ray hits (narrower than a pixel's spacing) is inactive.
    """
    dirs = jnp.asarray(pixel_directions(n_pix))
    rel, c2 = cylinder_offsets(landmarks, origin, heading)
    r = landmarks[:, 2]
    inside = c2 <= 0
    phi = jnp.arctan2(rel[:, 1], rel[:, 0])
    beta = jnp.arcsin(jnp.clip(r / jnp.sqrt(jnp.maximum(c2 + r**2, 1e-30)), 0.0, 1.0))
    step = np.float32(2.0 * np.pi / n_pix)
    s0 = jnp.ceil((phi - beta) / step).astype(jnp.int32)
    e0 = jnp.floor((phi + beta) / step).astype(jnp.int32)
    hit = lambda j: _pixel_hits(rel, c2, dirs, j)  # noqa: E731
    # the closed form is off by at most one pixel at a rim the renderer's float test decides otherwise
    first = jnp.where(hit(s0 - 1), s0 - 1, jnp.where(hit(s0), s0, s0 + 1))
    last = jnp.where(hit(e0 + 1), e0 + 1, jnp.where(hit(e0), e0, e0 - 1))
    length = last - first + 1
    active = visible & (inside | (length >= 1))
    first = jnp.where(inside, 0, jnp.mod(first, n_pix))
    length = jnp.where(inside, n_pix, jnp.clip(length, 0, n_pix))
    return first, length, active


def blobs_of_cylinders(
    landmarks: Array, visible: Array, origin: Array, heading: Array, n_pix: int
) -> tuple[Array, Array, Array]:
    """The blobs of the ring at `origin` with `heading` (docs/model.md §2.4): (bearing (L,), width (L,),
    valid (L,)) in the order of `sensing.blob_runs` before its sort (call `sensing.sort_blobs` after).

    A blob is a maximal circular run of covered pixels: it starts at a cylinder's first pixel whose
    left neighbour no cylinder covers, and ends at the nearest cylinder end ahead of it whose right
    neighbour no cylinder covers. Bearing and width use blob_runs' integer formulas, so the two
    agree wherever the covered pixels agree. Every pixel covered: one blob at 0 of width 2 pi.
    """
    n = n_pix
    first, length, active = cylinder_runs(landmarks, visible, origin, heading, n)
    idx = jnp.arange(first.shape[0])

    def covered(p: Array) -> Array:
        """Whether pixels p (any shape) lie in some active run."""
        return jnp.any(active & (jnp.mod(p[..., None] - first, n) < length), axis=-1)

    last = jnp.mod(first + length - 1, n)
    duplicate = jnp.any((idx[None, :] < idx[:, None]) & active[None, :] & (first[None, :] == first[:, None]), axis=1)
    starts = active & ~covered(jnp.mod(first - 1, n)) & ~duplicate
    ends = active & ~covered(jnp.mod(last + 1, n))
    ahead = jnp.where(ends[None, :], jnp.mod(last[None, :] - first[:, None], n), n)  # (start l, end m)
    run = jnp.min(ahead, axis=1)  # pixels from the blob's first to its last pixel
    half_pixels = jnp.mod(2 * first + run, 2 * n)
    bearing = half_pixels.astype(jnp.float32) * jnp.float32(np.pi / n)
    width = (run + 1).astype(jnp.float32) * jnp.float32(2.0 * np.pi / n)
    all_on = jnp.any(active) & ~jnp.any(starts)
    bearing = jnp.where(all_on | ~starts, 0.0, bearing)
    width = jnp.where(all_on, jnp.float32(2.0 * np.pi), jnp.where(starts, width, 0.0))
    valid = jnp.where(all_on, idx == 0, starts)
    return bearing, width, valid
