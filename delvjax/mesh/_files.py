"""Mesh worlds and routes as the field ships them (docs/mesh.md §3), read from a path the user gives (they are
not ours to ship): the Seville world in InvertSy's `.mat` form (X, Y, Z, colp: (T, 3) each, metres) and
bob_robotics' `.bin` form (T x 12 float64, column-major [X Y Z colp]), Wavefront `.obj` meshes, and the recorded
ant routes (`AntRoutes.mat`: Ant<a>_Route<r>, N x 3 [x cm, y cm, heading deg]; bob's `ant<a>_route<r>.bin`: the
same, column-major). Every file is checked before it is used (`InputError` naming the file and what is wrong)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.errors import InputError

GROUND_RGB = (229 / 255, 183 / 255, 90 / 255)  # ImgGrabber_2013.m and bob_robotics (docs/mesh.md §3)
SKY_RGB = (0.0, 1.0, 1.0)  # cyan, ImgGrabber_2013.m and bob's ardin_mb
MAT_KEYS = ("X", "Y", "Z", "colp")


@dataclass
class MeshFile:
    """vertices (T, 3, 3) cm, z up; shade (T,) the file's grey level (colp; 0.5 for an .obj); source: the path."""

    vertices: np.ndarray
    shade: np.ndarray
    source: str


def read_mesh(path: str | Path, abs_z: bool = True) -> MeshFile:
    """A mesh world file (`.mat`, `.bin` or `.obj`; module docstring), in cm. abs_z: the blades whose apex the
    Seville file puts below the ground are flipped up, as ImgGrabber_2013.m draws them (131 of 5000)."""
    p = Path(path)
    if not p.is_file():
        raise InputError("mesh", str(path), "is no file")
    suffix = p.suffix.lower()
    if suffix == ".mat":
        x, y, z, colp = _mat_world(p)
    elif suffix == ".bin":
        x, y, z, colp = _bin_world(p)
    elif suffix == ".obj":
        v = _obj_vertices(p)
        return checked(MeshFile(v, np.full(len(v), 0.5), str(p)))
    else:
        raise InputError("mesh", str(path), "must be a .mat (InvertSy), .bin (bob_robotics) or .obj (Wavefront) file")
    z = np.abs(z) if abs_z else z
    v = np.stack([x, y, z], -1) * 100.0  # (T, 3 corners, 3) m -> cm
    return checked(MeshFile(v, colp[:, 0], str(p)))


def _mat_world(p: Path) -> tuple[np.ndarray, ...]:
    from scipy.io import loadmat  # scipy.io: loaded only when a .mat file is read

    try:
        data = loadmat(p)
    except Exception as exc:  # noqa: BLE001 - any failure to parse means "not a MATLAB file"
        raise InputError("mesh", str(p), f"is not a MATLAB .mat file ({type(exc).__name__})") from None
    missing = [k for k in MAT_KEYS if k not in data]
    if missing:
        raise InputError("mesh", str(p), f"has no variable {missing[0]} (a world .mat holds {', '.join(MAT_KEYS)})")
    arrays = [np.asarray(data[k], np.float64) for k in MAT_KEYS]
    if any(a.ndim != 2 or a.shape[1] != 3 or a.shape != arrays[0].shape for a in arrays):
        raise InputError("mesh", str(p), f"X, Y, Z and colp must be (T, 3) each, got {[list(a.shape) for a in arrays]}")
    return tuple(arrays)


def _bin_world(p: Path) -> tuple[np.ndarray, ...]:
    raw = np.fromfile(p, dtype="<f8")
    if raw.size == 0 or raw.size % 12:
        raise InputError("mesh", str(p), f"holds {raw.size} doubles, not 12 a triangle (bob_robotics' world .bin)")
    table = raw.reshape(12, -1).T  # column-major (T, 12): X1 X2 X3 Y1 Y2 Y3 Z1 Z2 Z3 colp colp colp
    return table[:, 0:3], table[:, 3:6], table[:, 6:9], table[:, 9:12]


