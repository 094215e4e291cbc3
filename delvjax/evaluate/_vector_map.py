"""Python API for notebooks and scripts; mirrors the CLI (same names, same validation).

Every function validates all its options before any array work (`InputError` naming the
field and value), builds the method module and the `Sensor` (`options.make_setup`; None
means the module's default) and calls the core.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Sequence
from pathlib import Path

import jax
import numpy as np

from ..core import maps
from ..core.batching import bucket, pad_rows
from ..core.checks import angle_deg, is_traced, non_negative, positive_int, seed_value
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.maps import CLEARANCE, SPACING
from ..core.methods import HomingMethod
from ..core.rollouts import Grid, legacy_config
from ..core.scene import Env
from ..core.sensor import Sensor
from ..envs._presets import load_env
from ..options import _limits as limits
from ..options._limits import MAX_POINTS, check_size
from ..options._schema import ROLLOUT_ONLY
from ..options._setup import make_setup
from ..outputs._programs import kept_number
from ._progress import Progress, as_progress


def resolve_headings(heading_deg: float | None, seed: int) -> tuple[float | None, jax.Array]:
    """(fixed heading in radians or None for seeded random headings, PRNG key)."""
    key = jax.random.PRNGKey(seed_value(seed))
    if heading_deg is None:
        return None, key
    return math.radians(angle_deg(heading_deg, "heading_deg")), key


# what a caller may pass for a list of landmark indices, release distances or release points: a list,
# tuple or NumPy array alike
Indices = Sequence[int] | np.ndarray
Values = Sequence[float] | np.ndarray
PointList = Sequence[Sequence[float]] | np.ndarray


def visible_mask(env: Env, hidden: Indices | None) -> np.ndarray | None:
    """Boolean (L,) mask of the landmarks seen during homing, `hidden` ones occluded (docs/model.md §5).
    Indices may be Python or NumPy integers (a list, tuple or array)."""
    if hidden is None or len(hidden) == 0:
        return None
    n = env.n_landmarks
    for i in hidden:
        if isinstance(i, (bool, np.bool_)) or not isinstance(i, numbers.Integral) or not 0 <= i < n:
            raise InputError("hide", i, f"must be a landmark index in 0..{n - 1}")
    mask = np.ones(env.landmarks.shape[0], bool)
    mask[[int(i) for i in hidden]] = False
    return mask


def refuse_rollout_only(options: dict) -> None:
    """`InputError` for a given setting that acts only in rollouts (the motion noise): a vector map would
    silently ignore it."""
    for name, value in options.items():
        if value is not None and name.startswith(ROLLOUT_ONLY):
            raise InputError(
                name, value, "acts only in rollouts (catchment, success-rate, trajectories): a vector map ignores it"
            )


def scene_request(
    env: str | Path | Env,
    method: str | HomingMethod,
    clearance: float,
    heading_deg: float | None,
    seed: int,
    method_set=None,
    **options,
) -> tuple[Env, HomingMethod, Sensor, float | None, jax.Array, float]:
    """The options every evaluation shares, validated before any work: method name and settings,
    sensor options, grid clearance, environment, heading/seed. Returns
    (env, method module, sensor, heading rad | None, key, clearance)."""
    module, sensor = make_setup(method, method_set, **options)
    clearance = non_negative(clearance, "clearance")
    env = load_env(env)
    check_step(env, sensor.d)
    limits.check_memory(env, module, sensor)  # one group of items fits in memory, before any work
    limits.check_pixels(env, sensor)  # the ring resolves a landmark at home (issue 53)
    heading, key = resolve_headings(heading_deg, seed)
    return env, module, sensor, heading, key, clearance


MOVE_RESOLUTION = 100  # a unit move spans at least this many steps of float32 at the arena's farthest corner


def check_step(env: Env, d) -> None:
    """`InputError` naming d when the unit move is too short for float32 coordinates to resolve (below
    `MOVE_RESOLUTION` steps at the arena's farthest corner: the move would not move) or longer than the
    arena's diagonal (it would leave the arena from anywhere). A traced d is the caller's to keep in range."""
    if is_traced(d) or is_traced(env.arena):
        return
    arena = np.asarray(env.arena, np.float64)
    shortest = MOVE_RESOLUTION * float(np.spacing(np.float32(np.abs(arena).max())))
    diagonal = math.hypot(arena[2] - arena[0], arena[3] - arena[1])
    if not shortest <= float(d) <= diagonal:
        raise InputError(
            "d",
            float(d),
            f"must be in [{shortest:.2g}, {diagonal:.4g}] cm: at least {MOVE_RESOLUTION} steps of the float32 "
            "coordinates at the arena's farthest corner, at most the arena's diagonal",
        )


def check_grid(
    env: Env, grid: Grid, max_points: int = MAX_POINTS, copies: int = 1, what: str = "grid point"
) -> np.ndarray:
    """The points of `grid` (docs/model.md §5; `maps.grid_points`), built once and checked: `InputError` naming
    `spacing` when the grid (times `copies`, e.g. occlusion masks) has more than `max_points` points
    (`options._limits.check_size`, counted before the grid is built; `what` they are: grid points, or trials
    of a catchment) or no point clear of the landmarks."""
    spacing, clearance = grid.spacing, grid.clearance
    count = limits.grid_count(env.arena, spacing)
    check_size(count * copies, max_points, "spacing", spacing, what)
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(env.arena))
    if count == 0:
        raise InputError(
            "spacing",
            spacing,
            f"must be smaller than the arena ({xmax - xmin:.4g} x {ymax - ymin:.4g} cm): no grid cell fits",
        )
    if clearance >= math.hypot(xmax - xmin, ymax - ymin):
        raise InputError("clearance", clearance, "keeps every grid point away: it exceeds the arena's diagonal")
    points = maps.grid_points(env.arena, spacing)
    if not _has_clear_point(env, points, spacing, clearance):
        raise InputError(
            "spacing",
            spacing,
            f"leaves no grid point in the arena clear of the landmarks (r + clearance {clearance:g} cm) but home: "
            "use a smaller spacing or clearance",
        )
    return points


_CLEAR: dict[tuple, bool] = {}  # (scene numbers, spacing, clearance) -> answer: a sweep asks again per cell


def _has_clear_point(env: Env, points: np.ndarray, spacing: float, clearance: float) -> bool:
    """Whether some docs/model.md §5 grid point (`points`, of `spacing`) is clear of every landmark (r +
    clearance) and not home."""
    key = (
        np.asarray(env.landmarks).tobytes(),
        np.asarray(env.valid).tobytes(),
        np.asarray(env.arena).tobytes(),
        np.asarray(env.home).tobytes(),  # a point at home is left out
        float(spacing),
        float(clearance),
    )
    if key not in _CLEAR:  # kept on disk by the command line (`kept_number`): a warm run compiles nothing here
        text = "|".join(k.hex() if isinstance(k, bytes) else repr(k) for k in key)
        _CLEAR[key] = bool(kept_number("has_clear_point", text, lambda: int(_clear_point(env, points, clearance))))
        if len(_CLEAR) > 4096:
            _CLEAR.pop(next(iter(_CLEAR)))
    return _CLEAR[key]


def _clear_point(env: Env, points: np.ndarray, clearance: float) -> bool:
    """`_has_clear_point`, computed: the grid's mask (`maps.grid_included`) on the device."""
    n = points.shape[0]
    if n == 0:
        return False
    # padded to its shape bucket (`batching.bucket`): grids of many sizes share the mask's program
    padded = pad_rows(points, bucket(n, max(n, maps.DEFAULT_BATCH)))
    return bool(np.asarray(maps.grid_included(env, jax.device_put(padded), clearance))[:n].any())


def map_request(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    spacing: float = SPACING,
    heading_deg: float | None = None,
    seed: int = 0,
    clearance: float = CLEARANCE,
    hidden: Indices | None = None,
    batch_size: int = maps.DEFAULT_BATCH,
    max_points: int = MAX_POINTS,
    grid: Grid | None = None,
    **options,
) -> dict:
    """Validate the options of one vector map of a sweep (docs/sweeps.md; before any array work), whose
    axes are flat names (`spacing`, ...): keyword arguments of `core.maps.vector_map`. Raises `InputError`
    naming the field and value."""
    flat = dict(spacing=spacing, clearance=clearance, heading_deg=heading_deg)
    if grid is None:
        grid = Grid(**flat)
    else:
        legacy_config(Grid, grid, {k: v for k, v in flat.items() if v != getattr(Grid(), k)})
    return _checked_map(env, method, grid, seed, hidden, batch_size, max_points, **options)[0]


def _checked_map(env, method, grid: Grid, seed, hidden, batch_size, max_points, **options) -> tuple[dict, np.ndarray]:
    """(`map_request`'s keywords, the grid's points): the grid counted and built once (`check_grid`)."""
    refuse_rollout_only(options)
    env, module, sensor, heading, key, clearance = scene_request(
        env, method, grid.clearance, grid.heading_deg, seed, **options
    )
    points = check_grid(env, grid, max_points)
    batch_size = positive_int(batch_size, "batch_size")
    visible = visible_mask(env, hidden)
    request = dict(
        env=env,
        method=module,
        sensor=sensor,
        spacing=grid.spacing,
        heading=heading,
        key=key,
        clearance=clearance,
        visible=None if visible is None else jax.device_put(visible),
        batch_size=batch_size,
    )
    return request, points


@keywords_after(
    2,
    (
        "spacing",
        "heading_deg",
        "seed",
        "clearance",
        "hidden",
        "batch_size",
        "max_points",
        "grid",
        "progress",
        "chunk_program",
    ),
)
def vector_map(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    grid: Grid | None = None,
    seed: int = 0,
    hidden: Indices | None = None,
    batch_size: int = maps.DEFAULT_BATCH,
    max_points: int = MAX_POINTS,
    progress: Progress | Callable[[int, int], None] | None = None,
    chunk_program: Callable[..., maps.VectorMap] | None = None,
    **options,
) -> maps.VectorMap:
    """Homing direction of `method` at every docs/model.md §5 grid point, one jitted vmapped call.

    `method`: a registry name (`"delv-compass"`) or a method module (`DELV(levels=3,
    heading=Compass())`); `sensor=Sensor(...)` may replace the sensor options below.

    `Grid.heading_deg` fixes the heading at every point; otherwise headings are uniform random
    per point from `seed` (which also drives every noise source). `options`: sensor options
    (d, background, channel, alpha_r_deg, n_pix, and the noise keywords bearing_noise_deg,
    step_noise, turn_noise_deg, odometry_turn_noise_deg, compass_noise_deg) and method settings
    (levels, n_heading, scale, r_max; the warping hypotheses n_alpha, n_psi, n_rho, rho_min,
    rho_max; blur_deg); omitted ones take the modules' defaults.
    `hidden` lists landmark indices invisible in the current views (occlusion). The grid runs in
    host-side chunks of `batch_size` points (memory bounded by the chunk, the same numbers for every
    chunk size); a grid of more than `max_points` points is refused with an estimate (`options._limits`).
    `grid`: a `Grid(spacing, clearance, heading_deg)` (core/grid.py; default `Grid()`);
    `sensor=Sensor(...)` and `noise=Noise(...)` may replace the sensor and noise keywords. The flat
    keywords of earlier releases (spacing=, heading_deg=, clearance=) still work for one release, with
    a DeprecationWarning.
    `progress`: a `Progress` (evaluate/_progress.py): `start(P)` once every option is valid, with the
    P grid points, then `progress(n, P)` after each chunk of n points (a plain `f(n, P)` also works).
    `chunk_program` stands in for one chunk's jitted program (the command line's, kept on disk).
    Returns a `VectorMap` pytree (points, included, heading, direction, valid, error_deg) that carries
    the `grid` it was computed on (`VectorMap.grid`, `.spacing`).
    """
    if "rules" in options:  # a keyword of the rollout calls: say why it does not apply here
        raise InputError("rules", options["rules"], "is not used by a vector map (one unit move per point, no rollout)")
    grid = legacy_config(Grid, grid, options)
    request, points = _checked_map(env, method, grid, seed, hidden, batch_size, max_points, **options)
    report = as_progress(progress)
    report.start(points.shape[0])
    vm = maps.vector_map(**request, progress=report, chunk_program=chunk_program, points=points)
    return dataclasses.replace(vm, grid=grid)  # the user's object, heading_deg as given
