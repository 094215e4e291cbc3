"""CC, the snapshot model of Cartwright & Collett (landmarks only).

Source: B. A. Cartwright and T. S. Collett, "How honey bees use landmarks to guide their
return to a food source", Nature 295:560-564 (1982), and "Landmark learning in bees:
experiments and models", J. Comp. Physiol. A 151:521-543 (1983).  Reviewed in the thesis
§2.1 (the 'snapshot model') and §2.2.2 (sector pairing of light and dark sectors).

All angles are in one world-aligned frame (the alpha_r frame; the caller applied a compass).
Snapshot blobs i have bearing theta_i and apparent width s_i; current blobs j have a_j, w_j.
With u(x) = (cos x, sin x) and only valid blobs taken part:

    j(i)  = first argmin_j |wrap(a_j - theta_i)|            (pair with the closest in bearing)
    c_i   = a_j(i)
    T_i   = -sign(wrap(theta_i - c_i)) * u(c_i + pi/2)      (tangential: turns c_i toward theta_i)
    R_i   =  sign(s_i - w_j(i)) * u(c_i)                    (radial: toward the landmark if it looks too small)
    H     =  sum_i (T_i + radial_weight * R_i)

Sign check: a step along +u(c + pi/2) changes the bearing of a landmark seen at c by
-step/distance, so to raise c toward theta (wrap(theta - c) > 0) one moves along -u(c + pi/2).
Cartwright & Collett weight both kinds of unit vector equally (radial_weight = 1).

Our decision: only the landmarks (dark sectors) are paired; the gaps (light sectors) between
them, which the original model pairs as well (thesis §2.2.2), are not used.
"""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..geometry import angle_of, safe_norm, unit, wrap
from ..search import first_argmin
from ..sensing import UnitMove
from ..settings import setting
from ..types import BlobFlags, Blobs, Flag, Point
from .base import HomingMethod
from .heading import Compass, HeadingSource


def cc_home_vector(
    ref_bearing: Blobs,
    ref_width: Blobs,
    ref_valid: BlobFlags,
    cur_bearing: Blobs,
    cur_width: Blobs,
    cur_valid: BlobFlags,
    radial_weight: float | Array = 1.0,
) -> tuple[Point, Flag]:
    """Home vector H (2,) of the snapshot model, and whether it is defined.

    Inputs are fixed-shape (B,) blob arrays (bearing, apparent width, validity mask) of the
    home snapshot and the current view in the common alpha_r frame; invalid slots are ignored.
    `valid` is False, and H is 0, when either side has no valid blob or the unit vectors cancel.
    """
    dist = jnp.abs(wrap(cur_bearing[None, :] - ref_bearing[:, None]))  # (B_ref, B_cur)
    j = first_argmin(jnp.where(cur_valid[None, :], dist, jnp.inf))  # (B_ref,)
    c, w = cur_bearing[j], cur_width[j]
    tangential = -jnp.sign(wrap(ref_bearing - c))[:, None] * unit(c + jnp.pi / 2)
    radial = jnp.sign(ref_width - w)[:, None] * unit(c)
    pair_ok = ref_valid & jnp.any(cur_valid)
    h = jnp.sum(jnp.where(pair_ok[:, None], tangential + radial_weight * radial, 0.0), axis=0)
    valid = jnp.any(pair_ok) & (safe_norm(h) > 0)
    return h, valid


class CartwrightCollett(HomingMethod):
    """The snapshot model as a homing method: home blobs against current blobs turned into the
    alpha_r frame by the heading source (a compass by default); direction in the agent frame."""

    radial_weight: float = setting(
        1.0, check="non_negative", help="weight of the radial unit vectors against the tangential ones"
    )
    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        h, valid = cc_home_vector(
            home.start.bearing,
            home.start.width,
            home.start.valid,
            view.end.bearing + heading,
            view.end.width,
            view.end.valid,
            self.radial_weight,
        )
        return jnp.where(valid, wrap(angle_of(h) - heading), jnp.nan), valid

    def reads_gray(self, channel: str) -> bool:
        return self.heading.reads_gray
