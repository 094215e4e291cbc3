"""Angles and planar vectors (docs/model.md §1: cm, radians, counter-clockwise, 0 = +x)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

TWO_PI = 2.0 * jnp.pi


def wrap(a: Array) -> Array:
    """Map angles to (-pi, pi] (docs/model.md §1)."""
    return jnp.pi - jnp.mod(jnp.pi - a, TWO_PI)


def wrap_positive(a: Array) -> Array:
    """Map angles to [0, 2*pi) (float32 `mod` of a tiny negative angle rounds to 2*pi: folded to 0)."""
    r = jnp.mod(a, TWO_PI)
    return jnp.where(r >= TWO_PI, 0.0, r)


def unit(angle: Array) -> Array:
    """Unit vector(s) at `angle`; shape (..., 2)."""
    return jnp.stack([jnp.cos(angle), jnp.sin(angle)], axis=-1)


def rotate(v: Array, angle: Array) -> Array:
    """Rotate vectors `v` (..., 2) counter-clockwise by `angle`."""
    c, s = jnp.cos(angle), jnp.sin(angle)
    return jnp.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def angle_of(v: Array) -> Array:
    """Angle of vectors (..., 2) in (-pi, pi]."""
    return jnp.arctan2(v[..., 1], v[..., 0])


def safe_norm(v: Array) -> Array:
    """Euclidean norm over the last axis whose gradient is finite at 0."""
    sq = jnp.sum(v * v, axis=-1)
    positive = sq > 0
    return jnp.where(positive, jnp.sqrt(jnp.where(positive, sq, 1.0)), 0.0)
