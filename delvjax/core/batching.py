"""Fixed-width batches: the same numbers however the work is chunked (docs/reproduce.md "Chunking").

XLA compiles a vmapped computation differently for different batch widths (fusion, the order of
a reduction), so a point evaluated among 1, 7 or 1600 others may differ in the last bit, and a
near-tie (DELV's best heading and ordering) may then flip. Every per-point and per-trial program
therefore runs `WIDTH` items at a time (`lax.map` over groups of one `vmap` of width `WIDTH`):
the compiled arithmetic of an item is the same whatever the grid size, chunk size, lane count or
device count, and only the number of groups varies. Work split over the devices of a `local_mesh`
(`over_devices`) gives every device whole items, so it too leaves the numbers unchanged.
A call of fewer items than a chunk runs them padded to a shape bucket (`bucket`: 256, 1024, 4096, ...
items), so grids and trial counts of many sizes share one compiled program; the padding's groups are
skipped (`fixed_width_map`'s `n_valid`), and since an item's arithmetic is that of its group of `WIDTH`,
padding changes no number either (docs/reproduce.md "Shape buckets").
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np
from jax.sharding import Mesh, NamedSharding
from jax.sharding import PartitionSpec as P

WIDTH = 128  # items per vectorised step (a power of two: 256 lanes are two groups)


PANORAMA_WIDTH = 32  # items per vectorised step of a panorama method on an accelerator (`item_width`)


def item_width(reads_panorama: bool) -> int:
    """Items per vectorised step for a method: `WIDTH`; for one that reads whole panoramas (MinWarping)
    one on a CPU (its per-item working set is megabytes: batching them only evicts the cache, 1.6x
    slower at 16, and a padded group of 128 costs 128 searches however few items are active) and
    `PANORAMA_WIDTH` on an accelerator (one at a time leaves a GPU idle between small kernels).
    Items are independent, so the width changes no number."""
    if not reads_panorama:
        return WIDTH
    return 1 if jax.default_backend() == "cpu" else PANORAMA_WIDTH


def traced_floats(tree):
    """Every Python float leaf of `tree` as a float32 array. `equinox.filter_jit` holds Python numbers
    static, so each value of a setting (a noise sigma, an extractor threshold) would compile a program of
    its own; as arrays every value runs the one program (a gradient reaches them too)."""
    return jax.tree.map(lambda x: jnp.asarray(x, jnp.float32) if isinstance(x, float) else x, tree)


def padded(n: int, width: int = WIDTH) -> int:
    """`n` rounded up to a whole number of groups."""
    return -(-n // width) * width


# The padded lengths a chunk of items runs in (`bucket`): BUCKET_BASE * BUCKET_GROWTH**k, so grids of
# 257 to 1024 points share one program, 1025 to 4096 the next, ... up to the batch size (docs/reproduce.md
# "Shape buckets"). The padding's groups are skipped (`fixed_width_map`'s `n_valid`), so a larger bucket costs
# only the cheap per-item work outside them (headings, grid mask, errors: about 0.1 us a padded item).
BUCKET_BASE = 256
BUCKET_GROWTH = 4


def pad_rows(a, size: int) -> np.ndarray:
    """The rows of `a` (host array) padded to `size` with copies of row 0, as is where it has `size` rows or
    more: every chunk or bucket has one shape, so one program serves them all (the padding's results are
    dropped)."""
    a = np.asarray(a)
    return a if len(a) >= size else np.concatenate([a, np.repeat(a[:1], size - len(a), axis=0)])


def bucket(n: int, cap: int, width: int = WIDTH) -> int:
    """The padded length of a chunk of `n` items: the smallest `BUCKET_BASE * BUCKET_GROWTH**k` holding
    them, but at most `padded(cap, width)` (the chunk size a caller bounds memory with; n <= cap)."""
    size = BUCKET_BASE
    while size < n:
        size *= BUCKET_GROWTH
    return max(min(size, padded(cap, width)), padded(n, width))


def fixed_width_map(
    fn: Callable, xs: tuple, active: jax.Array | None = None, width: int = WIDTH, n_valid: jax.Array | None = None
):
    """`vmap(fn)(*xs)` over the leading axis of the arrays in `xs`, `width` items at a time.

    The leading length is padded to a multiple of `width` (with copies of item 0) and the padding
    dropped. With `active` (one flag per item), a group without an active item is skipped and
    its outputs are zeros (they must not be used). With `n_valid` (a count: the items from n_valid on
    are padding, as in a shape bucket) only the groups holding the first n_valid items run, one loop
    of as many steps (the same per-group program as without it; a `lax.cond` per group instead made
    a DELV map 1.6x slower); the others' outputs are zeros.
    A large item (a rendered image) takes a smaller `width`, which bounds the memory of a group.
    """
    n = jax.tree.leaves(xs)[0].shape[0]
    m = padded(n, width)
    pad = lambda a: jnp.concatenate([a, jnp.repeat(a[:1], m - n, axis=0)]) if m > n else a  # noqa: E731
    groups = jax.tree.map(lambda a: pad(a).reshape((m // width, width) + a.shape[1:]), xs)
    batched = jax.vmap(fn)
    if n_valid is not None:
        shapes = jax.eval_shape(lambda g: batched(*g), jax.tree.map(lambda a: a[0], groups))
        zeros = jax.tree.map(lambda s: jnp.zeros((m // width,) + s.shape, s.dtype), shapes)

        def step(i, out):
            g = jax.tree.map(lambda a: jax.lax.dynamic_index_in_dim(a, i, keepdims=False), groups)
            return jax.tree.map(lambda o, v: jax.lax.dynamic_update_index_in_dim(o, v, i, 0), out, batched(*g))

        out = jax.lax.fori_loop(0, (n_valid + width - 1) // width, step, zeros)
    elif active is None:
        out = jax.lax.map(lambda g: batched(*g), groups)
    else:
        flags = pad(active).reshape(m // width, width)
        shapes = jax.eval_shape(lambda g: batched(*g), jax.tree.map(lambda a: a[0], groups))
        idle = lambda g: jax.tree.map(lambda s: jnp.zeros(s.shape, s.dtype), shapes)  # noqa: E731
        out = jax.lax.map(lambda gf: jax.lax.cond(jnp.any(gf[1]), lambda g: batched(*g), idle, gf[0]), (groups, flags))
    return jax.tree.map(lambda a: a.reshape((m,) + a.shape[2:])[:n], out)


def local_mesh() -> Mesh | None:
    """A one-axis mesh ("items") over this process's devices, or None with one device."""
    devices = jax.local_devices()
    return None if len(devices) == 1 else Mesh(np.array(devices), ("items",))


