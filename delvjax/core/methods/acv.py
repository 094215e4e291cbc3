"""ACV, average correction vector (Hong et al. 1992, Weber et al. 1999; thesis Eq 5.2; docs/model.md §4.2)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..geometry import angle_of, safe_norm, unit, wrap
from ..search import first_argmin
from ..sensing import UnitMove, sort_blobs
from .base import HomingMethod
from .heading import Compass, HeadingSource
from .pairing import shift_pairs


class ACV(HomingMethod):
    """Average correction vector (Hong et al. 1992, Weber et al. 1999; thesis Eq 5.2; docs/model.md §4.2).

    Sorted world bearings are paired by the cyclic shift minimising sum wrap(theta - a)^2 and
    the corrections summed: each pair adds |wrap(theta - a)| at a + pi/2 if wrap(theta - a) < 0
    else a - pi/2, which is the vector -wrap(theta - a) * u(a + pi/2).
    """

    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        a, a_ok = sort_blobs(view.end.bearing + heading, view.end.valid)
        return correction_direction(home.start.bearing, home.start.valid, a, a_ok, heading)

    def reads_gray(self, channel: str) -> bool:
        return self.heading.reads_gray


def correction_direction(theta: Array, theta_ok: Array, a: Array, a_ok: Array, heading: Array) -> tuple[Array, Array]:
    """Eq 5.2 on two bearing lists in the home frame: pair by the cyclic shift minimising
    sum wrap(theta - a)^2, sum the corrections; (direction in the agent frame, valid)."""
    ref_idx, cur_idx, pair_ok, shift_ok = shift_pairs(theta_ok, a_ok)
    diff = wrap(theta[ref_idx] - a[cur_idx])  # (K, S)
    cost = jnp.where(shift_ok, jnp.sum(jnp.where(pair_ok, diff * diff, 0.0), axis=1), jnp.inf)
    k = first_argmin(cost)
    corr = -diff[k][:, None] * unit(a[cur_idx[k]] + jnp.pi / 2)
    hv = jnp.sum(jnp.where(pair_ok[k][:, None], corr, 0.0), axis=0)
    valid = jnp.any(pair_ok[k]) & (safe_norm(hv) > 0)
    return jnp.where(valid, wrap(angle_of(hv) - heading), jnp.nan), valid
