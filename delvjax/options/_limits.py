"""How big a run may be: the number of grid points or trials is known before any work, so a run
too large for the machine is refused with an estimate instead of exhausting memory (docs/reproduce.md
"Large grids"). The limit is the user's to raise (`--max-points`, `max_points=`)."""

from __future__ import annotations

import dataclasses
import math
import os

import jax
import jax.numpy as jnp
import numpy as np
from jax.extend import core as jcore

from ..core.batching import item_width
from ..core.checks import is_traced, positive_int
from ..core.errors import InputError
from ..core.kernel import direction_from, map_poses
from ..core.methods import HomingMethod
from ..core.scene import Env
from ..core.sensing import record_home
from ..core.sensor import Sensor
from ..outputs._programs import kept_number

MAX_POINTS = 1_000_000  # grid points (times masks) or trials in one run, by default
# host memory per item of the results and their CSV rows, bytes; slowest method per item on 2 CPU cores, s
BYTES = {"grid point": 120, "trial": 160, "path point": 40, "mesh image": 10_000}  # a 76 x 360 PNG of habitat0: 7.8 kB
SECONDS = {"grid point": 50e-6, "trial": 1.5e-3, "path point": 1e-4, "move": 1.5e-5, "mesh image": 0.025}
MOVES_PER_POINT = 100  # trials x (max_steps + 1) moves of a rollout run: at most this times max_points


def duration(seconds: float) -> str:
    """A time for a person: "40 s", "12 min", "2.5 h", "3.1 days" (never "0.0556 h")."""
    if seconds < 90:
        return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"
    if seconds < 90 * 60:
        return f"{seconds / 60:.0f} min"
    if seconds < 48 * 3600:
        return f"{seconds / 3600:.2g} h"
    return f"{seconds / 86400:.2g} days"


def check_moves(trials: int, max_steps: int, max_points) -> None:
    """`InputError` naming max_steps when `trials` rollouts of up to `max_steps` moves could run longer
    than MOVES_PER_POINT x max_points moves (the default: 1e8, about 25 minutes on 2 CPU cores)."""
    limit = MOVES_PER_POINT * positive_int(max_points, "max_points")
    moves = trials * (max_steps + 1)
    if moves > limit:
        raise InputError(
            "max_steps",
            max_steps,
            f"allows {moves:.3g} moves ({trials} trials x {max_steps + 1}), more than {MOVES_PER_POINT} x "
            f"max_points = {limit:.3g} (up to {duration(moves * SECONDS['move'])} on 2 CPU cores); lower --max-steps or raise --max-points",
        )


def grid_count(arena, spacing: float) -> int:
    """Number of cells of the docs/model.md §5 grid (at most one more per axis than `maps.grid_points`
    keeps), computed without building it: the count a run too large is refused by before it is built
    (`evaluate._vector_map.check_grid`, which then builds the grid once; the exact count is its length)."""
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(arena))  # host numbers, also while jax traces
    nx = max(0, math.ceil((xmax - xmin - spacing / 2) / spacing))
    ny = max(0, math.ceil((ymax - ymin - spacing / 2) / spacing))
    return nx * ny


def check_size(count: int, max_points, field: str, value, what: str = "grid point") -> int:
    """`InputError` naming `field` when `count` items exceed `max_points`; the message estimates the
    memory and time such a run would need. Returns the validated limit."""
    limit = positive_int(max_points, "max_points")
    if count > limit:
        gb = count * BYTES[what] / 1e9
        raise InputError(
            field,
            value,
            f"gives {count:.3g} {what}s, more than max_points {limit} (about {gb:.3g} GB "
            f"of results and up to {duration(count * SECONDS[what])} on 2 CPU cores); use fewer or raise "
            f"--max-points",
        )
    return limit


