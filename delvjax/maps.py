"""Vector maps: the homing direction at every grid point in one jitted, vmapped call (docs/model.md §5).

Every grid point gets its own PRNG key `fold_in(key_views, i)` and, when headings are
random, its heading from `fold_in(key_headings, i)`: the numbers do not depend on how
the points are chunked. Chunks (`lax.map(..., batch_size)`) bound the memory.
"""

from __future__ import annotations

from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from .config import Config
from .geometry import TWO_PI, wrap
from .methods import get_method
from .metrics import angular_error_deg, error_class
from .scene import Env
from .sensing import record_home, unit_move

DEFAULT_BATCH = 2048


class VectorMap(eqx.Module):
    """Per-point results; P = all cells of the grid (see `included`).

    points: (P, 2) cm; included: (P,) cell is a grid point (not within r + clearance of a
    landmark); heading: (P,) release heading of the unit move, rad; direction: (P,) world
    homing direction, rad, NaN where invalid; valid: (P,); error_deg: (P,) angular error,
    180 where invalid.
    """

    points: Array
    included: Array
    heading: Array
    direction: Array
    valid: Array
    error_deg: Array


def grid_points(arena, spacing: float) -> np.ndarray:
    """Centres of square cells of side `spacing` tiling the arena (docs/model.md §5), row-major from (xmin, ymin)."""
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(arena))
    xs = np.arange(xmin + spacing / 2, xmax, spacing, dtype=np.float64)
    ys = np.arange(ymin + spacing / 2, ymax, spacing, dtype=np.float64)
    gx, gy = np.meshgrid(xs[xs < xmax], ys[ys < ymax])
    return np.stack([gx.ravel(), gy.ravel()], axis=-1).astype(np.float32)


@jax.jit
def grid_included(env: Env, points: Array, clearance: float) -> Array:
    """True where a point is farther than r + clearance from every landmark centre."""
    dist = jnp.linalg.norm(points[:, None, :] - env.landmarks[None, :, :2], axis=-1)
    near = (dist <= env.landmarks[None, :, 2] + clearance) & env.valid[None, :]
    return ~jnp.any(near, axis=-1)


def stream_keys(key: Array) -> tuple[Array, Array, Array]:
    """(home, views, headings) keys of one seed."""
    return jax.random.fold_in(key, 0), jax.random.fold_in(key, 1), jax.random.fold_in(key, 2)


@partial(jax.jit, static_argnums=1)
def random_headings(key: Array, n: int) -> Array:
    """Per-point uniform headings in [0, 2 pi), point i from fold_in(key_headings, i)."""
    _, _, k_head = stream_keys(key)
    keys = jax.vmap(partial(jax.random.fold_in, k_head))(jnp.arange(n))
    return jax.vmap(lambda k: jax.random.uniform(k, (), minval=0.0, maxval=TWO_PI))(keys)


@partial(jax.jit, static_argnames=("method", "batch_size"))
def homing_directions(env: Env, points: Array, headings: Array, key: Array, config: Config,
                      method: str, visible: Array | None = None,
                      batch_size: int = DEFAULT_BATCH) -> tuple[Array, Array]:
    """World homing directions (P,) and validity (P,) of `method` at `points` with `headings`.

    The home record sees every landmark; the current views see only `visible` ones
    (occlusion, docs/model.md §5). One program: vmap over points inside chunks of `batch_size`.
    """
    fn = get_method(method)
    k_home, k_views, _ = stream_keys(key)
    home = record_home(env, k_home, config)

    def one(args):
        point, heading, index = args
        view, heading_end = unit_move(env, point, heading, jax.random.fold_in(k_views, index), config,
                                      visible=visible, end_at=point)
        angle, valid = fn(home, view, config)
        return jnp.where(valid, wrap(heading_end + angle), jnp.nan), valid

    index = jnp.arange(points.shape[0])
    return jax.lax.map(one, (points, headings, index), batch_size=min(batch_size, points.shape[0]))


def vector_map(env: Env, method: str, config: Config, spacing: float = 25.0, heading: float | None = None,
               key: Array | None = None, clearance: float = 10.0, visible: Array | None = None,
               batch_size: int = DEFAULT_BATCH) -> VectorMap:
    """The vector map of `method` on the docs/model.md §5 grid; heading fixed (rad) or random per point from `key`."""
    key = jax.random.PRNGKey(0) if key is None else key
    points = jnp.asarray(grid_points(env.arena, spacing))
    heading = None if heading is None else jnp.asarray(heading, jnp.float32)
    return _vector_map(env.arrays(), points, heading, key, config, method, clearance, visible, batch_size)


@partial(jax.jit, static_argnames=("method", "batch_size"))
def _vector_map(env: Env, points: Array, heading: Array | None, key: Array, config: Config, method: str,
                clearance: float, visible: Array | None, batch_size: int) -> VectorMap:
    """One program for the whole map: headings, directions, grid mask and errors."""
    if heading is None:
        headings = random_headings(key, points.shape[0])
    else:
        headings = jnp.full(points.shape[0], heading, jnp.float32)
    direction, valid = homing_directions(env, points, headings, key, config, method, visible, batch_size)
    return VectorMap(
        points=points,
        included=grid_included(env, points, clearance),
        heading=headings,
        direction=direction,
        valid=valid,
        error_deg=angular_error_deg(direction, valid, points, env.home),
    )


def replace_field(config: Config, name: str, value) -> Config:
    """`config` with the leaf `name` (e.g. "d", "levels", "noise.bearing") set to `value`."""
    def where(c):
        for part in name.split("."):
            c = getattr(c, part)
        return c

    return eqx.tree_at(where, config, value, is_leaf=lambda x: x is None)


def sweep(env: Env, method: str, config: Config, name: str, values: Array, spacing: float = 25.0,
          heading: float | None = None, key: Array | None = None, clearance: float = 10.0,
          visible: Array | None = None, batch_size: int = DEFAULT_BATCH) -> VectorMap:
    """Vector maps for every value of one continuous parameter, vmapped as one program.

    `name` is a leaf of `Config` ("d", "levels", "scale", "r_max", "noise.bearing", ...);
    the result's arrays gain a leading axis over `values` (Figs 4.6/4.7, 4.12/4.13).
    """
    key = jax.random.PRNGKey(0) if key is None else key
    points = jnp.asarray(grid_points(env.arena, spacing))
    heading = None if heading is None else jnp.asarray(heading, jnp.float32)
    env = env.arrays()
    one = lambda v: _vector_map(env, points, heading, key, replace_field(config, name, v), method,  # noqa: E731
                                clearance, visible, batch_size)
    return jax.vmap(one)(jnp.asarray(values))


def vector_map_columns(vm: VectorMap) -> dict[str, np.ndarray]:
    """The docs/model.md §7 per-point table of a map (grid points only; degrees; direction NaN where invalid)."""
    inc = np.asarray(vm.included)
    pts = np.asarray(vm.points)[inc]
    return {
        "x": pts[:, 0], "y": pts[:, 1],
        "heading_deg": np.degrees(np.asarray(vm.heading)[inc]),
        "direction_deg": np.degrees(np.asarray(vm.direction)[inc]),
        "error_deg": np.asarray(vm.error_deg)[inc],
        "valid": np.asarray(vm.valid)[inc],
        "error_class": np.asarray(error_class(vm.error_deg))[inc],
    }
