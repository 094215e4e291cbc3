"""Loading an image database (docs/images.md §6): a BoB database or a plain folder read into ring
snapshots at its positions, with its camera, extractor, spacing and arena checked first (`InputError`
naming the field, or the file, and the value)."""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from ..core.batching import pad_rows
from ..core.checks import finite, positive, positive_int
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.images import Camera, Catadioptric, Extractor
from ..core.images.database import RingDatabase, home_plan
from ..options._schema import extractor_options
from ._conventions import Conventions
from ._disk import DatabaseIndex, read_image, read_images, read_index
from ._render import DEFAULT_CHUNK, chunks, extract_rings, head


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
    kind: str = "grid"
    origin: np.ndarray = field(default_factory=lambda: np.zeros(2))
    heading_deg: np.ndarray | None = None  # (N,) the headings as stored, and how they were read
    conventions: Conventions | None = None

    def absolute(self, xy) -> np.ndarray:
        """Positions of this database's frame (relative to `origin`, float64) in the database's own cm."""
        return np.asarray(xy, np.float64) + self.origin


FAR = 1e5  # cm: beyond 1 km from (0, 0), positions are taken relative to an origin (float32 keeps 8 mm there)
CAMERAS = {  # BoB camera name -> (elevation top, bottom) deg, where the camera's metadata does not say
    "opengl": (60.0, -15.0),  # BoB's ant-world renderer: 75 deg from -15 to +60 (docs/images.md §4.2)
}


class DatabaseWarning(UserWarning):
    """A choice made for a database that its files did not state (the nearest image as home, an assumed camera)."""


def _warn(message: str) -> None:
    warnings.warn(message, DatabaseWarning, stacklevel=3)


def _pair(value, name: str, n: int) -> np.ndarray:
    v = [finite(x, name) for x in (value if isinstance(value, (list, tuple, np.ndarray)) else [value])]
    if len(v) != n:
        raise InputError(name, value, f"must be {n} numbers")
    return np.asarray(v, np.float64)


def database_spacing(index: DatabaseIndex, spacing) -> float:
    if spacing is not None:
        return positive(spacing, "spacing")
    if "spacing_cm" in index.meta:
        return positive(index.meta["spacing_cm"], "spacing_cm")
    sep = (index.bob.get("grid") or {}).get("separationMM") if isinstance(index.bob.get("grid"), dict) else None
    if isinstance(sep, list) and len(sep) >= 2 and all(isinstance(v, (int, float)) for v in sep[:2]):
        nonzero = [float(v) for v in sep[:2] if v and math.isfinite(v) and v > 0]
        if nonzero and len(set(nonzero)) == 1:  # BoB's grid block: one separation along x and y
            return nonzero[0] / 10.0
    if len(index.positions) < 2:
        raise InputError("images", str(index.folder), "has one image: give the spacing (unit move) explicitly")
    from scipy.spatial import cKDTree  # scipy: loaded only where this is used, so that `import delvjax` stays light

    dist, _ = cKDTree(index.positions).query(index.positions, k=2)
    return positive(float(np.median(dist[:, 1])), "spacing (median distance between neighbouring images)")


def database_arena(index: DatabaseIndex, arena, spacing: float) -> np.ndarray:
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
        raise InputError(
            "image", str(index.files[i]), f"position ({p[i, 0]:g}, {p[i, 1]:g}) cm lies outside the arena {a.tolist()}"
        )
    return a


def _extractor(index: DatabaseIndex, overrides: dict | None, channel: str | None, n_blobs: int | None) -> Extractor:
    known = extractor_options()
    settings = dict(index.meta.get("extractor") or {})
    for k, v in (overrides or {}).items():
        if k not in known:
            raise InputError(k, v, f"unknown extractor setting (choose from {', '.join(known)})")
        settings[k] = v
    out = {known[k].field: known[k].validate(v) for k, v in settings.items() if k in known}
    if n_blobs is not None:
        out["max_blobs"] = positive_int(n_blobs, "max_blobs")
    if channel is not None:
        if channel not in ("mask", "gray"):
            raise InputError("channel", channel, "must be mask or gray")
        out["channel"] = channel
    return Extractor(**out)


