"""Image databases on disk (docs/images.md §4): the BoB robotics layout and plain folders.

BoB layout: a folder with `database_entries.csv` (columns `X [mm], Y [mm], Z [mm], Heading [degrees],
Filename, Grid X, Grid Y, Grid Z`), `database_metadata.yaml` (OpenCV-style YAML; delvjax adds a
`delvjax:` block with the arena, home, spacing, camera and obstacles) and one PNG per entry. A
plain folder: images plus `positions.csv` with columns `filename, x, y` and optionally
`heading_deg` (cm, deg). Panorama files store the unmirrored view: file column c looks along
heading - 360 c / W (clockwise to the right); in memory column j looks along heading + 360 j / W.
Every reading error names the file (`InputError`, exit 2 in the CLI).
"""

from __future__ import annotations

import csv
import math
import os
import shutil
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from collections.abc import Iterable

import numpy as np

from ..core.errors import InputError
from ._metadata import check_metadata
from ..outputs._temporary import fsync_path, fsync_tree, new_temp_dir, ordinary_permissions

METADATA = "database_metadata.yaml"
ENTRIES = "database_entries.csv"
POSITIONS = "positions.csv"
BOB_COLUMNS = ("X [mm]", "Y [mm]", "Z [mm]", "Heading [degrees]", "Filename", "Grid X", "Grid Y", "Grid Z")
THREADS = 8  # image decoding and encoding (Pillow releases the GIL)
MAX_PIXELS = 4096 * 4096  # per image file, checked from its header before it is decoded


def file_columns(images: np.ndarray, axis: int = -2) -> np.ndarray:
    """Memory <-> file column order of panoramas (..., H, W, 3), or of any array whose columns are
    `axis` (a mask (H, W), a ring (W,): axis=-1). Self-inverse: column j <-> -j mod W."""
    return np.roll(np.flip(images, axis=axis), 1, axis=axis)


@dataclass
class DatabaseIndex:
    """What a database folder lists: files, positions (N, 2) cm, headings (N,) rad and its metadata
    (`meta`: the `delvjax` block, empty for other databases; `camera`: the BoB camera block)."""

    folder: Path
    files: list[Path]
    positions: np.ndarray
    headings: np.ndarray
    meta: dict = field(default_factory=dict)
    needs_unwrapping: bool = False


def _number(text: str, what: str, path: Path, row: int) -> float:
    try:
        v = float(text)
    except (TypeError, ValueError):
        raise InputError(what, str(path), f"row {row}: {text!r} is not a number") from None
    if not math.isfinite(v):
        raise InputError(what, str(path), f"row {row}: {text!r} is not finite")
    return v


