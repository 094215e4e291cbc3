"""BoB robotics' image-database reader, emulated check for check (BoB's src/navigation/image_database.cc,
`ImageDatabase::loadMetadata` and `loadCSV`), with OpenCV's own YAML parser; and BoB-format databases
built the way BoB's ant-world tools write them (its docs' example_grid and example_route), from
panoramas rendered by delvjax.

BoB's ant-world camera (docs/images.md §4.1): the centre column looks along the heading, a compass
bearing (clockwise from +y); columns run clockwise; the route recorder's heading of a segment is
90 deg - atan2(dy, dx).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

DEFAULT_FIELDS = (
    "X [mm]",
    "Y [mm]",
    "Z [mm]",
    "Heading [degrees]",
    "Filename",
    "Grid X",
    "Grid Y",
    "Grid Z",
    "Pitch [degrees]",
    "Roll [degrees]",
    "Frame",
)


class BoBAssert(AssertionError):
    """Where BoB's reader would stop (BOB_ASSERT or a thrown std::runtime_error)."""


def _check(cond: bool, what: str) -> None:
    if not cond:
        raise BoBAssert(what)


def _stod(text: str) -> float:
    """std::stod as BoB calls it: an empty field is NaN; "nan", "-nan", "inf" parse; junk throws."""
    if text == "":
        return math.nan
    try:
        return float(text.replace("-nan", "nan"))
    except ValueError:
        raise BoBAssert(f"stod({text!r})") from None


def _stoul(text: str) -> int:
    _check(text.isdigit(), f"stoul({text!r}): a grid cell must be an unsigned integer")
    return int(text)


def bob_read(folder: Path) -> dict:
    """What BoB's `ImageDatabase(folder)` reads, or `BoBAssert` where it would stop: the metadata through
    OpenCV's FileStorage (BoB prepends "%YAML:1.0\\n" to the file, as here), `type` grid or route,
    the camera's resolution, then the CSV: the first four default columns and Filename present, every
    Grid column for a grid, every row as many fields as the header, numbers by stod, cells by stoul,
    and (as `Entry::load`) every image readable by cv2.imread at the camera's resolution."""
    import cv2

    meta_path = folder / "database_metadata.yaml"
    out: dict = {"type": "route", "resolution": None}
    if meta_path.exists():
        text = "%YAML:1.0\n" + meta_path.read_text()
        try:
            fs = cv2.FileStorage(text, cv2.FileStorage_READ | cv2.FileStorage_MEMORY)
        except cv2.error as exc:
            raise BoBAssert(f"OpenCV cannot parse the metadata: {exc}") from None
        meta = fs.getNode("metadata")
        kind = meta.getNode("type").string()
        if kind not in ("grid", "route"):
            raise BoBAssert(f'Invalid database type "{kind}"')
        out["type"] = kind
        cam = meta.getNode("camera")
        if cam.isMap():
            res = cam.getNode("resolution")
            _check(res.isSeq() and res.size() == 2, "camera.resolution must be two integers")
            out["resolution"] = (int(res.at(0).real()), int(res.at(1).real()))
        out["metadata"] = meta
        out["storage"] = fs
    lines = (folder / "database_entries.csv").read_text().splitlines()
    fields = [f.strip() for f in lines[0].split(",")]
    idx = [fields.index(n) if n in fields else -1 for n in DEFAULT_FIELDS]
    _check(all(i >= 0 for i in idx[:4]), "the first four default columns")
    _check(idx[4] >= 0, "the Filename column")
    if out["type"] == "grid":
        _check(all(i >= 0 for i in idx[5:8]), "every Grid column of a grid database")
    entries = []
    for line in lines[1:]:
        line = line.strip()
        if not line:
            continue
        parts = [p.strip() for p in line.split(",")]
        _check(len(parts) == len(fields), f"row {line!r} has {len(parts)} fields, the header {len(fields)}")
        e = {
            "xyz": tuple(_stod(parts[idx[k]]) for k in range(3)),
            "heading": _stod(parts[idx[3]]),
            "path": folder / parts[idx[4]],
        }
        if out["type"] == "grid":
            e["grid"] = tuple(_stoul(parts[idx[k]]) for k in (5, 6, 7))
        entries.append(e)
    for e in entries:
        img = cv2.imread(str(e["path"]), cv2.IMREAD_COLOR)
        _check(img is not None, f"Could not load image file at {e['path']}")
        if out["resolution"] is not None:
            _check((img.shape[1], img.shape[0]) == out["resolution"], f"{e['path'].name} is not the camera's size")
    out["entries"] = entries
    return out