def camera_geometry(index: DatabaseIndex, elevation, camera_height, warn) -> tuple[float, float, float]:
    """(top, bottom elevation deg, camera height cm) of a database (docs/images.md §4.2): the caller's
    values, else the metadata's (delvjax block; BoB camera names of known geometry; the entries' Z as
    the camera height), else +30/-30 deg and 25 cm with a warning naming the assumption."""
    name = (index.bob.get("camera") or {}).get("name") if isinstance(index.bob.get("camera"), dict) else None
    if elevation is not None:
        top, bottom = (float(v) for v in _pair(elevation, "elevation", 2))
    elif "elevation_deg" in index.meta:
        top, bottom = index.meta["elevation_deg"]
    elif name in CAMERAS:
        top, bottom = CAMERAS[name]
    else:
        top, bottom = 30.0, -30.0
        warn(
            f"{index.folder}: the metadata gives no vertical field of view: rows are taken to span +30 to -30 deg "
            "(give --elevation TOP BOTTOM)"
        )
    if not -90 <= bottom < top <= 90:
        raise InputError(
            "elevation", f"{top:g} {bottom:g}", "must be TOP BOTTOM with -90 <= bottom < top <= 90 degrees"
        )
    z = index.z
    if camera_height is not None:
        height = positive(camera_height, "camera_height")
    elif "camera_height_cm" in index.meta:
        height = float(index.meta["camera_height_cm"])
    elif np.isfinite(z).all() and (z > 0).all():
        height = float(np.median(z))  # BoB's Z: the camera's height above the floor
    else:
        height = 25.0
        warn(f"{index.folder}: no camera height stored (Z): 25 cm taken (give --camera-height)")
    return float(top), float(bottom), height


def _camera(
    index: DatabaseIndex, shape: tuple[int, ...], elevation=None, camera_height=None, warn=_warn
) -> tuple[Camera, Catadioptric | None]:
    top, bottom, height = camera_geometry(index, elevation, camera_height, warn)
    if not index.needs_unwrapping:
        return Camera(
            height=height, elev_top_deg=float(top), elev_bottom_deg=float(bottom), rows=shape[0], cols=shape[1]
        ), None
    if shape[0] != shape[1]:
        raise InputError(
            "image", str(index.files[0]), f"is a donut image of {shape[1]} x {shape[0]} pixels: it must be square"
        )
    rows, cols = index.meta.get("panorama", (60, 360))
    mirror = Catadioptric(
        height=height,
        size=shape[0],
        **{k: float(v) for k, v in (index.meta.get("catadioptric") or {}).items() if k != "size"},
    )
    return Camera(
        height=height, elev_top_deg=float(top), elev_bottom_deg=float(bottom), rows=int(rows), cols=int(cols)
    ), mirror


def database_origin(positions: np.ndarray) -> np.ndarray:
    """(0, 0), or for positions beyond FAR: the lowest corner rounded down to whole metres (docs/images.md §4)."""
    if not len(positions) or np.abs(positions).max() <= FAR:
        return np.zeros(2)
    return np.floor(positions.min(0) / 100.0) * 100.0


def choose_home(index: DatabaseIndex, home, arena: np.ndarray, spacing: float, warn) -> int:
    """The home image (docs/images.md §6): the one at `home` (the caller's, else the metadata's home_cm),
    else the route's last image, else the image nearest the arena's centre. A stated home without an
    image there takes the nearest image, with a warning naming the distance; more than one spacing away
    is refused."""
    if home is not None:
        target, field_name = _pair(home, "home", 2), "home"
    elif "home_cm" in index.meta:
        target, field_name = np.asarray(index.meta["home_cm"], np.float64), "home_cm"
    elif index.kind == "route":
        return len(index.positions) - 1
    else:
        return int(np.argmin(np.linalg.norm(index.positions - (arena[:2] + arena[2:]) / 2, axis=-1)))
    dist = np.linalg.norm(index.positions - target, axis=-1)
    i = int(np.argmin(dist))
    where = f"({target[0]:g}, {target[1]:g})"
    if dist[i] > spacing:
        raise InputError(
            field_name, where, f"has no image within one spacing ({spacing:g} cm): the nearest is {dist[i]:g} cm away"
        )
    if dist[i] > 1e-6 * spacing:
        p = index.positions[i]
        warn(
            f"home {where} has no image: the nearest, {index.files[i].name} at ({p[0]:g}, {p[1]:g}), {dist[i]:.3g} cm away, is home"
        )
    return i


def check_home_move(positions: np.ndarray, home_index: int, spacing: float, field: str, value) -> None:
    """`InputError` when home has no image one spacing away along an axis (the home record's unit move,
    docs/images.md §6)."""
    if not home_plan(positions, np.zeros(len(positions)), home_index, spacing, 4).ok[0]:
        raise InputError(
            field,
            str(value),
            f"has no image {spacing:g} cm (one spacing) east, north, west or south "
            "of it: the home record needs that unit move",
        )


