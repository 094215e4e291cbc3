"""Vector maps: the homing direction at every grid point, vmapped (docs/model.md §5).

Every grid point gets its own PRNG key `fold_in(key_views, i)` and, when headings are
random, its heading from `fold_in(key_headings, i)`; points are evaluated `batching.WIDTH`
at a time. So the numbers do not depend on how the points are chunked: the grid runs in
host-side chunks of at most `batch_size` points, which bounds the memory however large the grid,
each padded to a shape bucket (`batching.bucket`), so grids of many sizes share one program.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from .batching import bucket, fixed_width_map, item_width, local_mesh, n_devices, over_devices, pad_rows
from .checks import is_traced
from .frames import frame
from .geometry import TWO_PI
from .grid import CLEARANCE as CLEARANCE
from .grid import SPACING as SPACING
from .grid import Grid
from .grid import grid_points as grid_points
from .kernel import direction_from, map_poses
from .methods.base import HomingMethod
from .metrics import angular_error_deg, error_class
from .scene import Env, clear_of_landmarks
from .sensing import record_home
from .sensor import Sensor
from .types import BlobFlags, GridFlag, GridFloat, GridPoints, PerPoint, PerPointFlag, Points, Real

DEFAULT_BATCH = 16384  # grid points per host-side chunk


class VectorMap(eqx.Module):
    """Per-point results; P = all cells of the grid (see `included`).

    points: (P, 2) cm; included: (P,) cell is a grid point (not within r + clearance of a
    landmark); heading: (P,) release heading of the unit move, rad; direction: (P,) world
    homing direction, rad, NaN where invalid; valid: (P,); error_deg: (P,) angular error,
    180 where invalid; grid: the `Grid` the map was computed on (`vector_map` and `sweep` set it; None on
    scattered points such as an image database, and on one chunk's result): a static field, no leaf, so
    a figure needs no `spacing=` (`plots.vector_map_figure`); `spacing` is its cell side.
    """

    points: GridPoints
    included: GridFlag
    heading: GridFloat
    direction: GridFloat
    valid: GridFlag
    error_deg: GridFloat
    grid: Grid | None = eqx.field(static=True, default=None)

    @property
    def spacing(self) -> float | None:
        """The grid's cell side in cm (None without a grid)."""
        return None if self.grid is None else self.grid.spacing

    def columns(self, method: str = "") -> dict:
        """The columns of the vector-map CSV (`vector_map_columns`); `method` is not a column of it."""
        return vector_map_columns(self)

    def to_dataframe(self, method: str = ""):
        """One row per grid point with the columns of the vector-map CSV, as a pandas DataFrame."""
        return frame(self.columns())

    def to_xarray(self):
        """The map as an `xarray.Dataset` over (y, x) in cm, CF units on every variable (`map_dataset`)."""
        return map_dataset(self)


def computed_on(spacing: float, clearance, heading) -> Grid | None:
    """The `Grid` of a map computed with these core arguments (heading in radians or None); None where the
    clearance is traced or per cell (no number of one grid)."""
    if is_traced(clearance) or np.ndim(clearance) or is_traced(heading):
        return None
    fixed = None if heading is None else math.degrees(float(heading))
    return Grid(spacing=float(spacing), clearance=float(clearance), heading_deg=fixed)


# A grid point within this distance of home is home itself: no homing direction is defined there
# (docs/model.md §5 "Grid"), so it is left out, as the image databases leave out their home image.
AT_HOME_CM = 1e-3


@jax.jit
def grid_included(env: Env, points: Points, clearance: Real) -> PerPointFlag:
    """True where a grid point is farther than r + clearance from every landmark centre and is not
    home itself (docs/model.md §5 "Grid")."""
    away = jnp.sum((points - env.home) ** 2, axis=-1) > AT_HOME_CM**2
    return clear_of_landmarks(env, points, clearance) & away


def stream_keys(key: Array) -> tuple[Array, Array, Array]:
    """(home, views, headings) keys of one seed."""
    return jax.random.fold_in(key, 0), jax.random.fold_in(key, 1), jax.random.fold_in(key, 2)


@partial(jax.jit, static_argnums=1)
def random_headings(key: Array, n: int, start: Array | int = 0) -> Array:
    """Per-point uniform headings in [0, 2 pi), point i (counted from `start`) from fold_in(key_headings, i)."""
    _, _, k_head = stream_keys(key)
    keys = jax.vmap(partial(jax.random.fold_in, k_head))(start + jnp.arange(n))
    return jax.vmap(lambda k: jax.random.uniform(k, (), minval=0.0, maxval=TWO_PI, dtype=jnp.float32))(keys)


@jax.jit
def homing_directions(
    env: Env,
    points: Points,
    headings: PerPoint,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    visible: BlobFlags | None = None,
    start: Array | int = 0,
    n_valid: Array | None = None,
) -> tuple[PerPoint, PerPointFlag]:
    """World homing directions (P,) and validity (P,) of `method` at `points` with `headings`.

    The home record sees every landmark; the current views see only `visible` ones
    (occlusion, docs/model.md §5). Point i uses the view stream of index `start + i`.
    One program, `batching.item_width` points at a time; with `n_valid` only the first n_valid
    points are evaluated (a group of padding is skipped; its outputs are zeros, not to be used).
    """
    k_home, k_views, _ = stream_keys(key)
    home = record_home(env, k_home, sensor)
    seen = jnp.ones(env.landmarks.shape[0], bool) if visible is None else visible

    def one(args):
        point, heading, index = args
        return direction_from(env, seen, map_poses(point, heading, k_views, index, sensor), home, method, sensor)

    index = start + jnp.arange(points.shape[0])
    width = item_width(method.reads_panorama())
    return fixed_width_map(lambda *a: one(a), (points, headings, index), width=width, n_valid=n_valid)


def vector_map(
    env: Env,
    method: HomingMethod,
    sensor: Sensor,
    spacing: float = SPACING,
    heading: float | None = None,
    key: Array | None = None,
    clearance: Real = CLEARANCE,
    visible: Array | None = None,
    batch_size: int = DEFAULT_BATCH,
    progress: Callable[[int, int], None] | None = None,
    chunk_program: Callable[..., VectorMap] | None = None,
    points: np.ndarray | None = None,
) -> VectorMap:
    """The vector map of `method` on the docs/model.md §5 grid; heading fixed (rad) or random per point from `key`.

    The grid runs in host-side chunks of `batch_size` points (the last one padded, so one
    program), so memory is bounded by the chunk; a grid smaller than a chunk is padded to its shape
    bucket (`batching.bucket`: grids of 1025 to 4096 points run one program). The padding is never
    evaluated. `progress(n, P)` is called after each chunk of n of the P points. The numbers are the
    same for every `batch_size`. `chunk_program` stands in for the chunk's jitted program on one device (the
    command line's, kept on disk between runs). `points`: the grid `grid_points(env.arena, spacing)`
    when the caller has built it already (the API has, to check it). The result carries `spacing`.
    """
    key = jax.random.PRNGKey(0) if key is None else key
    points = grid_points(env.arena, spacing) if points is None else points
    heading = None if heading is None else jnp.asarray(heading, jnp.float32)
    n = points.shape[0]
    mesh = local_mesh()
    per_device = bucket(-(-min(batch_size, n) // n_devices(mesh)), -(-batch_size // n_devices(mesh)))
    chunk = per_device * n_devices(mesh)
    parts = []
    for start in range(0, n, chunk):  # chunked driver: every chunk is the same compiled program
        rows = pad_rows(points[start : start + chunk], chunk)
        n_valid = np.int32(min(chunk, n - start))
        if mesh is None:
            part = (chunk_program or _vector_map)(
                env, rows, heading, key, sensor, method, clearance, visible, np.int32(start), n_valid
            )
        else:  # device d evaluates grid points start + d * per_device ...: the same per-point program
            starts = (start + per_device * np.arange(mesh.size)).astype(np.int32)
            counts = np.clip(n_valid - per_device * np.arange(mesh.size), 0, per_device).astype(np.int32)
            part = over_devices(
                _device_chunk, mesh, 7, env, heading, key, sensor, method, clearance, visible, rows, starts, counts
            )
        parts.append(jax.tree.map(lambda a: np.asarray(a)[: n - start], part))
        if progress is not None:
            progress(min(chunk, n - start), n)
    vm = jax.tree.map(lambda *a: jax.device_put(np.concatenate(a)), *parts)  # a plain copy: no program compiled
    return dataclasses.replace(vm, grid=computed_on(spacing, clearance, heading))


def _device_chunk(
    env: Env,
    heading: Array | None,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    clearance,
    visible: Array | None,
    points: Array,
    starts: Array,
    counts: Array,
) -> VectorMap:
    """One device's part of a chunk (`batching.over_devices`): its points start at starts[0], the first
    counts[0] of them grid points (the rest padding)."""
    return _vector_map(env, points, heading, key, sensor, method, clearance, visible, starts[0], counts[0])


@jax.jit
def _vector_map(
    env: Env,
    points: Array,
    heading: Array | None,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    clearance: Real,
    visible: Array | None,
    start: Array | int = 0,
    n_valid: Array | None = None,
) -> VectorMap:
    """One program for a chunk of the map: headings, directions, grid mask and errors; point i is grid point
    start + i; with `n_valid` the points from n_valid on are padding, not evaluated (zero direction and validity)."""
    if heading is None:
        headings = random_headings(key, points.shape[0], start)
    else:
        headings = jnp.full(points.shape[0], heading, jnp.float32)
    direction, valid = homing_directions(env, points, headings, key, sensor, method, visible, start, n_valid)
    return VectorMap(
        points=points,
        included=grid_included(env, points, clearance),
        heading=headings,
        direction=direction,
        valid=valid,
        error_deg=angular_error_deg(direction, valid, points, env.home),
    )


CHUNK_PROGRAM = _vector_map  # one chunk's jitted program: what `vector_map(chunk_program=)` stands in for


def replace_field(method: HomingMethod, sensor: Sensor, name: str, value) -> tuple[HomingMethod, Sensor]:
    """(method, sensor) with the leaf `name` set to `value` (`eqx.tree_at`): "method.levels",
    "sensor.noise.bearing", or a bare path looked up on the method first, then the sensor
    ("levels", "d", "noise.bearing")."""
    parts = name.split(".")
    owner = parts[0] if parts[0] in ("method", "sensor") else None
    path = parts[1:] if owner else parts

    def where(obj):
        for part in path:
            obj = getattr(obj, part)
        return obj

    def has(obj) -> bool:
        try:
            where(obj)
            return True
        except AttributeError:
            return False

    owner = owner or ("method" if has(method) else "sensor")
    if owner == "method":
        return eqx.tree_at(where, method, value, is_leaf=lambda x: x is None), sensor
    return method, eqx.tree_at(where, sensor, value, is_leaf=lambda x: x is None)


def sweep(
    env: Env,
    method: HomingMethod,
    sensor: Sensor,
    name: str,
    values: Array,
    spacing: float = SPACING,
    heading: float | None = None,
    key: Array | None = None,
    clearance: Real = CLEARANCE,
    visible: Array | None = None,
) -> VectorMap:
    """Vector maps for every value of one continuous setting, vmapped as one program.

    `name` names a leaf of the method or the sensor (`replace_field`: "levels", "d",
    "noise.bearing", "sensor.d", ...); the result's arrays gain a leading axis over `values`
    (Figs 4.6/4.7, 4.12/4.13).
    """
    key = jax.random.PRNGKey(0) if key is None else key
    points = jnp.asarray(grid_points(env.arena, spacing))
    heading = None if heading is None else jnp.asarray(heading, jnp.float32)

    def one(v):
        m, s = replace_field(method, sensor, name, v)
        return _vector_map(env, points, heading, key, s, m, clearance, visible)

    return dataclasses.replace(jax.vmap(one)(jnp.asarray(values)), grid=computed_on(spacing, clearance, heading))


def vector_map_columns(vm: VectorMap) -> dict[str, np.ndarray]:
    """Per grid point (grid points only): x, y, heading_deg, direction_deg (NaN where invalid),
    error_deg, valid, error_class."""
    inc = np.asarray(vm.included)
    pts = np.asarray(vm.points)[inc]
    return {
        "x": pts[:, 0],
        "y": pts[:, 1],
        "heading_deg": np.degrees(np.asarray(vm.heading)[inc]),
        "direction_deg": np.degrees(np.asarray(vm.direction)[inc]),
        "error_deg": np.asarray(vm.error_deg)[inc],
        "valid": np.asarray(vm.valid)[inc],
        "error_class": error_class(np.asarray(vm.error_deg))[inc],  # NumPy's comparisons: no programs compiled
    }


def map_dataset(vm: VectorMap):
    """A `VectorMap` as an `xarray.Dataset`: on a regular grid (`delvjax.vector_map`) the variables
    heading_deg, direction_deg, error_deg, valid, included over dimensions (y, x) in cm; on scattered
    points (an image database) over `point`, with x and y as coordinates. CF `units` and `long_name`
    on every variable; NaN direction where invalid."""
    import xarray as xr  # xarray: loaded only when a labelled view is asked for

    pts = np.asarray(vm.points, dtype=np.float64)
    values = {
        "heading_deg": (np.degrees(np.asarray(vm.heading)), "degree", "release heading of the unit move"),
        "direction_deg": (np.degrees(np.asarray(vm.direction)), "degree", "homing direction, world frame"),
        "error_deg": (np.asarray(vm.error_deg), "degree", "angular error to the true home direction"),
        "valid": (np.asarray(vm.valid), "1", "a homing direction was found"),
        "included": (
            np.asarray(vm.included),
            "1",
            "a grid point of the mean (not inside or next to a landmark, not home)",
        ),
    }
    xs, ys = np.unique(pts[:, 0]), np.unique(pts[:, 1])
    gx, gy = np.meshgrid(xs, ys)
    grid = xs.size * ys.size == len(pts) and np.array_equal(np.stack([gx.ravel(), gy.ravel()], -1), pts)
    if grid:  # row-major from (xmin, ymin), as `maps.grid_points` lays it out
        data = {
            k: (("y", "x"), v.reshape(ys.size, xs.size), {"units": u, "long_name": t})
            for k, (v, u, t) in values.items()
        }
        coords = {"x": ("x", xs, {"units": "cm", "long_name": "x"}), "y": ("y", ys, {"units": "cm", "long_name": "y"})}
    else:
        data = {k: (("point",), v, {"units": u, "long_name": t}) for k, (v, u, t) in values.items()}
        coords = {
            "x": ("point", pts[:, 0], {"units": "cm", "long_name": "x"}),
            "y": ("point", pts[:, 1], {"units": "cm", "long_name": "y"}),
        }
    return xr.Dataset(data, coords=coords)
