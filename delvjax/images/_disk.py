"""Image databases on disk (docs/images.md §4): the BoB robotics layout and plain folders.

BoB layout (read and written as BoB's `ImageDatabase` does): `database_entries.csv` (BoB's columns
`X [mm], Y [mm], Z [mm], Heading [degrees], Pitch [degrees], Roll [degrees], Filename` and, for a
grid, `Grid X, Grid Y, Grid Z`; numbers as `%.17e`, NaN as `nan`), `database_metadata.yaml` (OpenCV
FileStorage YAML: `type: grid|route`, a `grid` block, BoB's `camera` block, the declared conventions
of `_conventions.py`, and a `delvjax:` block with the arena, home, spacing, camera and obstacles) and
one PNG per entry (`image_%+07d_%+07d_%+07d.png` in mm for a grid, `image%05d.png` for a route).
A plain folder: images plus `positions.csv` with columns `filename, x, y` and optionally
`heading_deg` (cm, deg). Positions and headings stay float64 on the host (UTM millimetres keep
their digits). Every reading error names the file (`InputError`, exit 2 in the CLI).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.errors import InputError
from ..core.images.database import route_checks
from ._conventions import BOB, DELVJAX_BEFORE, PLAIN, Conventions, declared, file_columns, resolve
from ._metadata import check_metadata

__all__ = ["file_columns", "read_index", "read_images"]

METADATA = "database_metadata.yaml"
ENTRIES = "database_entries.csv"
POSITIONS = "positions.csv"
THREADS = 8  # image decoding and encoding (Pillow releases the GIL)
MAX_PIXELS = 4096 * 4096  # per image file, checked from its header before it is decoded


@dataclass
class DatabaseIndex:
    """What a database folder lists: files, positions and heights as stored (N, 3) float64 mm (NaN where
    a height is not stored); stored headings (N,) deg as written (NaN where missing) and how to read them
    (`conventions`); `kind` grid or route; `meta`: the `delvjax` block (empty for other databases),
    `bob`: BoB's own metadata fields."""

    folder: Path
    files: list[Path]
    xyz_mm: np.ndarray
    heading_deg: np.ndarray
    conventions: Conventions = DELVJAX_BEFORE
    kind: str = "grid"
    meta: dict = field(default_factory=dict)
    bob: dict = field(default_factory=dict)
    needs_unwrapping: bool = False

    @property
    def positions(self) -> np.ndarray:
        """(N, 2) float64 cm."""
        return self.xyz_mm[:, :2] / 10.0

    @property
    def z(self) -> np.ndarray:
        """(N,) float64 cm, NaN where not stored."""
        return self.xyz_mm[:, 2] / 10.0

    def headings(self, width: int) -> np.ndarray:
        """(N,) float64 rad: the world heading of memory column 0 of every image (NaN kept)."""
        return np.radians(self.conventions.column0_deg(self.heading_deg, width))


def _number(text: str, what: str, path: Path, row: int, finite: bool = True) -> float:
    """A CSV number; an empty field is NaN (as BoB and pandas read it); NaN only where not `finite`."""
    try:
        v = float(text) if text != "" or finite else math.nan
    except (TypeError, ValueError):
        raise InputError(what, str(path), f"row {row}: {text!r} is not a number") from None
    if finite and not math.isfinite(v):
        raise InputError(what, str(path), f"row {row}: {text!r} is not finite")
    if not finite and math.isinf(v):
        raise InputError(what, str(path), f"row {row}: {text!r} is infinite")
    return v


