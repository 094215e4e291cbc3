"""The docs/model.md §5 grid: where a vector map or catchment is evaluated. `Grid` holds its cell
`spacing`, the `clearance` from the landmarks and the release heading; a `VectorMap` and a `Catchment`
carry the `Grid` they were computed on. Its own module so that maps (`core/maps.py`) and rollouts
(`core/rollouts/config.py`, beside `Rules`) both hold it (docs/architecture.md "How a setting travels")."""

from __future__ import annotations

import math

import equinox as eqx
import numpy as np

from .checks import angle_deg, non_negative, positive

SPACING = 25.0  # cm, grid spacing (docs/model.md §5: 40 x 40 in the 1000 cm arena)
CLEARANCE = 10.0  # cm, grid points within r + clearance of a landmark are dropped (§5)


def _heading(value: float | None) -> float | None:
    return None if value is None else angle_deg(value, "heading_deg")


class Grid(eqx.Module):
    """The docs/model.md §5 grid: cell `spacing` and `clearance` from the landmarks (cm); a fixed
    release heading at every point (`heading_deg`, degrees), or None for a random heading per point
    from the seed. Also the release clearance and heading of the success rate and trajectories."""

    spacing: float = eqx.field(default=SPACING, converter=lambda v: positive(v, "spacing"))
    clearance: float = eqx.field(default=CLEARANCE, converter=lambda v: non_negative(v, "clearance"))
    heading_deg: float | None = eqx.field(default=None, converter=_heading)

    def describe(self) -> str:
        """The grid as a progress line names it: "spacing 25 cm"."""
        return f"spacing {self.spacing:g} cm"

    @property
    def heading(self) -> float | None:
        """The fixed release heading in radians, or None (random per point from the seed)."""
        return None if self.heading_deg is None else math.radians(self.heading_deg)


def grid_points(arena, spacing: float) -> np.ndarray:
    """Centres of square cells of side `spacing` tiling the arena (docs/model.md §5), row-major from (xmin, ymin)."""
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(arena))
    xs = np.arange(xmin + spacing / 2, xmax, spacing, dtype=np.float64)
    ys = np.arange(ymin + spacing / 2, ymax, spacing, dtype=np.float64)
    gx, gy = np.meshgrid(xs[xs < xmax], ys[ys < ymax])
    return np.stack([gx.ravel(), gy.ravel()], axis=-1).astype(np.float32)
