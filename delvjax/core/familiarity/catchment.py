"""Catchment areas along a route as bob_robotics' Python `calculate_ca` and `calculate_rca` define them (docs/familiarity.md §3.3), for
every goal at once:

- `ca_bounds` (`calculate_ca`): from the goal outward, the region over which the (median-filtered)
  image difference function does not decrease: upper = the first j >= goal with f[j+1] < f[j], lower
  = the last j <= goal with f[j-1] < f[j] (+-inf where there is none);
- `rca_bounds` (`calculate_rca`): the region over which the heading error stays below `threshold`
  deg: upper = (the first j > goal with error >= threshold) - 1, lower likewise (+-inf where none).

The size of a region is upper - lower (inf when a bound is); its size on the route clips the bounds to
the route's ends (BoB's `get_finite_bounds`). `route_tables` computes, for every route
image as the goal, the difference (IDF) of every route image from it and the heading error of the
best rotation (RIDF), the inputs BoB passes to them.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from .ridf import rolled, turn_of_shift, unmasked_table

GOAL_BATCH = 4  # goals side by side (`route_tables`; the differences are reduced as they are made)


def medfilt(values: ArrayLike, size: int) -> Array:
    """scipy.signal.medfilt of a 1-D array: the median of `size` (odd) neighbours, zero-padded."""
    if size == 1:
        return values
    half = size // 2
    padded = jnp.pad(values, half)
    windows = jnp.stack([padded[i : i + values.shape[0]] for i in range(size)], -1)
    return jnp.median(windows, -1)


def edges(lower: ArrayLike, upper: ArrayLike, goal: ArrayLike, n: int) -> tuple[Array, Array]:
    """Bounds as floats: none found is -inf / +inf, but a goal at an end of the route is its own bound
    there (BoB's `ca` of an empty side is 0)."""
    lower = jnp.where(lower >= 0, lower.astype(jnp.float32), -jnp.inf)
    upper = jnp.where(upper < n, upper.astype(jnp.float32), jnp.inf)
    g = jnp.asarray(goal, jnp.float32)
    return jnp.where(goal == 0, g, lower), jnp.where(goal == n - 1, g, upper)


def ca_bounds(idf: ArrayLike, goal: ArrayLike, size: int = 1) -> tuple[Array, Array]:
    """(lower, upper) of `calculate_ca` for one IDF (N,) and its goal index (floats; +-inf: no bound)."""
    f = medfilt(idf, size)
    j = jnp.arange(f.shape[0])
    drops_after = jnp.concatenate([f[1:] < f[:-1], jnp.array([False])])  # f[j+1] < f[j]
    drops_before = jnp.concatenate([jnp.array([False]), f[:-1] < f[1:]])  # f[j-1] < f[j]
    up = jnp.where(drops_after & (j >= goal), j, f.shape[0])
    low = jnp.where(drops_before & (j <= goal), j, -1)
    return edges(jnp.max(low), jnp.min(up), goal, f.shape[0])


def rca_bounds(error_deg: ArrayLike, goal: ArrayLike, threshold: float = 45.0, size: int = 1) -> tuple[Array, Array]:
    """(lower, upper) of `calculate_rca` for one heading-error curve (N,) deg and its goal index."""
    e = medfilt(error_deg, size)
    j = jnp.arange(e.shape[0])
    bad = e >= threshold
    up = jnp.min(jnp.where(bad & (j > goal), j - 1, e.shape[0]))
    low = jnp.max(jnp.where(bad & (j < goal), j + 1, -1))
    return edges(low, up, goal, e.shape[0])


def route_tables(images: ArrayLike, kind: str = "abs") -> tuple[Array, Array]:
    """(idf (G, N), error_deg (G, N)) for route images (N, H, W) in order: row g is image g as the
    goal; idf[g, i] the unrotated difference of image i from it; error_deg[g, i] |the turn of image i's
    best rotation against it| (BoB's `route_ridf_errors`; views aligned along the route)."""
    images = jnp.asarray(images, jnp.float32)
    w = images.shape[-1]
    shifts = jnp.arange(w)
    turns = jnp.abs(jnp.degrees(turn_of_shift(shifts, w)))

    def one_goal(goal: ArrayLike) -> tuple[Array, Array]:
        # image i rolled right by k against the goal = the goal rolled left by k against image i
        curves = unmasked_table(rolled(goal, -shifts), images, kind)  # (N, W)
        best = jnp.argmin(jnp.where(jnp.isnan(curves), jnp.inf, curves), -1)
        return curves[:, 0], turns[best]

    return jax.lax.map(one_goal, images, batch_size=GOAL_BATCH)


def route_catchments(images: ArrayLike, kind: str = "abs", threshold: float = 45.0, size: int = 1) -> dict[str, Array]:
    """Every route image as the goal: CA and RCA bounds and sizes (in images) from `route_tables`."""
    idf, err = route_tables(images, kind)
    goals = jnp.arange(idf.shape[0])
    ca_lo, ca_hi = jax.vmap(lambda f, g: ca_bounds(f, g, size))(idf, goals)
    rca_lo, rca_hi = jax.vmap(lambda e, g: rca_bounds(e, g, threshold, size))(err, goals)
    last = jnp.float32(idf.shape[0] - 1)
    clipped = lambda lo, hi: jnp.minimum(hi, last) - jnp.maximum(lo, 0.0)  # noqa: E731 (BoB's get_finite_bounds)
    return {"ca_lower": ca_lo, "ca_upper": ca_hi, "ca_size": ca_hi - ca_lo, "ca_size_on_route": clipped(ca_lo, ca_hi),
            "rca_lower": rca_lo, "rca_upper": rca_hi, "rca_size": rca_hi - rca_lo,
            "rca_size_on_route": clipped(rca_lo, rca_hi)}  # fmt: skip
