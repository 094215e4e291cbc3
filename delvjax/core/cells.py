"""Many vector-map configurations ("cells") of one shape as one program (docs/sweeps.md).

Cells that share every static field (the method's class and shapes, the sensor's pixels and
channel, the landmark slots and the grid) differ only in traced leaves (d, levels, noise sigmas,
the seed's key, the scene's numbers). They are stacked along a leading axis and evaluated one
after the other inside one compiled program (`lax.map`), each cell's vector map exactly as
`maps.vector_map` computes it (the same per-point program, `batching.WIDTH` points at a time),
so a cell's numbers do not depend on which cells share its chunk.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from .maps import homing_directions, random_headings
from .methods.base import HomingMethod
from .metrics import angular_error_deg, over_edges
from .scene import Env
from .sensor import Sensor


class CellMetrics(eqx.Module):
    """Per-cell sums over the included grid points, (C,) each: points, invalid points, points with
    error > 45 and > 90 degrees (`metrics.over_edges`), sum of errors and of squared errors (degrees; invalid = 180)."""

    points: Array
    invalid: Array
    gt45: Array
    gt90: Array
    error_sum: Array
    error_sq_sum: Array


def _errors(env, inc, method, sensor, key, points, n_valid=None):
    """One cell's per-point angular errors (P,) (degrees; invalid = 180), as `maps.vector_map` computes them;
    with `n_valid` 0 none is evaluated (a row that pads a chunk: its numbers are thrown away)."""
    headings = random_headings(key, points.shape[0])
    direction, valid = homing_directions(env, points, headings, key, sensor, method, n_valid=n_valid)
    return angular_error_deg(direction, valid, points, env.home), valid


@jax.jit
def map_cells(
    envs: Env, points: Array, included: Array, methods: HomingMethod, sensors: Sensor, keys: Array, live: Array
) -> CellMetrics:
    """Vector-map metrics of C stacked cells (leading axis C on `envs`, `included`, `methods`,
    `sensors`, `keys`, `live`); `points` (P, 2) is the shared grid. Headings are random per point from each
    cell's key, as in `maps.vector_map`. `live` (C,): False for a row that only pads the chunk to its
    program's size (none of its points is evaluated, as a shape bucket's padding: it costs nearly nothing)."""
    counts = jnp.where(live, points.shape[0], 0).astype(jnp.int32)

    def one(cell):
        env, inc, method, sensor, key, n_valid = cell
        err, valid = _errors(env, inc, method, sensor, key, points, n_valid)
        count = lambda m: jnp.sum(m & inc).astype(jnp.int32)  # noqa: E731
        e = jnp.where(inc, err, 0.0)
        gt45, gt90 = over_edges(err)
        return CellMetrics(
            points=count(jnp.ones_like(inc)),
            invalid=count(~valid),
            gt45=count(gt45),
            gt90=count(gt90),
            error_sum=jnp.sum(e),
            error_sq_sum=jnp.sum(e * e),
        )

    return jax.lax.map(one, (envs, included, methods, sensors, keys, counts))


@jax.jit
def map_cells_errors(
    envs: Env, points: Array, included: Array, methods: HomingMethod, sensors: Sensor, keys: Array
) -> Array:
    """The per-point angular errors (C, P) of C stacked cells, those `map_cells` sums (degrees; invalid =
    180; NaN at a point not included): what error curves and regions of the grid (the landmarks' hull)
    are read from, with the same arguments."""

    def one(cell):
        env, inc, method, sensor, key = cell
        return jnp.where(inc, _errors(env, inc, method, sensor, key, points)[0], jnp.nan)

    return jax.lax.map(one, (envs, included, methods, sensors, keys))
