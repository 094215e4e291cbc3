"""Variants of the comparators that a thesis number's gap may come from (the gap probe of
`studies/runs/causes_probe.py`; docs/reproduce.md "What the unexplained gaps were"): methods the
thesis's words allow but our registry does not run, registered for the probe's sweeps only."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from delvjax.core.geometry import angle_of, safe_norm, unit, wrap
from delvjax.core.methods.base import HomingMethod
from delvjax.core.methods.heading import Compass, HeadingSource
from delvjax.core.sensing import UnitMove
from delvjax.options import register, unregister

ACV_NEAREST = "acv-nearest"


class ACVNearest(HomingMethod):
    """ACV whose pairs are each current landmark and the home landmark nearest in bearing (Weber et al.
    1999's non-distinctive landmarks: no one-to-one order), instead of the best cyclic shift of the
    sorted lists (docs/model.md §4.2). With every landmark seen and small bearing changes the two agree;
    with a landmark hidden this keeps every visible landmark with its own home bearing near home."""

    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        theta, theta_ok = home.start.bearing, home.start.valid
        a, a_ok = view.end.bearing + heading, view.end.valid
        diff = wrap(theta[None, :] - a[:, None])  # (current, home)
        near = jnp.argmin(jnp.where(theta_ok[None, :], jnp.abs(diff), jnp.inf), axis=1)
        d = jnp.take_along_axis(diff, near[:, None], axis=1)[:, 0]
        hv = jnp.sum(jnp.where(a_ok[:, None], -d[:, None] * unit(a + jnp.pi / 2), 0.0), axis=0)
        valid = jnp.any(a_ok) & jnp.any(theta_ok) & (safe_norm(hv) > 0)
        return jnp.where(valid, wrap(angle_of(hv) - heading), jnp.nan), valid


def register_variants() -> tuple[str, ...]:
    """Register the probe's method variants (idempotent) and return their names; `unregister_variants` removes
    them (the registry's methods live in `delvjax/core/methods`: these are the probe's alone)."""
    register(ACV_NEAREST, ACVNearest(), "ACV pairing each landmark with the nearest home bearing (gap probe)")
    return (ACV_NEAREST,)


def unregister_variants() -> None:
    """Remove the probe's method variants from the registry."""
    unregister(ACV_NEAREST)