def _rows(path: Path) -> list[dict[str, str]]:
    """The rows of an index CSV (a UTF-8 byte-order mark is allowed); a row with more fields than the
    header, or one that repeats an earlier row, is refused naming the row (row 1 is the header)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            reader = csv.DictReader(fh, skipinitialspace=True)
            raw = list(reader)
            fields = [f.strip() for f in reader.fieldnames or []]
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise InputError("images", str(path), f"cannot be read ({exc})") from None
    seen: dict[tuple, int] = {}
    for i, r in enumerate(raw):
        if None in r:
            raise InputError(
                "images", str(path), f"row {i + 2} has {len(fields) + len(r[None])} fields, the header {len(fields)}"
            )
        key = tuple((v or "").strip() for v in r.values())
        if key in seen:
            raise InputError("images", str(path), f"row {i + 2} repeats row {seen[key]}")
        seen[key] = i + 2
    rows = [{(k or "").strip(): (v or "").strip() for k, v in r.items()} for r in raw]
    if not rows:
        raise InputError("images", str(path), "lists no images")
    return rows if fields else []


def _read_yaml(path: Path) -> dict:
    import yaml  # PyYAML: loaded only for a database's metadata

    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("images", str(path), f"cannot be read ({exc})") from None
    lines = [ln for ln in text.splitlines() if not ln.startswith("%YAML")]  # OpenCV writes "%YAML:1.0"
    try:
        data = yaml.safe_load("\n".join(lines)) or {}
    except yaml.YAMLError as exc:
        raise InputError("images", str(path), f"is not valid YAML ({str(exc).splitlines()[0]})") from None
    return data.get("metadata", data) if isinstance(data, dict) else {}


def read_index(src: str | Path) -> DatabaseIndex:
    """The entries of a BoB database or a plain folder with positions.csv (module docstring)."""
    folder = Path(src)
    if not folder.is_dir():
        raise InputError("images", str(src), "is not a folder")
    if (folder / ENTRIES).is_file():
        rows = _rows(folder / ENTRIES)
        need = ("X [mm]", "Y [mm]", "Filename")
        keys = {"x": "X [mm]", "y": "Y [mm]", "heading": "Heading [degrees]", "file": "Filename"}
        scale, path = 0.1, folder / ENTRIES
    elif (folder / POSITIONS).is_file():
        rows = _rows(folder / POSITIONS)
        need = ("filename", "x", "y")
        keys = {"x": "x", "y": "y", "heading": "heading_deg", "file": "filename"}
        scale, path = 1.0, folder / POSITIONS
    else:
        raise InputError("images", str(src), f"has neither {ENTRIES} (BoB layout) nor {POSITIONS}")
    missing = [c for c in need if not rows or c not in rows[0]]
    if missing:
        raise InputError("images", str(path), f"lacks the column(s) {', '.join(missing)}")
    pos = (
        np.array(
            [
                [_number(r[keys["x"]], "images", path, i + 2), _number(r[keys["y"]], "images", path, i + 2)]
                for i, r in enumerate(rows)
            ]
        )
        * scale
    )
    head = np.radians([_number(r.get(keys["heading"]) or "0", "images", path, i + 2) for i, r in enumerate(rows)])
    files = [folder / r[keys["file"]] for r in rows]
    first: dict[Path, int] = {}
    for i, f in enumerate(files):
        if first.setdefault(f, i + 2) != i + 2:
            raise InputError("images", str(path), f"row {i + 2} lists {f.name} again (row {first[f]})")
    meta = _read_yaml(folder / METADATA) if (folder / METADATA).is_file() else {}
    return DatabaseIndex(
        folder,
        files,
        pos.astype(np.float32),
        head.astype(np.float32),
        meta=dict(check_metadata(meta.get("delvjax"), folder / METADATA)),
        needs_unwrapping=bool(meta.get("needsUnwrapping", 0)),
    )


def read_image(path: Path) -> np.ndarray:
    """An RGB uint8 array (H, W, 3) of an image file (Pillow), as stored (file column order; `read_images`
    turns panoramas into memory order)."""
    from PIL import Image, UnidentifiedImageError  # Pillow: loaded only when image files are read or written

    if not path.is_file():
        raise InputError("image", str(path), "does not exist")
    try:
        with Image.open(path) as im:  # reads the header only
            w, h = im.size
            if w * h > MAX_PIXELS:
                raise Image.DecompressionBombError(f"{w} x {h} pixels")
            return np.asarray(im.convert("RGB"))
    except Image.DecompressionBombError as exc:  # from its header, before the pixels are decoded
        size = str(exc) if " x " in str(exc) else "its header's size"
        raise InputError("image", str(path), f"is {size}, more than {MAX_PIXELS} pixels (a panorama is far smaller)")
    except (OSError, UnidentifiedImageError, ValueError) as exc:
        raise InputError("image", str(path), f"cannot be read ({type(exc).__name__}: {exc})") from None


def read_images(index: DatabaseIndex, rows: Iterable[int], shape: tuple[int, ...] | None = None) -> np.ndarray:
    """(k, H, W, 3) uint8 images of entries `rows` (panoramas in memory column order); every image must
    have `shape` (default: the first one's)."""
    paths = [index.files[i] for i in rows]
    with ThreadPoolExecutor(THREADS) as pool:
        images = list(pool.map(read_image, paths))
    shape = shape or images[0].shape
    for p, im in zip(paths, images):
        if im.shape != tuple(shape):
            raise InputError(
                "image",
                str(p),
                f"is {im.shape[1]} x {im.shape[0]} pixels, the database's images {shape[1]} x {shape[0]}",
            )
    stack = np.stack(images)
    return stack if index.needs_unwrapping else file_columns(stack)


def bob_filename(gx: int, gy: int) -> str:
    return f"image_{gx:+05d}_{gy:+05d}_+0000.png"


class DatabaseWriter:
    """Writes a BoB database into a temporary folder beside `out`; `commit` renames it into place, so a
    failed or interrupted run leaves no partial database (`out` must not exist or be empty)."""

    def __init__(self, out: str | Path):
        self.out = Path(os.path.realpath(out)) if Path(out).is_symlink() else Path(out)  # a link: its folder
        if self.out.exists() and (not self.out.is_dir() or any(self.out.iterdir())):
            raise InputError("--out", str(out), "exists and is not an empty folder")
        self.out.parent.mkdir(parents=True, exist_ok=True)
        self.tmp = new_temp_dir(self.out.parent)
        self.rows: list[list] = []
        self.pool = ThreadPoolExecutor(THREADS)

    def add(
        self,
        images: np.ndarray,
        positions: np.ndarray,
        headings: np.ndarray,
        grid: np.ndarray,
        donut: bool = False,
        first: int | None = None,
    ) -> None:
        """Images (k, H, W, 3) uint8 in memory order, positions (k, 2) cm, headings (k,) rad, grid (k, 2) int.
        Files are named by grid cell; with `first` (entries not on distinct grid cells, e.g. a route) by
        entry number, `image_{first + i:05d}.png`, as BoB names route images."""
        from PIL import Image  # Pillow: loaded only when image files are read or written

        names = (
            [bob_filename(int(gx), int(gy)) for gx, gy in grid]
            if first is None
            else [f"image_{first + i:05d}.png" for i in range(len(grid))]
        )
        files = images if donut else file_columns(images)
        try:
            list(
                self.pool.map(
                    lambda a: Image.fromarray(a[0]).save(self.tmp / a[1], compress_level=1), zip(files, names)
                )
            )
        except OSError as exc:
            raise InputError("--out", str(self.out), f"could not be written ({exc.strerror or exc})") from None
        for (x, y), h, (gx, gy), name in zip(positions, headings, grid, names):
            self.rows.append(
                [
                    round(float(x) * 10, 3),
                    round(float(y) * 10, 3),
                    0,
                    round(math.degrees(float(h)), 6),
                    name,
                    int(gx),
                    int(gy),
                    0,
                ]
            )

    def commit(self, metadata: dict) -> None:
        try:
            self._commit(metadata)
        except OSError as exc:
            raise InputError("--out", str(self.out), f"could not be written ({exc.strerror or exc})") from None

    def _commit(self, metadata: dict) -> None:
        import yaml  # PyYAML: loaded only for a database's metadata

        with open(self.tmp / ENTRIES, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(BOB_COLUMNS)
            w.writerows(self.rows)
        (self.tmp / METADATA).write_text("%YAML:1.0\n---\n" + yaml.safe_dump({"metadata": metadata}, sort_keys=False))
        self.pool.shutdown()
        fsync_tree(self.tmp)
        ordinary_permissions(self.tmp)  # a database is an ordinary folder
        if self.out.exists():
            self.out.rmdir()
        os.replace(self.tmp, self.out)
        fsync_path(self.out.parent)

    def discard(self) -> None:
        self.pool.shutdown(wait=True)
        shutil.rmtree(self.tmp, ignore_errors=True)