def available_bytes() -> int:
    """Memory a program may use now: the accelerator's free memory, else the host's MemAvailable
    (/proc/meminfo; free pages where that cannot be read)."""
    device = jax.local_devices()[0]
    stats = device.memory_stats() if device.platform != "cpu" else None
    if stats and "bytes_limit" in stats:
        return int(stats["bytes_limit"]) - int(stats.get("bytes_in_use", 0))
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def _largest(jaxpr, best: int = 0) -> int:
    """Bytes of the largest array any equation of `jaxpr` (and of the programs inside it) makes."""
    for eqn in jaxpr.eqns:
        for v in eqn.outvars:
            shape = getattr(v.aval, "shape", None)
            if shape is not None:
                best = max(best, math.prod(shape) * v.aval.dtype.itemsize)
        for param in eqn.params.values():
            for sub in param if isinstance(param, (list, tuple)) else (param,):
                if isinstance(sub, (jcore.ClosedJaxpr, jcore.Jaxpr)):
                    best = _largest(getattr(sub, "jaxpr", sub), best)
    return best


_PEAK: dict[tuple, int] = {}  # (scene shapes, method and sensor structure) -> bytes: one trace per program


def item_peak_bytes(env: Env, method: HomingMethod, sensor: Sensor) -> int:
    """The largest array one item (one grid point's or one rollout step's homing direction) makes, from
    the shapes alone: the program is traced (`jax.make_jaxpr`), not run; a lower bound of its peak."""
    leaves = jax.tree.leaves((env, method, sensor))
    key = (
        jax.tree.structure((env, method, sensor)),  # an Env's name is not part of it (`scene.Name`)
        tuple((np.shape(x), str(jnp.result_type(x))) for x in leaves),
    )
    if key not in _PEAK:  # kept on disk by the command line (`kept_number`): a warm run traces nothing here
        _PEAK[key] = kept_number("item_peak_bytes", repr(key), lambda: _traced_peak(env, method, sensor))
    return _PEAK[key]


def _traced_peak(env: Env, method: HomingMethod, sensor: Sensor) -> int:
    """`item_peak_bytes` by tracing one item's program."""
    seed = jax.random.PRNGKey(0)

    def one(scene: Env, meth: HomingMethod, sens: Sensor, point: jax.Array, heading: jax.Array):
        home = record_home(scene, seed, sens)
        seen = jnp.ones(scene.landmarks.shape[0], bool)
        return direction_from(scene, seen, map_poses(point, heading, seed, 0, sens), home, meth, sens)

    # every leaf an argument, as in the programs that run (a method's float settings arrive traced)
    shapes = jax.tree.map(lambda a: jax.ShapeDtypeStruct(np.shape(a), jnp.result_type(a)), (env, method, sensor))
    return _largest(jax.make_jaxpr(one)(*shapes, jnp.zeros(2), jnp.zeros(())).jaxpr)


# Hypothesis tables a method builds on the host while its program is traced, bytes per entry of the
# product of the fields named (float64 with its temporaries): Warping's warp_indices (n_alpha x n_rho x n_pix)
HOST_TABLES = {("n_alpha", "n_rho"): 32}


def host_table_bytes(module: object, n_pix: int) -> int:
    """Bytes of the largest host table (`HOST_TABLES`) of `module` or of a module inside it on `n_pix` pixels."""
    best = 0
    for fields, per_entry in HOST_TABLES.items():
        counts = [getattr(module, f, None) for f in fields]
        if all(isinstance(c, int) for c in counts):
            best = max(best, per_entry * n_pix * math.prod(counts))
    for f in dataclasses.fields(module) if dataclasses.is_dataclass(module) else ():
        inner = getattr(module, f.name, None)
        if dataclasses.is_dataclass(inner) and not isinstance(inner, type):
            best = max(best, host_table_bytes(inner, n_pix))
    for inner in getattr(module, "methods", ()) or ():  # a MethodSet's methods
        best = max(best, host_table_bytes(inner, n_pix))
    return best


