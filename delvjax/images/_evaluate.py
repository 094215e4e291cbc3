"""Evaluating homing methods on an image database (docs/images.md §6-7): load a BoB database or a
plain folder into ring snapshots, then vector maps and nearest-snapshot rollouts of any method.
Validation first (`InputError` naming the field, or the file, and the value)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Callable

import jax
import jax.numpy as jnp
import numpy as np

from ._render import DEFAULT_CHUNK, chunks, extract_rings, full, head
from ..core.errors import InputError
from ..core.images import Camera, Catadioptric, Extractor
from ..core.images.database import RingDatabase, database_directions, home_plan, move_plan, perceived_landmarks
from ..core.images.rollouts import OUTCOMES, Field, Paths, nearest_snapshot_rollouts
from ..core.maps import VectorMap
from ..core.rollouts import MAX_STEPS
from ..core.sensing import Snapshot
from ._disk import DatabaseIndex, read_image, read_images, read_index
from ..options._settings import finite, make_setup, non_negative, positive, positive_int, seed_value
from ._render import database_metadata
from ._disk import DatabaseWriter
from ._render import ImageSettings, check_render, render_rings, world_grid
from ..options._limits import MAX_POINTS

EXTRACTOR_FIELDS = ("hue_deg", "hue_width_deg", "sat_min", "val_min", "band_deg", "band_height_deg", "fill",
                    "max_blobs")


@dataclass
class LoadedDatabase:
    """A database as ring snapshots with what evaluating it needs (docs/images.md §6)."""
    name: str
    rings: RingDatabase
    files: list[Path]
    home: np.ndarray
    home_index: int
    arena: np.ndarray
    spacing: float
    camera: Camera
    extractor: Extractor
    obstacles: dict = field(default_factory=lambda: {"cylinders": [], "boxes": []})
    mirror: Catadioptric | None = None


def _pair(value, name: str, n: int) -> np.ndarray:
    v = [finite(x, name) for x in (value if isinstance(value, (list, tuple, np.ndarray)) else [value])]
    if len(v) != n:
        raise InputError(name, value, f"must be {n} numbers")
    return np.asarray(v, np.float64)


def _spacing(index: DatabaseIndex, spacing) -> float:
    if spacing is not None:
        return positive(spacing, "spacing")
    if "spacing_cm" in index.meta:
        return positive(index.meta["spacing_cm"], "spacing_cm")
    if len(index.positions) < 2:
        raise InputError("images", str(index.folder), "has one image: give the spacing (unit move) explicitly")
    from scipy.spatial import cKDTree  # scipy: loaded only where this is used, so that `import delvjax` stays light

    dist, _ = cKDTree(index.positions).query(index.positions, k=2)
    return positive(float(np.median(dist[:, 1])), "spacing (median distance between neighbouring images)")


def _arena(index: DatabaseIndex, arena, spacing: float) -> np.ndarray:
    if arena is not None:
        a = _pair(arena, "arena", 4)
    elif "arena_cm" in index.meta:
        a = _pair(index.meta["arena_cm"], "arena_cm", 4)
    else:
        a = np.concatenate([index.positions.min(0) - spacing / 2, index.positions.max(0) + spacing / 2])
    if not (a[0] < a[2] and a[1] < a[3]):
        raise InputError("arena", a.tolist(), "must be xmin < xmax and ymin < ymax")
    p = index.positions
    out = (p[:, 0] < a[0]) | (p[:, 0] > a[2]) | (p[:, 1] < a[1]) | (p[:, 1] > a[3])
    if out.any():
        i = int(np.argmax(out))
        raise InputError("image", str(index.files[i]), f"position ({p[i, 0]:g}, {p[i, 1]:g}) cm lies outside the "
                                                       f"arena {a.tolist()}")
    return a


def _extractor(index: DatabaseIndex, overrides: dict | None, channel: str | None, n_blobs: int | None) -> Extractor:
    settings = dict(index.meta.get("extractor") or {})
    for k, v in (overrides or {}).items():
        if k not in EXTRACTOR_FIELDS:
            raise InputError(k, v, f"unknown extractor setting (choose from {', '.join(EXTRACTOR_FIELDS)})")
        settings[k] = v
    out = {k: (positive_int(v, k) if k == "max_blobs" else finite(v, k)) for k, v in settings.items()
           if k in EXTRACTOR_FIELDS}
    if n_blobs is not None:
        out["max_blobs"] = positive_int(n_blobs, "max_blobs")
    if channel is not None:
        if channel not in ("mask", "gray"):
            raise InputError("channel", channel, "must be mask or gray")
        out["channel"] = channel
    return Extractor(**out)


def _camera(index: DatabaseIndex, shape: tuple[int, ...]) -> tuple[Camera, Catadioptric | None]:
    top, bottom = index.meta.get("elevation_deg", (30.0, -30.0))
    height = float(index.meta.get("camera_height_cm", 25.0))
    if not index.needs_unwrapping:
        return Camera(height=height, elev_top_deg=float(top), elev_bottom_deg=float(bottom), rows=shape[0],
                      cols=shape[1]), None
    if shape[0] != shape[1]:
        raise InputError("image", str(index.files[0]), f"is a donut image of {shape[1]} x {shape[0]} pixels: "
                                                       "it must be square")
    rows, cols = index.meta.get("panorama", (60, 360))
    mirror = Catadioptric(height=height, size=shape[0], **{k: float(v) for k, v in
                                                           (index.meta.get("catadioptric") or {}).items() if k != "size"})
    return Camera(height=height, elev_top_deg=float(top), elev_bottom_deg=float(bottom), rows=int(rows),
                  cols=int(cols)), mirror


def check_home_move(positions: np.ndarray, home_index: int, spacing: float, field: str, value) -> None:
    """`InputError` when home has no image one spacing away along an axis (the home record's unit move,
    docs/images.md §6)."""
    if not home_plan(positions, np.zeros(len(positions)), home_index, spacing, 4).ok[0]:
        raise InputError(field, str(value), f"has no image {spacing:g} cm (one spacing) east, north, west or south "
                                            "of it: the home record needs that unit move")


def load_database(src: str | Path, home=None, arena=None, spacing: float | None = None, channel: str | None = None,
                  extractor: dict | None = None, max_blobs: int | None = None, chunk: int = DEFAULT_CHUNK,
                  progress: Callable[[int, int], None] | None = None,
                  sink: Callable[[np.ndarray, slice], None] | None = None) -> LoadedDatabase:
    """Read a database (docs/images.md §4) into ring snapshots, `chunk` images at a time. home, arena,
    spacing: override the metadata (else: the metadata, else the point nearest the arena's centre,
    the positions' extent, the median neighbour distance); extractor: Extractor settings by name;
    sink(images, rows): called with every chunk of images read (`import_database`)."""
    index = read_index(src)
    chunk = positive_int(chunk, "chunk")
    spacing = _spacing(index, spacing)
    a = _arena(index, arena, spacing)
    ex = _extractor(index, extractor, channel, max_blobs)
    target = _pair(home, "home", 2) if home is not None else (
        np.asarray(index.meta["home_cm"], float) if "home_cm" in index.meta else (a[:2] + a[2:]) / 2)
    dist = np.linalg.norm(index.positions - target, axis=-1)
    home_index = int(np.argmin(dist))
    if home is not None and dist[home_index] > spacing / 2:
        raise InputError("home", list(target), f"has no image within spacing / 2 = {spacing / 2:g} cm")
    check_home_move(index.positions, home_index, spacing, "home", index.files[home_index])
    shape = read_image(index.files[0]).shape
    cam, mirror = _camera(index, shape)
    if not mirror and cam.cols % 4:
        raise InputError("image", str(index.files[0]), f"is {cam.cols} columns wide: it must be a multiple of 4")
    parts = []
    size = min(chunk, len(index.files))
    for lo, hi in chunks(len(index.files), size):
        images = read_images(index, range(lo, hi), shape)
        parts.append(head(extract_rings(jnp.asarray(full(images, size)), cam, mirror, ex), hi - lo))
        if sink:
            sink(images, slice(lo, hi))
        if progress:
            progress(hi - lo, len(index.files))
    snaps = jax.tree.map(lambda *x: jnp.concatenate(x), *parts)
    rings = RingDatabase(snaps, jnp.asarray(index.positions), jnp.asarray(index.headings))
    obstacles = index.meta.get("obstacles") or {"cylinders": [], "boxes": []}
    return LoadedDatabase(index.meta.get("world", index.folder.name), rings, index.files,
                          index.positions[home_index].astype(np.float64), home_index, a, spacing, cam, ex, obstacles,
                          mirror)


def with_channel(db: RingDatabase, channel: str) -> RingDatabase:
    """The database with the image methods reading `channel` (mask or gray) of every snapshot."""
    s = db.snapshots
    snap = Snapshot(mask=s.mask, gray=s.gray, bearing=s.bearing, width=s.width, valid=s.valid, channel=channel)
    return RingDatabase(snap, db.positions, db.headings)


def plans(db: LoadedDatabase):
    """(the unit move ending at every point, the home record's move) of a database (docs/images.md §6)."""
    pos, head = np.asarray(db.rings.positions), np.asarray(db.rings.headings)
    plan = jax.tree.map(jnp.asarray, move_plan(pos, head, db.spacing, db.camera.cols))
    home = jax.tree.map(jnp.asarray, home_plan(pos, head, db.home_index, db.spacing, db.camera.cols))
    return plan, home


def perceived(db: LoadedDatabase, delv) -> np.ndarray:
    """World positions of the landmarks in the reference map of `delv` (a `DELV` module; Fig 4.20)."""
    xy, valid = perceived_landmarks(db.rings, plans(db)[1], delv)
    return np.asarray(xy)[np.asarray(valid)]


def database_vector_map(db: LoadedDatabase, method="delv", home_rings: RingDatabase | None = None, program=None,
                        **options) -> VectorMap:
    """The homing direction of `method` at every database point (docs/images.md §6). `options`: method
    settings and `channel` as in `api.vector_map`; `home_rings`: take the home record from another
    rendering of the same positions (e.g. other lighting); `program`: registry names compiled into one
    program with `method` (`registry.program`). The home point itself is not included."""
    module, sensor = make_setup(method, program, n_pix=db.camera.cols, **options)
    rings = with_channel(db.rings, sensor.channel)
    home_db = rings if home_rings is None else with_channel(home_rings, sensor.channel)
    plan, home = plans(db)
    pos = np.asarray(db.rings.positions)
    direction, valid, error = database_directions(rings, plan, home_db, home, module, jnp.asarray(db.home, jnp.float32))
    included = np.arange(len(pos)) != db.home_index
    return VectorMap(points=jnp.asarray(pos), included=jnp.asarray(included), heading=jnp.asarray(
        np.arctan2(*(pos[np.asarray(plan.end)] - pos[np.asarray(plan.start)]).T[::-1]), jnp.float32),
        direction=direction, valid=valid, error_deg=error)


def database_rollouts(db: LoadedDatabase, vm: VectorMap, starts, step: float | None = None,
                      home_radius: float | None = None, max_steps: int = MAX_STEPS,
                      motion_heading_noise_deg: float = 0.0, motion_step_noise: float = 0.0, seed: int = 0,
                      collisions: bool = True) -> Paths:
    """Nearest-snapshot rollouts (docs/images.md §7) from `starts` (T, 2) cm on the directions of `vm`.
    step and home_radius default to the spacing; the database's obstacles (rendered databases list
    them) end a trial where `collisions`."""
    step = db.spacing if step is None else positive(step, "step")
    home_radius = db.spacing if home_radius is None else non_negative(home_radius, "home_radius")
    max_steps = positive_int(max_steps, "max_steps")
    noise = jnp.asarray([math.radians(non_negative(motion_heading_noise_deg, "motion_heading_noise_deg")),
                         non_negative(motion_step_noise, "motion_step_noise")], jnp.float32)
    key = jax.random.fold_in(jax.random.PRNGKey(seed_value(seed)), 3)
    obs = db.obstacles if collisions else {}
    cyl = np.asarray(obs.get("cylinders") or np.zeros((0, 3)), np.float32).reshape(-1, 3)
    box = np.asarray(obs.get("boxes") or np.zeros((0, 4)), np.float32).reshape(-1, 4)
    f = Field(db.rings.positions, vm.direction, vm.valid, jnp.asarray(db.home, jnp.float32),
              jnp.asarray(db.arena, jnp.float32), jnp.asarray(cyl), jnp.asarray(box))
    return nearest_snapshot_rollouts(f, jnp.asarray(starts, jnp.float32).reshape(-1, 2), key, jnp.float32(step),
                                     jnp.float32(home_radius), noise, max_steps)


def database_catchment(db: LoadedDatabase, vm: VectorMap, home_radius: float | None = None, **options
                       ) -> tuple[np.ndarray, Paths]:
    """Catchment (docs/images.md §7): `database_rollouts` from every database point farther than
    `home_radius` (default: the spacing) from home: (release points (T, 2), Paths)."""
    radius = db.spacing if home_radius is None else non_negative(home_radius, "home_radius")
    pos = np.asarray(db.rings.positions)
    starts = pos[np.linalg.norm(pos - db.home, axis=-1) > radius]
    return starts, database_rollouts(db, vm, starts, home_radius=radius, **options)


def catchment_numbers(paths: Paths) -> dict:
    """Catchment (%) and the share of every other outcome (%), mean steps of the successes."""
    code = np.asarray(paths.outcome)
    n = max(len(code), 1)
    out = {"releases": int(len(code)), "catchment_pct": 100.0 * float(np.sum(code == 0)) / n}
    out.update({f"{name}_pct": 100.0 * float(np.sum(code == i)) / n for i, name in enumerate(OUTCOMES) if i})
    steps = np.asarray(paths.steps)[code == 0]
    out["mean_steps_success"] = float(steps.mean()) if steps.size else float("nan")
    return out


def import_database(src: str | Path, out: str | Path, **options) -> LoadedDatabase:
    """Read a database (BoB or a plain folder; `load_database` options), check every image, and write
    it as a BoB database at `out` with delvjax metadata (docs/images.md §4); nothing is left at `out`
    if any image fails."""

    index = read_index(src)
    spacing = _spacing(index, options.get("spacing"))
    arena = _arena(index, options.get("arena"), spacing)
    writer = DatabaseWriter(out)

    grid = np.round((index.positions - arena[:2] - spacing / 2) / spacing).astype(int)
    on_cells = len(np.unique(grid, axis=0)) == len(grid)  # else (a route, a jittered grid) files by entry number

    def sink(images: np.ndarray, rows: slice) -> None:
        writer.add(images, index.positions[rows], index.headings[rows], grid[rows], donut=index.needs_unwrapping,
                   first=None if on_cells else rows.start)

    try:
        db = load_database(src, sink=sink, **options)
        writer.commit(database_metadata(db.name, db.arena, db.home, db.spacing, db.camera, db.mirror, db.extractor,
                                        db.obstacles))
    except BaseException:
        writer.discard()
        raise
    return db


def render_in_memory(env: str, spacing: float | None = None, settings=None, seed: int = 0,
                      extractor: Extractor | None = None, chunk: int = DEFAULT_CHUNK) -> LoadedDatabase:
    """The database `render_database` would write, rendered and reduced to rings in memory (no files;
    ring for ring what `load_database` reads back from them, docs/images.md §5)."""

    settings = settings or ImageSettings()
    iw, spacing = check_render(env, spacing, settings, seed, MAX_POINTS, chunk)
    pts, _ = world_grid(iw, spacing)
    ex = extractor or iw.extractor
    rings = render_rings(iw, settings, pts, np.zeros(len(pts), np.float32), jax.random.PRNGKey(seed), ex, chunk)
    home_index = int(np.argmin(np.linalg.norm(pts - np.asarray(iw.home), axis=-1)))
    check_home_move(pts, home_index, spacing, "env", env)
    return LoadedDatabase(iw.name, rings, [], pts[home_index].astype(np.float64), home_index,
                          np.asarray(iw.world.arena, np.float64), spacing, settings.camera, ex, iw.obstacles(),
                          settings.mirror)


rendered_database = render_in_memory  # the name until 0.1 (CHANGELOG): `render_database` writes files, this does not