def _obj_vertices(p: Path) -> np.ndarray:
    """Triangles (fans of every face) of a Wavefront .obj, its units taken as cm."""
    verts, faces = [], []
    try:
        lines = p.read_text().splitlines()
    except UnicodeDecodeError:
        raise InputError("mesh", str(p), "is not a text Wavefront .obj file") from None
    for n, line in enumerate(lines, 1):
        parts = line.split()
        if not parts or parts[0] not in ("v", "f"):
            continue
        try:
            if parts[0] == "v":
                verts.append([float(v) for v in parts[1:4]])
            else:
                idx = [int(f.split("/")[0]) for f in parts[1:]]
                faces += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
        except ValueError:
            raise InputError("mesh", f"{p}:{n}", f"cannot be read: {line.strip()[:60]!r}") from None
    v = np.asarray(verts, np.float64).reshape(-1, 3)
    f = np.asarray(faces, np.int64).reshape(-1, 3)
    f = np.where(f < 0, f + len(v), f - 1)  # 1-based, negative counts from the end
    if f.size and (f.min() < 0 or f.max() >= len(v)):
        raise InputError("mesh", str(p), f"a face names vertex {int(f.max()) + 1} of {len(v)}")
    return v[f]


def checked(m: MeshFile) -> MeshFile:
    """Refuse an empty mesh, a non-finite vertex and a degenerate (zero-area) triangle, naming the triangle."""
    v = m.vertices
    if v.shape[0] == 0:
        raise InputError("mesh", m.source, "holds no triangle")
    bad = ~np.isfinite(v).all((1, 2))
    if bad.any():
        raise InputError("mesh", m.source, f"triangle {int(np.argmax(bad))} has a non-finite vertex")
    area = np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=-1)
    flat = area <= 1e-9 * np.maximum(np.max(np.abs(v), (1, 2)) ** 2, 1.0)
    if flat.any():
        raise InputError("mesh", m.source, f"triangle {int(np.argmax(flat))} is degenerate (zero area)")
    return m


def matlab_green(shade: np.ndarray) -> np.ndarray:
    """(T, 3) colours as ImgGrabber_2013.m draws the grey levels: 64 green levels over their range
    (floor(k 255 / 63) / 255, k = floor((colp - min) / (max - min) 64) clipped to 63), red and blue 0."""
    lo, hi = float(np.min(shade)), float(np.max(shade))
    k = np.clip(np.floor((shade - lo) / max(hi - lo, 1e-12) * 64), 0, 63)
    g = np.floor(k * 255 / 63) / 255
    return np.stack([np.zeros_like(g), g, np.zeros_like(g)], -1)


def read_route(ant_route: str | Path, route_name: str = "Ant1_Route1") -> np.ndarray:
    """(N, 3) [x cm, y cm, heading rad counter-clockwise from +x] of a recorded route: variable `route_name` of
    the file `ant_route` (AntRoutes.mat), or a bob_robotics route .bin (N x 3 float64, column-major, heading in
    deg; `route_name` unused)."""
    p = Path(ant_route)
    if not p.is_file():
        raise InputError("ant_route", str(ant_route), "is no file")
    if p.suffix.lower() == ".mat":
        from scipy.io import loadmat  # scipy.io: loaded only when a .mat file is read

        try:
            data = loadmat(p)
        except Exception as exc:  # noqa: BLE001
            raise InputError("ant_route", str(p), f"is not a MATLAB .mat file ({type(exc).__name__})") from None
        routes = sorted(k for k in data if not k.startswith("__"))
        if route_name not in data:
            raise InputError("route_name", route_name, f"is not in {p.name} (it holds {', '.join(routes[:4])}, ...)")
        r = np.asarray(data[route_name], np.float64)
    elif p.suffix.lower() == ".bin":
        raw = np.fromfile(p, dtype="<f8")
        if raw.size == 0 or raw.size % 3:
            raise InputError("ant_route", str(p), f"holds {raw.size} doubles, not 3 a point (bob_robotics' route .bin)")
        r = raw.reshape(3, -1).T
    else:
        raise InputError("ant_route", str(p), "must be AntRoutes.mat or a bob_robotics route .bin")
    if r.ndim != 2 or r.shape[1] != 3 or r.shape[0] < 2 or not np.isfinite(r).all():
        raise InputError("ant_route", str(p), f"must be N >= 2 finite rows of x, y, heading, got {list(r.shape)}")
    return np.column_stack([r[:, 0], r[:, 1], np.radians(r[:, 2])])