@keywords_after(
    1,
    (
        "home",
        "arena",
        "spacing",
        "channel",
        "extractor",
        "max_blobs",
        "chunk",
        "progress",
        "sink",
        "check",
        "conventions",
        "elevation",
        "camera_height",
        "warn",
        "panoramas",
    ),
)
def load_database(
    src: str | Path,
    *,
    home=None,
    arena=None,
    spacing: float | None = None,
    channel: str | None = None,
    extractor: dict | None = None,
    max_blobs: int | None = None,
    chunk: int = DEFAULT_CHUNK,
    progress: Callable[[int, int], None] | None = None,
    sink: Callable[[np.ndarray, slice], None] | None = None,
    check: Callable[[int, int], None] | None = None,
    conventions: dict | None = None,
    elevation=None,
    camera_height: float | None = None,
    warn: Callable[[str], None] = _warn,
    panoramas: bool = False,
) -> LoadedDatabase:
    """Read a database (docs/images.md §4) into ring snapshots, `chunk` images at a time. home, arena,
    spacing: override the metadata (else: the metadata, else `choose_home`, the positions' extent, the
    median neighbour distance); extractor: Extractor settings by name; conventions: heading,
    heading_column, columns (docs/images.md §4.1) where the database does not declare them;
    elevation [top, bottom] deg and camera_height cm: override the metadata; warn(message): every
    choice the files did not state (default: a `DatabaseWarning`); sink(images, rows): called with every
    chunk of images read (`import_database`); check(images, ring pixels): called before any image but
    the first is read (the caller's own checks); panoramas: keep every gray panorama too (the methods that
    read them, MinWarping; docs/model.md §4.7)."""
    index = read_index(src, conventions)
    chunk = positive_int(chunk, "chunk")
    spacing = database_spacing(index, spacing)
    a = database_arena(index, arena, spacing)
    ex = _extractor(index, extractor, channel, max_blobs)
    if panoramas:
        ex = dataclasses.replace(ex, panorama=True)
    home_index = choose_home(index, home, a, spacing, warn)
    if index.kind == "grid":
        check_home_move(index.positions, home_index, spacing, "home", index.files[home_index])
    shape = read_image(index.files[0]).shape
    cam, mirror = _camera(index, shape, elevation, camera_height, warn)
    if not mirror and cam.cols % 4:
        raise InputError("image", str(index.files[0]), f"is {cam.cols} columns wide: it must be a multiple of 4")
    headings = index.headings(shape[1]) if not index.needs_unwrapping else np.radians(index.heading_deg)
    if np.isnan(headings).any():
        i = int(np.argmax(np.isnan(headings)))
        raise InputError(
            "image",
            str(index.files[i]),
            "has no heading (nan): every method turns the views into the unit move's frame by it (docs/images.md §6)",
        )
    if check is not None:
        check(len(index.files), cam.cols)
    parts = []
    size = min(chunk, len(index.files))
    for lo, hi in chunks(len(index.files), size):
        images = read_images(index, range(lo, hi), shape)
        parts.append(head(extract_rings(jnp.asarray(pad_rows(images, size)), cam, mirror, ex), hi - lo))
        if sink:
            sink(images, slice(lo, hi))
        if progress:
            progress(hi - lo, len(index.files))
    snaps = jax.tree.map(lambda *x: jnp.concatenate(x), *parts)
    origin = database_origin(index.positions)
    rel = index.positions - origin
    rings = RingDatabase(snaps, jnp.asarray(rel, jnp.float32), jnp.asarray(headings, jnp.float32))
    obstacles = index.meta.get("obstacles") or {"cylinders": [], "boxes": []}
    if origin.any():
        shift = {"cylinders": np.r_[origin, 0.0], "boxes": np.r_[origin, origin]}
        obstacles = {k: [list(np.asarray(r, np.float64) - shift[k]) for r in v] for k, v in obstacles.items()}
    return LoadedDatabase(
        index.meta.get("world", index.folder.name),
        rings,
        index.files,
        rel[home_index],
        home_index,
        a - np.r_[origin, origin],
        spacing,
        cam,
        ex,
        obstacles,
        mirror,
        index.kind,
        origin,
        index.heading_deg,
        index.conventions,
    )


def with_channel(db: RingDatabase, channel: str) -> RingDatabase:
    """The database with the image methods reading `channel` (mask or gray) of every snapshot."""
    s = db.snapshots
    return RingDatabase(dataclasses.replace(s, channel=channel), db.positions, db.headings)