def _rows(path: Path) -> list[dict[str, str]]:
    """The rows of an index CSV (a UTF-8 byte-order mark is allowed); a row with more fields than the
    header, or one that repeats an earlier row, is refused naming the row (row 1 is the header)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            reader = csv.DictReader(fh, skipinitialspace=True)
            raw = [r for r in reader if any((v or "").strip() for v in r.values() if isinstance(v, str))]
            fields = [f.strip() for f in reader.fieldnames or []]
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise InputError("images", str(path), f"cannot be read ({exc})") from None
    other = next((sep for sep in ";\t|" if len(fields) == 1 and sep in fields[0]), None)
    if other is not None:  # a spreadsheet's export in a locale with decimal commas
        raise InputError(
            "images",
            str(path),
            f"separates its fields with {other!r}, not ',' (delvjax reads comma-separated values with '.' "
            "decimals: export as 'CSV (comma delimited)' or convert, e.g. pandas.read_csv(f, sep=';', decimal=',')"
            ".to_csv(f, index=False))",
        )
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
    data = data.get("metadata", data) if isinstance(data, dict) else {}
    return data if isinstance(data, dict) else {}


def _conventions(folder: Path, bob: dict, layout: str, given: dict) -> Conventions:
    """docs/images.md §4.1: declared in the metadata, else BoB's for a BoB database with BoB's metadata,
    delvjax's former ones for a database delvjax wrote before it declared them, the documented ones of
    positions.csv; a BoB entries file without metadata cannot tell."""
    own = declared(bob, folder / METADATA)
    if layout == "plain":
        default = PLAIN
    elif "delvjax" in bob and not own:
        default = DELVJAX_BEFORE
    elif bob:
        default = BOB
    else:
        default = None
    return resolve(own, default, given, str(folder / METADATA) if bob else str(folder))


def read_index(src: str | Path, conventions: dict | None = None) -> DatabaseIndex:
    """The entries of a BoB database or a plain folder with positions.csv (module docstring);
    `conventions`: heading, heading_column, columns chosen by the caller (docs/images.md §4.1)."""
    folder = Path(src)
    if not folder.is_dir():
        raise InputError("images", str(src), "is not a folder")
    if (folder / ENTRIES).is_file():
        rows = _rows(folder / ENTRIES)
        need = ("X [mm]", "Y [mm]", "Filename")
        keys = {"x": "X [mm]", "y": "Y [mm]", "z": "Z [mm]", "heading": "Heading [degrees]", "file": "Filename"}
        scale, path, layout = 1.0, folder / ENTRIES, "bob"
    elif (folder / POSITIONS).is_file():
        rows = _rows(folder / POSITIONS)
        need = ("filename", "x", "y")
        keys = {"x": "x", "y": "y", "z": "z", "heading": "heading_deg", "file": "filename"}
        scale, path, layout = 10.0, folder / POSITIONS, "plain"
    else:
        raise InputError("images", str(src), f"has neither {ENTRIES} (BoB layout) nor {POSITIONS}")
    missing = [c for c in need if not rows or c not in rows[0]]
    if missing:
        raise InputError("images", str(path), f"lacks the column(s) {', '.join(missing)}")
    num = lambda r, k, i, finite=True: _number(r.get(keys[k], ""), "images", path, i + 2, finite)  # noqa: E731
    xyz = np.array([[num(r, "x", i), num(r, "y", i), num(r, "z", i, False)] for i, r in enumerate(rows)], np.float64)
    xyz = xyz if scale == 1.0 else xyz * scale
    head = np.array(
        [num(r, "heading", i, False) if keys["heading"] in r else 0.0 for i, r in enumerate(rows)], np.float64
    )
    files = [folder / r[keys["file"]] for r in rows]
    first: dict[Path, int] = {}
    for i, f in enumerate(files):
        if first.setdefault(f, i + 2) != i + 2:
            raise InputError("images", str(path), f"row {i + 2} lists {f.name} again (row {first[f]})")
    bob = _read_yaml(folder / METADATA) if (folder / METADATA).is_file() else {}
    kind = bob.get("type")
    if kind is not None and kind not in ("grid", "route"):
        raise InputError("images", str(folder / METADATA), f"type must be grid or route, got {kind!r}")
    if kind is None:  # as BoB decides without metadata: a grid if the entries have grid columns
        kind = "grid" if layout == "plain" or "Grid X" in rows[0] or "delvjax" in bob else "route"
    if kind == "route":
        route_checks(xyz[:, :2], [f.name for f in files], str(path))
    return DatabaseIndex(
        folder,
        files,
        xyz,
        head,
        conventions=_conventions(folder, bob, layout, conventions or {}),
        kind=kind,
        meta=dict(check_metadata(bob.get("delvjax"), folder / METADATA)),
        bob={k: v for k, v in bob.items() if k != "delvjax"},
        needs_unwrapping=bool(bob.get("needsUnwrapping", 0)),
    )


SIXTEEN_BIT = ("I;16", "I;16L", "I;16B", "I;16N")  # Pillow's modes of a 16-bit grayscale file (PNG, TIFF)


def rgb8(im, path: Path) -> np.ndarray:
    """An RGB uint8 array of an opened Pillow image. A 16-bit (or 32-bit integer holding 16-bit) grayscale image
    keeps its top 8 bits: Pillow's `convert("RGB")` clips it, so a 16-bit PNG was read as white (issue 53). A
    floating-point image has no agreed range and is refused."""
    if im.mode in SIXTEEN_BIT or im.mode == "I":
        gray = np.asarray(im).astype(np.int64)
        if gray.min() < 0 or gray.max() > 65535:
            raise InputError("image", str(path), f"is a {im.mode} image with values outside 0-65535 (not 16-bit)")
        return np.repeat((gray >> 8).astype(np.uint8)[..., None], 3, axis=-1)
    if im.mode == "F":
        raise InputError("image", str(path), "is a floating-point image: save it as 8- or 16-bit")
    return np.asarray(im.convert("RGB"))


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
            return rgb8(im, path)
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
    return stack if index.needs_unwrapping else index.conventions.to_memory(stack)
