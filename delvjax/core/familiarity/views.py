"""The views a familiarity model reads (docs/familiarity.md §3.1): a gray panorama rendered at a pose
(`core/images/render.py`) at `factor` times the view's resolution, 8-bit like a camera's, turned by
whole rendered columns and block-averaged down to (H, W). Values are on the 8-bit scale (0-255)."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..geometry import TWO_PI
from ..images.render import panorama
from ..images.world import Camera, World
from .ridf import rolled


class ViewCamera(eqx.Module):
    """camera: the rendering camera (rows = H factor, cols = W factor); factor: rendered pixels per view
    pixel along each axis. A turn must be a whole number of rendered columns (360 / cols deg)."""

    camera: Camera
    factor: int = eqx.field(static=True, default=4)

    def shape(self) -> tuple[int, int]:
        """(H, W) of a view."""
        return self.camera.rows // self.factor, self.camera.cols // self.factor

    def column_deg(self) -> float:
        """Width of a rendered column, deg."""
        return 360.0 / self.camera.cols


def view_camera(rows: int = 10, cols: int = 90, factor: int = 4, **camera) -> ViewCamera:
    """A `ViewCamera` for (rows, cols) views rendered at `factor` x; `camera`: `Camera` fields (height,
    elevations)."""
    return ViewCamera(Camera(rows=rows * factor, cols=cols * factor, **camera), factor)


def downsample(images: ArrayLike, factor: int) -> Array:
    """Block means of `factor` x `factor` pixels over the last two axes."""
    *lead, h, w = images.shape
    return jnp.mean(images.reshape(*lead, h // factor, factor, w // factor, factor), (-3, -1))


def gray(world: World, camera: Camera, pos: ArrayLike, heading: ArrayLike) -> Array:
    """(rows, cols) 8-bit luminance (Rec. 601, rounded) of the panorama at `pos` facing `heading`, as float."""
    lum = panorama(world, camera, pos, heading) @ jnp.array([0.299, 0.587, 0.114], jnp.float32)
    return jnp.round(jnp.clip(lum, 0.0, 1.0) * 255.0)


def turn_columns(turns: ArrayLike, cols: int) -> Array:
    """Whole columns of a `cols`-column panorama in every turn (rad, counter-clockwise)."""
    return jnp.round(jnp.asarray(turns) / (TWO_PI / cols)).astype(jnp.int32)


def views_at(world: World, vc: ViewCamera, pos: ArrayLike, heading: ArrayLike, turns: ArrayLike) -> Array:
    """(R, H, W) the views after every turn (R,) rad from `heading` at `pos`: one rendering, rolled (a
    left turn by k columns rolls the counter-clockwise panorama left by k) and block-averaged."""
    g = gray(world, vc.camera, pos, heading)
    return downsample(rolled(g, -turn_columns(turns, vc.camera.cols)), vc.factor)
