"""The views a familiarity model reads in a triangle-mesh world (docs/mesh.md §6): the green channel of a 360 deg
panorama (`core/mesh/render.py`) over the ant eye's band of elevation (-15 to 60 deg, Ardin et al. 2016), 8-bit
like a camera's, rendered at `factor` times the view's resolution with the eye `height` cm above the ground,
turned by whole rendered columns and block-averaged down to (H, W), as `views.py` does in a colour world."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..images import to_uint8
from ..mesh.eye import Eye
from ..mesh.mesh import Mesh
from ..mesh.render import mesh_panorama
from .ridf import rolled
from .views import downsample, turn_columns

ANT_BAND_DEG = (60.0, -15.0)  # elevation of the top and bottom edge of the ant eye (Ardin et al. 2016), deg


class MeshCamera(eqx.Module):
    """eye: the rendering eye (360 deg wide, rows = H factor, cols = W factor); factor: rendered pixels per
    view pixel along each axis; height: cm of the eye above the ground."""

    eye: Eye
    factor: int = eqx.field(static=True, default=2)
    height: float = eqx.field(static=True, default=1.0)

    def shape(self) -> tuple[int, int]:
        """(H, W) of a view."""
        return self.eye.rows // self.factor, self.eye.cols // self.factor

    def column_deg(self) -> float:
        """Width of a rendered column, deg."""
        return 360.0 / self.eye.cols


def mesh_camera(rows: int = 19, cols: int = 90, factor: int = 2, height: float = 1.0) -> MeshCamera:
    """A `MeshCamera` for (rows, cols) views over the ant eye's band of elevation, rendered at `factor` x."""
    top, bottom = ANT_BAND_DEG
    eye = Eye(rows=rows * factor, cols=cols * factor, width_deg=360.0, elev_top_deg=top, elev_bottom_deg=bottom)
    return MeshCamera(eye, factor, float(height))


def mesh_green(mesh: Mesh, eye: Eye, pose: ArrayLike) -> Array:
    """(rows, cols) the 8-bit green channel (`to_uint8`, as float) of the panorama at `pose` (x, y, z, heading)."""
    return to_uint8(mesh_panorama(mesh, eye, pose)[..., 1]).astype(jnp.float32)


def mesh_views_at(mesh: Mesh, mc: MeshCamera, pos: ArrayLike, heading: ArrayLike, turns: ArrayLike) -> Array:
    """(R, H, W) the views after every turn (R,) rad from `heading` at `pos` (2,): one rendering, rolled (a left
    turn by k columns rolls the counter-clockwise panorama left by k) and block-averaged."""
    pos = jnp.asarray(pos, jnp.float32)
    pose = jnp.stack([pos[0], pos[1], jnp.float32(mc.height), jnp.asarray(heading, jnp.float32)])
    g = mesh_green(mesh, mc.eye, pose)
    return downsample(rolled(g, -turn_columns(turns, mc.eye.cols)), mc.factor)
