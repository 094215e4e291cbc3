"""ALV, average landmark vector (Lambrinos et al. 2000; thesis Eqs 3.11-3.12; docs/model.md §4.1)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..config import Config
from ..geometry import angle_of, safe_norm, unit, wrap
from ..sensing import UnitMove


def direction_with_heading(home: UnitMove, view: UnitMove, config: Config, heading: Array) -> tuple[Array, Array]:
    """H = sum_j u(b_j(x)) - sum_i u(b_i(home)) with world-frame bearings (bearing + heading estimate)."""
    here = jnp.sum(jnp.where(view.end.valid[:, None], unit(view.end.bearing + heading), 0.0), axis=0)
    there = jnp.sum(jnp.where(home.start.valid[:, None], unit(home.start.bearing), 0.0), axis=0)
    h = here - there
    valid = jnp.any(view.end.valid) & jnp.any(home.start.valid) & (safe_norm(h) > 0)
    return jnp.where(valid, wrap(angle_of(h) - heading), jnp.nan), valid
