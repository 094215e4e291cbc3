"""A route as a polyline (docs/familiarity.md §3): the distance of a point to it, the nearest point on
it and the route's direction there; the route's cumulative length. Pure array programs for one point,
vmapped by the callers."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..geometry import angle_of


class Route(eqx.Module):
    """positions: (N, 2) cm, the route's images in order (N >= 2; the last is the goal); headings: (N,)
    rad, the world heading of every image's column 0 (the direction of travel where the route was
    walked facing forward)."""

    positions: Array
    headings: Array

    def segments(self) -> tuple[Array, Array]:
        """(starts (N-1, 2), vectors (N-1, 2)) of the polyline's segments."""
        return self.positions[:-1], self.positions[1:] - self.positions[:-1]

    def length(self) -> Array:
        """Total length of the polyline, cm."""
        _, v = self.segments()
        return jnp.sum(jnp.sqrt(jnp.sum(v * v, -1)))


def nearest_on_route(route: Route, x: ArrayLike) -> tuple[Array, Array, Array, Array]:
    """(distance cm, nearest point (2,), direction of the route there rad, index of the segment) for a
    point x (2,): the orthogonal projection on the nearest segment, clipped to its ends."""
    a, v = route.segments()
    vv = jnp.maximum(jnp.sum(v * v, -1), 1e-12)
    t = jnp.clip(jnp.sum((x - a) * v, -1) / vv, 0.0, 1.0)
    p = a + t[:, None] * v
    d2 = jnp.sum((x - p) ** 2, -1)
    i = jnp.argmin(d2)
    return jnp.sqrt(d2[i]), p[i], angle_of(v[i]), i


def nearest_image(route: Route, x: ArrayLike) -> Array:
    """Index of the route image nearest to x (2,)."""
    return jnp.argmin(jnp.sum((route.positions - x) ** 2, -1))
