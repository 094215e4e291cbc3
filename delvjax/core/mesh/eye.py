"""An equirectangular eye (docs/mesh.md §2): `cols` columns over `width_deg` of azimuth centred on the heading
and `rows` rows from `elev_top_deg` (row 0) to `elev_bottom_deg`, at pixel centres. Columns run
counter-clockwise, as every delvjax panorama (docs/images.md §2): column 0 looks `width_deg` / 2 to the right
of the heading (for 360 deg, column j looks along heading + 360 j / cols, as `Camera`). The eye turns by
heading (about z), then pitch (nose up, about the eye's y), then roll (about its x)."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike


class Eye(eqx.Module):
    """rows x cols pixels over width_deg x (elev_top_deg - elev_bottom_deg)."""

    rows: int = eqx.field(static=True, default=90)
    cols: int = eqx.field(static=True, default=360)
    width_deg: float = eqx.field(static=True, default=360.0)
    elev_top_deg: float = eqx.field(static=True, default=45.0)
    elev_bottom_deg: float = eqx.field(static=True, default=-45.0)

    def azimuths(self) -> Array:
        """(cols,) azimuth of every column centre relative to the heading, rad (counter-clockwise)."""
        if self.width_deg >= 360.0:
            return jnp.radians(360.0 * jnp.arange(self.cols, dtype=jnp.float32) / self.cols)
        step = self.width_deg / self.cols
        return jnp.radians(-self.width_deg / 2 + step * (jnp.arange(self.cols, dtype=jnp.float32) + 0.5))

    def elevations(self) -> Array:
        """(rows,) elevation of every row centre, rad (row 0 the highest)."""
        step = (self.elev_top_deg - self.elev_bottom_deg) / self.rows
        return jnp.radians(self.elev_top_deg - step * (jnp.arange(self.rows, dtype=jnp.float32) + 0.5))

    @property
    def cyclic(self) -> bool:
        """Whether the columns close the circle (column cols is column 0)."""
        return self.width_deg >= 360.0

    def fractional_pixel(self, azimuth: ArrayLike, elevation: ArrayLike) -> tuple[Array, Array]:
        """(row, col) as floats of eye-frame directions (rad): integers at pixel centres; the column of a cyclic
        eye modulo nothing (the caller wraps), of a partial one outside [-0.5, cols - 0.5] out of view."""
        if self.cyclic:
            col = jnp.asarray(azimuth) * self.cols / (2 * jnp.pi)
        else:
            col = (jnp.degrees(azimuth) + self.width_deg / 2) * self.cols / self.width_deg - 0.5
        row = (self.elev_top_deg - jnp.degrees(elevation)) * self.rows / (
            self.elev_top_deg - self.elev_bottom_deg
        ) - 0.5
        return row, col

    def rays(self, angles: ArrayLike) -> Array:
        """(rows, cols, 3) unit ray directions in the world for angles (heading[, pitch, roll]) rad."""
        a, e = self.azimuths()[None, :], self.elevations()[:, None]
        local = jnp.stack(jnp.broadcast_arrays(jnp.cos(e) * jnp.cos(a), jnp.cos(e) * jnp.sin(a), jnp.sin(e)), -1)
        return local @ self.orientation(angles).T

    def orientation(self, angles: ArrayLike) -> Array:
        """(3, 3) eye -> world rotation of angles (heading[, pitch, roll]) rad (`rotation`)."""
        angles = jnp.concatenate([jnp.asarray(angles, jnp.float32).reshape(-1), jnp.zeros(2, jnp.float32)])
        return rotation(angles[0], angles[1], angles[2])


def rotation(heading: ArrayLike, pitch: ArrayLike, roll: ArrayLike) -> Array:
    """(3, 3) eye -> world: R_z(heading) R_y(-pitch) R_x(roll) (pitch > 0 tilts the view up)."""
    ch, sh = jnp.cos(heading), jnp.sin(heading)
    cp, sp = jnp.cos(pitch), jnp.sin(pitch)
    cr, sr = jnp.cos(roll), jnp.sin(roll)
    rz = jnp.array([[ch, -sh, 0.0], [sh, ch, 0.0], [0.0, 0.0, 1.0]])
    ry = jnp.array([[cp, 0.0, -sp], [0.0, 1.0, 0.0], [sp, 0.0, cp]])
    rx = jnp.array([[1.0, 0.0, 0.0], [0.0, cr, -sr], [0.0, sr, cr]])
    return rz @ ry @ rx


ANT_EYE = Eye(rows=19, cols=74, width_deg=296.0, elev_top_deg=60.0, elev_bottom_deg=-15.0)  # Ardin et al. 2016