def n_devices(mesh: Mesh | None) -> int:
    """How many devices share the items."""
    return 1 if mesh is None else mesh.size


@partial(jax.jit, static_argnums=(0, 1, 2))
def over_devices(fn: Callable, mesh: Mesh, n_replicated: int, *args):
    """`fn(*args)` with every device given the replicated first `n_replicated` args and its own
    contiguous slice of the leading axis of the others; the outputs' leading axes are joined.
    Every device runs the same per-item program, so results equal the one-device ones."""
    specs = (P(),) * n_replicated + (P("items"),) * (len(args) - n_replicated)
    return jax.shard_map(fn, mesh=mesh, in_specs=specs, out_specs=P("items"), check_vma=False)(*args)


def global_mesh() -> Mesh:
    """A one-axis mesh ("items") over every device of every process (`jax.distributed`)."""
    return Mesh(np.array(jax.devices()), ("items",))


def process_rows(mesh: Mesh, total: int) -> tuple[int, int]:
    """The rows [start, stop) of a leading axis of length `total` (a multiple of the mesh size) that
    this process's devices hold when it is split over `mesh` (contiguous: a device's slice each)."""
    spans = NamedSharding(mesh, P("items")).addressable_devices_indices_map((total,)).values()
    starts, stops = zip(*[(s[0].start or 0, total if s[0].stop is None else s[0].stop) for s in spans])
    start, stop = min(starts), max(stops)
    if stop - start != total * len(spans) // mesh.size:
        raise RuntimeError("this process's devices do not hold contiguous rows of the mesh")
    return start, stop


def over_processes(fn: Callable, mesh: Mesh, n_replicated: int, total: int, *args):
    """`over_devices` on a mesh spanning processes (one program over every device of every process):
    each process passes the whole replicated args and only its own rows (`process_rows`) of the split
    ones, and gets its own rows of the outputs back (NumPy)."""
    replicated, split = NamedSharding(mesh, P()), NamedSharding(mesh, P("items"))
    glob = [
        jax.tree.map(lambda a: jax.make_array_from_process_local_data(replicated, np.asarray(a)), x)
        for x in args[:n_replicated]
    ]
    glob += [
        jax.tree.map(
            lambda a: jax.make_array_from_process_local_data(split, np.asarray(a), (total,) + np.shape(a)[1:]), x
        )
        for x in args[n_replicated:]
    ]
    out = over_devices(fn, mesh, n_replicated, *glob)

    def mine(a):
        shards = sorted(a.addressable_shards, key=lambda s: s.index[0].start or 0)
        return np.concatenate([np.asarray(s.data) for s in shards])

    return jax.tree.map(mine, out)