# --- BoB-format databases made from delvjax panoramas ------------------------------------------------


def compass_deg(math_deg: np.ndarray) -> np.ndarray:
    """A world angle (counter-clockwise from +x) as a compass bearing (clockwise from +y), [0, 360)."""
    return np.mod(90.0 - np.asarray(math_deg, np.float64), 360.0)


def bob_file_image(memory: np.ndarray, column0_deg: float, bob_heading_deg: float) -> np.ndarray:
    """The file a BoB ant-world camera at compass heading `bob_heading_deg` stores, from a delvjax
    memory-order panorama whose column 0 looks along `column0_deg` (math): file column c looks along
    the bearing heading + 360 (c - W // 2) / W (clockwise), so file column W // 2 looks along the heading."""
    w = memory.shape[1]
    c = np.arange(w)
    world = 90.0 - (bob_heading_deg + 360.0 * (c - w // 2) / w)  # math angle seen by file column c
    j = np.round(np.mod(world - column0_deg, 360.0) * w / 360.0).astype(int) % w  # the memory column
    return memory[:, j]


def write_bob_database(
    folder: Path, images: list[np.ndarray], xyz_mm: np.ndarray, headings: np.ndarray, kind: str, names=None
) -> Path:
    """A database exactly as BoB's example_grid / example_route are written: `X [mm], ...` CSV with ", "
    separators (grid: the Grid columns and `image_%+07d_%+07d_%+07d.png` names; route:
    `image_%05d.png` as in the example), metadata with time, type, grid block, camera opengl, no
    delvjax block. Images are file-order uint8 RGB (saved as BGR by cv2, as BoB does)."""
    import cv2

    folder.mkdir(parents=True)
    n = len(images)
    xyz_mm = np.asarray(xyz_mm, np.float64)
    if names is None:
        names = (
            ["image_" + "_".join(f"{int(round(v)):+07d}" for v in p) + ".png" for p in xyz_mm]
            if kind == "grid"
            else [f"image_{i:05d}.png" for i in range(n)]
        )
    for im, name in zip(images, names):
        assert cv2.imwrite(str(folder / name), np.ascontiguousarray(im[..., ::-1]))
    header = ["X [mm]", "Y [mm]", "Z [mm]", "Heading [degrees]", "Filename"]
    meta = ["%YAML:1.0", "---", "metadata:", '   time: "2019-01-29 13:05:14"', f"   type: {kind}"]
    rows = []
    if kind == "grid":
        header += ["Grid X", "Grid Y", "Grid Z"]
        xs, ys = np.unique(xyz_mm[:, 0]), np.unique(xyz_mm[:, 1])
        sep = [float(np.diff(xs).min()) if len(xs) > 1 else 0.0, float(np.diff(ys).min()) if len(ys) > 1 else 0.0]
        meta += [
            "   grid:",
            f"      beginAtMM: [ {float(xs[0])!r}, {float(ys[0])!r}, {float(xyz_mm[0, 2])!r} ]",
            f"      separationMM: [ {sep[0]!r}, {sep[1]!r}, 0. ]",
            f"      size: [ {len(xs)}, {len(ys)}, 1 ]",
        ]
    for i, (p, h, name) in enumerate(zip(xyz_mm, headings, names)):
        row = [f"{p[0]:g}", f"{p[1]:g}", f"{p[2]:g}", f"{h:g}", name]
        if kind == "grid":
            row += [str(int(round((p[0] - xs[0]) / sep[0]))), str(int(round((p[1] - ys[0]) / sep[1]))), "0"]
        rows.append(", ".join(row))
    h, w = images[0].shape[:2]
    meta += [
        "   camera:",
        "      name: opengl",
        f"      resolution: [ {w}, {h} ]",
        "      isPanoramic: 0",
        "   needsUnwrapping: 0",
        "   isGreyscale: 0",
    ]
    (folder / "database_entries.csv").write_text(", ".join(header) + "\n" + "\n".join(rows) + "\n")
    (folder / "database_metadata.yaml").write_text("\n".join(meta) + "\n")
    return folder
