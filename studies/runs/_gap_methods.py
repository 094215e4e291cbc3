"""Variants of the comparators that a thesis number's gap may come from (the gap probe of
`studies/runs/causes_probe.py`; docs/reproduce.md "What the unexplained gaps were"): methods the
thesis's words allow but our registry does not run, registered for the probe's sweeps only."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from delvjax.core.geometry import angle_of, safe_norm, unit, wrap
from delvjax.core.methods.acv import correction_direction
from delvjax.core.methods.base import HomingMethod
from delvjax.core.methods.heading import Compass, HeadingSource
from delvjax.core.sensing import UnitMove
from delvjax.options import register, unregister

ACV_NEAREST = "acv-nearest"
ACV_AGENT = "acv-agent"
ALV_MEAN = "alv-mean"


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


class ACVAgent(HomingMethod):
    """ACV whose current list keeps the order the camera reads it, sorted by agent-frame bearing
    (`DELV(order="agent")`'s list, docs/model.md §3.3), instead of re-sorted by home-frame bearing (§4.2).
    With every landmark seen a cyclic shift only relabels the pairs, so the two agree; with a landmark
    hidden the list wraps where the agent faces, so a rollout gets a fresh chance at every step to pair the
    visible landmarks with their own home bearings (the thesis does not say in which frame ACV sorts)."""

    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        a, a_ok = view.end.bearing + heading, view.end.valid  # blobs arrive sorted in the agent frame
        return correction_direction(home.start.bearing, home.start.valid, a, a_ok, heading)


class ALVMean(HomingMethod):
    """ALV as the *average* of the unit landmark vectors (thesis lines 209, 234, 408: "the average landmark vector
    at each point"; Lambrinos et al. 2000) instead of Eq 3.11's sum (docs/model.md §4.1). With as many blobs as
    the home view the two give the same direction; where a landmark is hidden or two blobs merge, the sum loses a
    whole unit vector and the average only the hidden one's share."""

    heading: HeadingSource = Compass()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        heading = self.heading(home, view)
        here = jnp.sum(jnp.where(view.end.valid[:, None], unit(view.end.bearing + heading), 0.0), axis=0)
        there = jnp.sum(jnp.where(home.start.valid[:, None], unit(home.start.bearing), 0.0), axis=0)
        m, n = jnp.sum(view.end.valid), jnp.sum(home.start.valid)
        h = here / jnp.maximum(m, 1) - there / jnp.maximum(n, 1)
        valid = (m > 0) & (n > 0) & (safe_norm(h) > 0)
        return jnp.where(valid, wrap(angle_of(h) - heading), jnp.nan), valid


def register_variants() -> tuple[str, ...]:
    """Register the probe's method variants (idempotent) and return their names; `unregister_variants` removes
    them (the registry's methods live in `delvjax/core/methods`: these are the probe's alone)."""
    register(ACV_NEAREST, ACVNearest(), "ACV pairing each landmark with the nearest home bearing (gap probe)")
    register(ACV_AGENT, ACVAgent(), "ACV with the current list in the agent frame (gap probe)")
    register(ALV_MEAN, ALVMean(), "ALV averaging the unit landmark vectors (gap probe)")
    return (ACV_NEAREST, ACV_AGENT, ALV_MEAN)


def unregister_variants() -> None:
    """Remove the probe's method variants from the registry."""
    unregister(ACV_NEAREST)
    unregister(ACV_AGENT)
    unregister(ALV_MEAN)
