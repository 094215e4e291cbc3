"""Writing an image database in BoB's layout (docs/images.md §4): BoB's entries CSV (its columns,
`%.17e` numbers, `nan`), OpenCV-readable metadata with `type` and the `grid` block, BoB's file names,
the images in the declared conventions (docs/images.md §4.1)."""

from __future__ import annotations

import math
import os
import shutil
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.errors import InputError
from ..outputs._temporary import fsync_path, fsync_tree, new_temp_dir, ordinary_permissions
from ._conventions import BOB, Conventions
from ._disk import ENTRIES, METADATA, THREADS

BOB_COLUMNS = ("X [mm]", "Y [mm]", "Z [mm]", "Heading [degrees]", "Pitch [degrees]", "Roll [degrees]", "Filename")
BOB_GRID_COLUMNS = ("Grid X", "Grid Y", "Grid Z")


def bob_grid_filename(x_mm: float, y_mm: float, z_mm: float) -> str:
    """BoB's grid image name: the position in whole millimetres, `image_%+07d_%+07d_%+07d.png`."""
    return "image_" + "_".join(f"{int(round(v)):+07d}" for v in (x_mm, y_mm, z_mm)) + ".png"


def bob_route_filename(i: int) -> str:
    """BoB's route image name (`RouteRecorder`): `image%05d.png`, counted from 1."""
    return f"image{i + 1:05d}.png"


def precise(value: float) -> str:
    """A number as BoB writes it (`writePreciseString`: scientific, 17 digits; NaN as `nan`)."""
    return "nan" if math.isnan(value) else f"{value:.17e}"


class _OpenCVDumper:
    """PyYAML's emitter made to write what OpenCV's FileStorage parser reads: block sequences indented
    under their key (OpenCV rejects `- x` at the key's indentation), leaf lists in flow style."""

    @staticmethod
    def dump(data: dict) -> str:
        import yaml  # PyYAML: loaded only for a database's metadata

        class Dumper(yaml.SafeDumper):
            def increase_indent(self, flow=False, indentless=False):
                return super().increase_indent(flow, False)

        return "%YAML:1.0\n---\n" + yaml.dump(
            data, Dumper=Dumper, sort_keys=False, default_flow_style=None, indent=3, width=1 << 16
        )


@dataclass
class Entry:
    """One database entry to write: memory-order image data goes to the pool, the row to the CSV."""

    x_mm: float
    y_mm: float
    z_mm: float
    heading_deg: float
    name: str
    grid: tuple[int, int, int] | None


class DatabaseWriter:
    """Writes a BoB database (module docstring) into a temporary folder beside `out`; `commit` renames
    it into place, so a failed or interrupted run leaves no partial database (`out` must not exist or
    be empty). Images arrive in memory order with their world heading of column 0; they are stored in
    `conventions` (BoB's by default) and the metadata declares them."""

    def __init__(self, out: str | Path, conventions: Conventions = BOB):
        self.out = Path(os.path.realpath(out)) if Path(out).is_symlink() else Path(out)  # a link: its folder
        if self.out.exists() and (not self.out.is_dir() or any(self.out.iterdir())):
            raise InputError("--out", str(out), "exists and is not an empty folder")
        self.out.parent.mkdir(parents=True, exist_ok=True)
        self.tmp = new_temp_dir(self.out.parent)
        self.conventions = conventions
        self.entries: list[Entry] = []
        self.pool = ThreadPoolExecutor(THREADS)

    def add(
        self,
        images: np.ndarray,
        xyz_mm: np.ndarray,
        column0_deg: np.ndarray,
        grid: np.ndarray | None,
        donut: bool = False,
        stored: np.ndarray | None = None,
    ) -> None:
        """Images (k, H, W, 3) uint8 in memory order, positions and heights (k, 3) mm (a NaN height: not
        known), world headings of column 0 (k,) deg, grid cells (k, 2) int, or None for a route (files
        named by entry number, as BoB's route recorder names them); `stored`: the headings to write
        as they are (a database copied in its own conventions keeps its numbers exactly)."""
        from PIL import Image  # Pillow: loaded only when image files are read or written

        width = images.shape[2]
        mm, z_mm = np.asarray(xyz_mm, np.float64)[:, :2], np.asarray(xyz_mm, np.float64)[:, 2]
        n0 = len(self.entries)
        names = [
            bob_grid_filename(x, y, 0.0 if math.isnan(zz) else zz) if grid is not None else bob_route_filename(n0 + i)
            for i, ((x, y), zz) in enumerate(zip(mm, z_mm))
        ]
        if stored is None:
            stored = column0_deg if donut else self.conventions.stored_deg(column0_deg, width)
        files = images if donut else self.conventions.to_file(images)
        try:
            list(
                self.pool.map(
                    lambda a: Image.fromarray(a[0]).save(self.tmp / a[1], compress_level=1), zip(files, names)
                )
            )
        except OSError as exc:
            raise InputError("--out", str(self.out), f"could not be written ({exc.strerror or exc})") from None
        for i, ((x, y), zz, h, name) in enumerate(zip(mm, z_mm, np.asarray(stored, np.float64), names)):
            cell = None if grid is None else (int(grid[i][0]), int(grid[i][1]), 0)
            self.entries.append(Entry(float(x), float(y), float(zz), float(h), name, cell))

    def commit(self, metadata: dict) -> None:
        try:
            self._commit(metadata)
        except OSError as exc:
            raise InputError("--out", str(self.out), f"could not be written ({exc.strerror or exc})") from None

    def _commit(self, metadata: dict) -> None:
        is_grid = all(e.grid is not None for e in self.entries)
        names = [e.name for e in self.entries]
        if len(set(names)) != len(names):  # two grid entries within a millimetre
            raise InputError("--out", str(self.out), "two entries would share the image name " + names[0])
        with open(self.tmp / ENTRIES, "w", newline="") as fh:  # BoB's addNewEntries: ", " between fields
            fh.write(", ".join(BOB_COLUMNS + (BOB_GRID_COLUMNS if is_grid else ())) + "\n")
            for e in self.entries:
                row = [precise(e.x_mm), precise(e.y_mm), precise(e.z_mm), precise(e.heading_deg), "nan", "nan", e.name]
                fh.write(", ".join(row + ([str(v) for v in e.grid] if is_grid else [])) + "\n")
        bob = {
            "type": "grid" if is_grid else "route"
        }  # no `time`: BoB reads it only if present; files stay reproducible
        if is_grid and self.entries:
            bob["grid"] = grid_block(self.entries)
        bob.update(metadata)
        bob.update(self.conventions.metadata())
        (self.tmp / METADATA).write_text(_OpenCVDumper.dump({"metadata": bob}))
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


def grid_block(entries: list[Entry]) -> dict:
    """BoB's `grid` metadata block: beginAtMM (the first cell's position), separationMM, size."""
    g = np.array([e.grid for e in entries])
    xyz = np.array([[e.x_mm, e.y_mm, 0.0 if math.isnan(e.z_mm) else e.z_mm] for e in entries])
    lo, span = g.min(0), g.max(0) - g.min(0)
    sep = np.array([(xyz[:, k].max() - xyz[:, k].min()) / span[k] if span[k] else 0.0 for k in range(3)])
    i = int(np.argmin(np.abs(g - lo).sum(1)))  # the entry nearest the first cell
    begin = [float(v) for v in xyz[i] - sep * (g[i] - lo)]
    sep = [float(v) for v in sep]
    return {"beginAtMM": begin, "separationMM": sep, "size": [int(v) for v in span + 1]}
