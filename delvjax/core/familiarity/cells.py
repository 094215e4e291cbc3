"""Route-following cells of a sweep (docs/sweeps.md "Route-following sweeps"): C stacked cells, each a
trained model, its views, route, rules and key, run one after the other (`lax.map`) as one program;
each cell's trials are `following.follow_route`'s, so a cell's numbers equal `route_experiments`' with
the same settings. A padding row (`live` False) runs no trial."""

from __future__ import annotations

from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..rollouts.rules import SUCCESS
from .base import FamiliarityModel
from .following import Following, ViewSource, follow_route
from .route import Route


class FollowingCell(eqx.Module):
    """One cell: `trials` trials from the route's start facing along it; key: raw uint32 key data
    (`jax.random.key_data`), stackable with NumPy; live: False for a padding row."""

    model: FamiliarityModel
    source: ViewSource
    route: Route
    rules: Following
    key: ArrayLike
    live: ArrayLike


class FollowingSums(eqx.Module):
    """Per-cell sums, (C,) each: trials run, successes, returns to the route, moves."""

    trials: Array
    successes: Array
    errors: Array
    moves: Array


@partial(jax.jit, static_argnames=("trials",))
def following_cells(cells: FollowingCell, trials: int) -> FollowingSums:
    """`trials` route-following trials of each of C stacked cells (module docstring)."""

    def one(cell: FollowingCell) -> Array:
        def run(_) -> Array:
            r = cell.route
            starts = jnp.repeat(r.positions[:1], trials, 0)
            heads = jnp.repeat(r.headings[:1], trials, 0)
            key = jax.random.wrap_key_data(cell.key)
            t = follow_route(cell.model, cell.source, r, cell.rules, starts, heads, key)
            counts = (trials, jnp.sum(t.outcome == SUCCESS), jnp.sum(t.errors), jnp.sum(t.steps))
            return jnp.stack([jnp.asarray(c, jnp.float32) for c in counts])

        return jax.lax.cond(cell.live, run, lambda _: jnp.zeros(4, jnp.float32), None)

    out = jax.lax.map(one, cells)
    return FollowingSums(trials=out[:, 0], successes=out[:, 1], errors=out[:, 2], moves=out[:, 3])
