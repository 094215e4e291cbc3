"""Landmark distances from a unit movement, quantization, landmark vectors (thesis §3.2.1-3.2.3).

docs/model.md §3.1: a C-bearing beta seen in P's frame is beta' = beta + psi_hat; its partner is
the nearest P-blob theta; delta = wrap(beta' - theta); by the sine law in P-L-C

    R_C = d_hat sin(theta) / sin(delta)            (Eq 3.2, psi = 0)
    R_P = d_hat sin(theta + delta) / sin(delta)    (Eq 3.3, typo corrected)
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import jax.numpy as jnp
from jax import Array

from .geometry import unit, wrap
from .search import first_argmin
from .sensing import UnitMove
from .types import BlobFlags, Blobs, BlobVectors, Real


@runtime_checkable
class DistanceSettings(Protocol):
    """What distance estimation reads (docs/model.md §3.1-3.2): the cap r_max (cm), quantization
    levels Q (0 = continuous) and scale a (cm). `DELV` has these fields."""

    r_max: Array | float
    levels: Array | int
    scale: Array | float


SIN_EPS = 1e-9


TIE_RAD = 1e-5  # partners closer than this in |parallax| tie (bearings sit on a half-pixel lattice)


def _nearest(parallax: Array, other_valid: Array) -> tuple[Array, Array]:
    """Row-wise partner with the smallest |parallax| among valid columns: (index, parallax).

    Blob bearings are multiples of half a pixel, so a C-blob exactly midway between two
    P-blobs is common; float32 rounding must not decide it: differences within `TIE_RAD`
    are ties, and the first partner in bearing order wins (as in exact arithmetic).
    """
    score = jnp.where(other_valid[None, :], jnp.abs(parallax), jnp.inf)
    best = jnp.min(score, axis=-1, keepdims=True)
    idx = first_argmin(jnp.where(score <= best + TIE_RAD, 0.0, 1.0), axis=-1)
    return idx, jnp.take_along_axis(parallax, idx[:, None], axis=-1)[:, 0]


def _guard(r: Array, sin_delta: Array, r_max: Real) -> Array:
    """docs/model.md §3.1: negative, non-finite, > r_max or |sin(delta)| < 1e-9 -> r_max. "Negative"
    is read as "not positive": a landmark on the line of the move gives R = 0 (no triangle)."""
    bad = (jnp.abs(sin_delta) < SIN_EPS) | ~jnp.isfinite(r) | (r <= 0) | (r > r_max)
    return jnp.where(bad, r_max, r)


def _sin_on_lattice(a: Array) -> Array:
    """sin(a), exactly 0 for a bearing on the line of the move (0 or pi up to float32 rounding:
    float32 sin(pi) is -8.7e-8, which would otherwise give a tiny positive distance)."""
    s = jnp.sin(a)
    return jnp.where(jnp.abs(s) < 1e-6, 0.0, s)


def end_distances(move: UnitMove, settings: DistanceSettings) -> Blobs:
    """R_C for every end (C) blob, Eq 3.2; (B,) cm, r_max where undefined."""
    beta = move.end.bearing + move.psi_hat
    theta_all = move.start.bearing
    idx, delta = _nearest(wrap(beta[:, None] - theta_all[None, :]), move.start.valid)
    theta = theta_all[idx]
    s = jnp.sin(delta)
    r = move.d_hat * _sin_on_lattice(theta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
    r = _guard(r, s, settings.r_max)
    return jnp.where(jnp.any(move.start.valid), r, settings.r_max)


def start_distances(move: UnitMove, settings: DistanceSettings) -> Blobs:
    """R_P for every start (P) blob, Eq 3.3 (each P-blob takes the nearest C-blob); (B,) cm."""
    theta = move.start.bearing
    beta = move.end.bearing + move.psi_hat
    _, delta = _nearest(wrap(beta[None, :] - theta[:, None]), move.end.valid)
    s = jnp.sin(delta)
    r = move.d_hat * _sin_on_lattice(theta + delta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
    r = _guard(r, s, settings.r_max)
    return jnp.where(jnp.any(move.end.valid), r, settings.r_max)


def quantize(r: Blobs, levels: int | Array | None, scale: float | Array) -> Blobs:
    """Eq 3.17 / docs/model.md §3.2: R -> a * clip(ceil(R Q / a), 1, Q) / Q; `levels` 0 (or None) keeps R.

    `levels` may be traced: continuous and quantized distances share one compiled program."""
    if levels is None:
        return r
    q = jnp.maximum(levels, 1)
    quantized = scale * jnp.clip(jnp.ceil(r * q / scale), 1, q) / q
    return jnp.where(jnp.asarray(levels) > 0, quantized, r)


def reference_vectors(home: UnitMove, settings: DistanceSettings) -> tuple[BlobVectors, BlobFlags]:
    """Reference map V^R_i = R_P,i (cos theta_i, sin theta_i), home frame (docs/model.md §3.3): ((B, 2), (B,))."""
    r = quantize(start_distances(home, settings), settings.levels, settings.scale)
    return r[:, None] * unit(home.start.bearing), home.start.valid


def current_vectors(view: UnitMove, settings: DistanceSettings) -> tuple[BlobVectors, BlobFlags]:
    """Current vectors V_j = R_C,j (cos beta_j, sin beta_j), agent frame at C (docs/model.md §3.3): ((B, 2), (B,))."""
    r = quantize(end_distances(view, settings), settings.levels, settings.scale)
    return r[:, None] * unit(view.end.bearing), view.end.valid
