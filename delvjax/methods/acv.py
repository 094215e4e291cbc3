"""ACV, average correction vector (Hong et al. 1992, Weber et al. 1999; thesis Eq 5.2; docs/model.md §4.2)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..config import Config
from ..search import first_argmin
from ..geometry import angle_of, safe_norm, unit, wrap
from ..sensing import UnitMove, sort_blobs
from .pairing import shift_pairs


def direction_with_heading(home: UnitMove, view: UnitMove, config: Config, heading: Array) -> tuple[Array, Array]:
    """Pair sorted world bearings by the cyclic shift minimising sum wrap(theta - a)^2; sum corrections.

    Each pair adds |wrap(theta - a)| at a + pi/2 if wrap(theta - a) < 0 else a - pi/2, which
    is the vector -wrap(theta - a) * u(a + pi/2).
    """
    theta, theta_ok = home.start.bearing, home.start.valid
    a, a_ok = sort_blobs(view.end.bearing + heading, view.end.valid)
    ref_idx, cur_idx, pair_ok, shift_ok = shift_pairs(theta_ok, a_ok)
    diff = wrap(theta[ref_idx] - a[cur_idx])  # (K, S)
    cost = jnp.where(shift_ok, jnp.sum(jnp.where(pair_ok, diff * diff, 0.0), axis=1), jnp.inf)
    k = first_argmin(cost)
    corr = -diff[k][:, None] * unit(a[cur_idx[k]] + jnp.pi / 2)
    hv = jnp.sum(jnp.where(pair_ok[k][:, None], corr, 0.0), axis=0)
    valid = jnp.any(pair_ok[k]) & (safe_norm(hv) > 0)
    return jnp.where(valid, wrap(angle_of(hv) - heading), jnp.nan), valid
