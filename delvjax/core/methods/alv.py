"""ALV, average landmark vector (Lambrinos et al. 2000; thesis Eqs 3.11-3.12; docs/model.md §4.1)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..geometry import angle_of, safe_norm, unit, wrap
from ..sensing import UnitMove
from .base import HomingMethod
from .heading import Compass, HeadingSource


class ALV(HomingMethod):
    """Average landmark vector (Lambrinos et al. 2000; thesis Eqs 3.11-3.12; docs/model.md §4.1).

    H = sum_j u(b_j(x)) - sum_i u(b_i(home)) with world-frame bearings (bearing + heading estimate).
    """

    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        here = jnp.sum(jnp.where(view.end.valid[:, None], unit(view.end.bearing + heading), 0.0), axis=0)
        there = jnp.sum(jnp.where(home.start.valid[:, None], unit(home.start.bearing), 0.0), axis=0)
        h = here - there
        valid = jnp.any(view.end.valid) & jnp.any(home.start.valid) & (safe_norm(h) > 0)
        return jnp.where(valid, wrap(angle_of(h) - heading), jnp.nan), valid

    def reads_gray(self, channel: str) -> bool:
        return self.heading.reads_gray
