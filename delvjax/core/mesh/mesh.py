"""A world of coloured triangles over a flat ground (docs/mesh.md §1): `Mesh` holds T triangles (cm, z up),
their colours and a validity mask (padding rows never hit), with the ground's and the sky's colours."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike


class Mesh(eqx.Module):
    """vertices: (T, 3, 3) cm, triangle t's corners in rows (x, y, z; z up, the ground at z = 0); rgb: (T, 3)
    in [0, 1]; valid: (T,) False for padding; ground_rgb, sky_rgb: (3,) what a ray that meets no triangle sees
    below and above the horizon (the ground is the plane z = 0)."""

    vertices: Array
    rgb: Array
    valid: Array
    ground_rgb: Array
    sky_rgb: Array

    @property
    def n_triangles(self) -> int:
        return int(self.vertices.shape[0])


def make_mesh(
    vertices: ArrayLike,
    rgb: ArrayLike | None = None,
    valid: ArrayLike | None = None,
    ground_rgb: ArrayLike | tuple = (0.0, 0.0, 0.0),
    sky_rgb: ArrayLike | tuple = (0.0, 0.0, 1.0),
) -> Mesh:
    """A `Mesh` from (T, 3, 3) vertices (cm), colours (T, 3) (default gray 0.5) and validity (default all)."""
    v = jnp.asarray(vertices, jnp.float32).reshape(-1, 3, 3)
    n = v.shape[0]
    c = jnp.full((n, 3), 0.5, jnp.float32) if rgb is None else jnp.broadcast_to(jnp.asarray(rgb, jnp.float32), (n, 3))
    ok = jnp.ones(n, bool) if valid is None else jnp.asarray(valid, bool)
    return Mesh(v, c, ok, jnp.asarray(ground_rgb, jnp.float32), jnp.asarray(sky_rgb, jnp.float32))
