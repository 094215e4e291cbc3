"""A mesh world ready to render (docs/mesh.md §2-4): a file's mesh or a generated habitat as a `Mesh` (core/mesh/mesh.py)
with the reference renderers' colours, and checked panoramas of it at many poses."""

from __future__ import annotations

import numpy as np
from jax.typing import ArrayLike

from ..core.errors import InputError
from ..core.mesh.eye import ANT_EYE, Eye
from ..core.mesh.mesh import Mesh, make_mesh
from ..core.mesh.render import mesh_panoramas
from ._files import GROUND_RGB, SKY_RGB, MeshFile, checked, matlab_green
from ._habitat import Habitat

__all__ = ["ANT_EYE", "Eye", "mesh_world", "panoramas"]
MAX_POSES = 1_000_000


def mesh_world(source: MeshFile | Habitat, colours: str = "matlab") -> Mesh:
    """The mesh of a file (`read_mesh`) or a habitat, grass green: "matlab" (ImgGrabber_2013.m's 64 levels over
    the grey range, test_img's colours) or "shade" (green = the grey level, bob_robotics'); the ground
    (229, 183, 90) and a cyan sky."""
    if colours not in ("matlab", "shade"):
        raise InputError("colours", colours, "must be matlab or shade")
    m = checked(MeshFile(np.asarray(source.vertices, np.float64), np.asarray(source.shade, np.float64), source.name
                         if isinstance(source, Habitat) else source.source))  # fmt: skip
    green = matlab_green(m.shade) if colours == "matlab" else np.stack([0 * m.shade, m.shade, 0 * m.shade], -1)
    return make_mesh(m.vertices, green, ground_rgb=GROUND_RGB, sky_rgb=SKY_RGB)


def panoramas(mesh: Mesh, poses: ArrayLike | list | tuple, eye: Eye = ANT_EYE, batch: int = 16) -> np.ndarray:
    """(N, rows, cols, 3) colour panoramas at poses (N, 4..6) [x, y, z cm, heading[, pitch, roll] rad], checked
    first (finite, at most MAX_POSES); `batch` poses rendered side by side (docs/mesh.md §2)."""
    p = np.asarray(poses, np.float64)
    if p.ndim == 1:
        p = p[None]
    if p.ndim != 2 or not 4 <= p.shape[1] <= 6 or len(p) == 0:
        raise InputError("poses", list(p.shape), "must be (N, 4..6): x, y, z cm, heading[, pitch, roll] rad")
    if len(p) > MAX_POSES:
        raise InputError("poses", len(p), f"must be at most {MAX_POSES} (split the call)")
    bad = ~np.isfinite(p).all(1)
    if bad.any():
        raise InputError(f"poses[{int(np.argmax(bad))}]", p[bad][0].tolist(), "must be finite")
    return np.asarray(mesh_panoramas(mesh, eye, p.astype(np.float32), batch=batch))
