"""A colour world and two camera models (docs/images.md §1-2).

A `World` is vertical cylinders and boxes standing on a floor inside a walled, textured arena,
lit by one directional light; every field is an array (a pytree leaf), so worlds of one shape
share a compiled renderer and a gradient can reach any of them. Units: cm and radians; colours
RGB in [0, 1].
"""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
import numpy as np
from jax import Array

RED = (0.80, 0.10, 0.10)  # the landmarks of the robot world and of every docs/model.md environment


class World(eqx.Module):
    """cylinders: (C, 4) [x, y, r, height]; cylinder_rgb: (C, 3); boxes: (K, 5) [xmin, ymin, xmax,
    ymax, height]; box_rgb: (K, 3); arena: (4,) [xmin, ymin, xmax, ymax]; wall_height: cm;
    floor_rgb, ceiling_rgb: (3,); light: (3,) unit vector towards the light (z up); ambient: the
    unlit share of every surface's colour; texture: contrast of the wall texture (0: plain grey).
    An object of height 0 is padding: it is never hit (fixed shapes, docs/images.md §1)."""

    cylinders: Array
    cylinder_rgb: Array
    boxes: Array
    box_rgb: Array
    arena: Array
    wall_height: Array
    floor_rgb: Array
    ceiling_rgb: Array
    light: Array
    ambient: Array
    texture: Array


def make_world(
    cylinders=(),
    cylinder_rgb=(),
    boxes=(),
    box_rgb=(),
    arena=(0.0, 0.0, 1000.0, 1000.0),
    wall_height: float = 120.0,
    floor_rgb=(0.45, 0.43, 0.40),
    ceiling_rgb=(0.92, 0.92, 0.95),
    light_azimuth_deg: float = 45.0,
    light_elevation_deg: float = 50.0,
    ambient: float = 0.45,
    texture: float = 1.0,
) -> World:
    """A `World` from plain numbers (an empty list of cylinders or boxes becomes one padding row)."""

    def table(rows, width: int) -> np.ndarray:
        a = np.asarray(rows, np.float32).reshape(-1, width)
        return a if a.shape[0] else np.zeros((1, width), np.float32)

    az, el = np.radians(light_azimuth_deg), np.radians(light_elevation_deg)
    light = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], np.float32)
    f = lambda v: jnp.asarray(np.asarray(v, np.float32))  # noqa: E731
    return World(
        cylinders=f(table(cylinders, 4)),
        cylinder_rgb=f(table(cylinder_rgb, 3)),
        boxes=f(table(boxes, 5)),
        box_rgb=f(table(box_rgb, 3)),
        arena=f(arena),
        wall_height=f(wall_height),
        floor_rgb=f(floor_rgb),
        ceiling_rgb=f(ceiling_rgb),
        light=f(light),
        ambient=f(ambient),
        texture=f(texture),
    )


class Camera(eqx.Module):
    """An equirectangular panoramic camera (docs/images.md §2).

    height: lens height above the floor, cm (thesis §4.4.1: 25 cm on the ROOMBA); the image spans
    elevations `elev_top_deg` (row 0) to `elev_bottom_deg` (last row) in `rows` equal steps (row
    centres) and the full circle in `cols` columns. Column j looks along heading + 2 pi j / cols
    (counter-clockwise, the ring convention of docs/model.md §2.2; files store the mirror image,
    docs/images.md §4).
    """

    height: float = 25.0
    elev_top_deg: float = 30.0
    elev_bottom_deg: float = -30.0
    rows: int = eqx.field(static=True, default=60)
    cols: int = eqx.field(static=True, default=360)

    def elevations(self) -> Array:
        """(rows,) elevation of every row centre, rad."""
        step = (self.elev_top_deg - self.elev_bottom_deg) / self.rows
        return jnp.radians(self.elev_top_deg - step * (jnp.arange(self.rows) + 0.5))

    def azimuths(self) -> Array:
        """(cols,) agent-frame azimuth of every column, rad."""
        return 2.0 * jnp.pi * jnp.arange(self.cols) / self.cols


class Catadioptric(eqx.Module):
    """The donut image of a camera looking at a mirror (docs/images.md §2): an equiangular model.

    The image is `size` x `size` pixels around the centre ((size - 1) / 2, (size - 1) / 2). A
    pixel at radius rho (pixels) sees elevation linear in rho, `elev_inner_deg` at
    rho = inner * size / 2 and `elev_outer_deg` at rho = outer * size / 2; outside that annulus the
    image is black. Its angle theta (counter-clockwise from the image's +x, image up = +y) sees
    agent-frame azimuth theta - pi / 2: the robot's forward points up in the image.
    """

    height: float = 25.0
    inner: float = 0.2
    outer: float = 0.95
    elev_inner_deg: float = -30.0
    elev_outer_deg: float = 30.0
    size: int = eqx.field(static=True, default=240)

    def radius_px(self, elevation: Array) -> Array:
        """Radius (pixels) at which `elevation` (rad) is imaged."""
        frac = (jnp.degrees(elevation) - self.elev_inner_deg) / (self.elev_outer_deg - self.elev_inner_deg)
        return (self.inner + frac * (self.outer - self.inner)) * self.size / 2.0

    def pixel_rays(self) -> tuple[Array, Array, Array]:
        """(azimuth (S, S) agent frame, elevation (S, S), inside (S, S) bool) of every pixel."""
        c = (self.size - 1) / 2.0
        rows, cols = jnp.meshgrid(jnp.arange(self.size), jnp.arange(self.size), indexing="ij")
        dx, dy = cols - c, c - rows
        rho = jnp.hypot(dx, dy) / (self.size / 2.0)
        frac = (rho - self.inner) / (self.outer - self.inner)
        elevation = jnp.radians(self.elev_inner_deg + frac * (self.elev_outer_deg - self.elev_inner_deg))
        inside = (rho >= self.inner) & (rho <= self.outer)
        return jnp.arctan2(dy, dx) - jnp.pi / 2, elevation, inside