def check_tables(method: HomingMethod, n_pix: int, limit: int | None = None) -> None:
    """`InputError` naming the settings when the host tables of `method` on `n_pix`-pixel views
    (`host_table_bytes`) would pass `limit` (default: the memory available now), before any work:
    every setup calls it (`options.make_setup`), image databases too."""
    tables = host_table_bytes(method, n_pix)
    if not tables:
        return
    limit = available_bytes() if limit is None else limit
    if tables > limit:
        raise InputError(
            "settings",
            ", ".join(_sizes(method)),
            f"need at least {tables / 2**30:.3g} GiB (hypothesis tables of {type(method).__name__} on {n_pix} "
            f"pixels), more than the {limit / 2**30:.3g} GiB available: use smaller settings",
        )


def _sizes(module: object) -> list[str]:
    """The integer settings of a module (and of the modules in it) that differ from their defaults."""
    out = []
    for f in dataclasses.fields(module) if dataclasses.is_dataclass(module) else ():
        value = getattr(module, f.name, None)
        if isinstance(value, int) and not isinstance(value, bool) and value != f.default:
            out.append(f"{f.name} = {value}")
        elif dataclasses.is_dataclass(value) and not isinstance(value, type):
            out.extend(_sizes(value))
    return out


def check_memory(env: Env, method: HomingMethod, sensor: Sensor, limit: int | None = None) -> None:
    """`InputError` naming the landmarks and the method's sizes when one vectorised group of items
    (`batching.item_width` grid points or trials) would need more memory than `limit` (default: what is
    available now, `available_bytes`), checked before any work (docs/reliability.md "Memory")."""
    if any(is_traced(x) for x in jax.tree.leaves((env, method, sensor))):
        return  # inside a user's jax transformation: the program is theirs to size
    width = item_width(method.reads_panorama())
    limit = available_bytes() if limit is None else limit
    tables = host_table_bytes(method, sensor.n_pix)  # made while the program is traced: bounded first
    need = tables if tables > limit else width * item_peak_bytes(env, method, sensor)
    if need > limit:
        sizes = ", ".join([f"{env.n_landmarks} landmarks", *_sizes(method), *_sizes(sensor)])
        raise InputError(
            "landmarks" if not _sizes(method) and not _sizes(sensor) else "settings",
            sizes,
            f"need at least {need / 2**30:.3g} GiB ({'hypothesis tables' if need == tables else f'one group of {width} items'} "
            f"of {type(method).__name__}), more "
            f"than the {limit / 2**30:.3g} GiB available: use fewer landmarks or smaller settings",
        )


def check_pixels(env: Env, sensor: Sensor) -> None:
    """`InputError` naming n_pix when the ring's pixels are wider than every landmark seen from home: the
    snapshot may then hold no landmark at all (n_pix = 1 or 8 on env1 left every point invalid, with a hint
    about landmarks). A landmark of angular width w is hit by at least one pixel ray when w >= 360 / n_pix."""
    if any(is_traced(x) for x in jax.tree.leaves((env, sensor))):
        return  # inside a user's jax transformation: the program is theirs to size
    lms, valid = np.asarray(env.landmarks, np.float64), np.asarray(env.valid, bool)
    if not valid.any():
        return
    lms, home = lms[valid], np.asarray(env.home, np.float64)  # on the host: no program compiled for an index
    dist = np.hypot(lms[:, 0] - home[0], lms[:, 1] - home[1])
    widest = float(np.degrees(2.0 * np.arcsin(np.minimum(lms[:, 2] / np.maximum(dist, 1e-12), 1.0))).max())
    if 360.0 / sensor.n_pix > widest:
        raise InputError(
            "n_pix",
            sensor.n_pix,
            f"makes pixels of {360.0 / sensor.n_pix:.3g} deg, wider than every landmark seen from home (the widest "
            f"spans {widest:.3g} deg): the snapshot may hold no landmark; use n_pix >= {math.ceil(360.0 / widest)}",
        )
