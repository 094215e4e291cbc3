"""Image databases of a mesh world in BoB's layout (docs/mesh.md §7): a grid database (points every `spacing` cm
within the world's band about its route, column 0 facing +x) or a route database (every `spacing` cm along the
recorded route, column 0 facing along it, files named as BoB's route recorder names them), panoramas over the
full circle and the ant eye's band of elevation, the eye `eye_height` cm above the ground: the green channel in
all three of a PNG's channels by default (what the ant models see, docs/mesh.md §6: a gray image of the colours
would lose the skyline, the ground and the cyan sky being of nearly one luminance), or the colours. Checked before any
work; nothing is left at `out` if it fails (`images/_writer.py`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import positive, positive_int
from ..core.errors import InputError
from ..core.familiarity.mesh_views import ANT_BAND_DEG
from ..core.images import Camera, Extractor, to_uint8
from ..core.mesh.eye import Eye
from ..core.mesh.render import mesh_panoramas
from ..core.polyline import headings_along, resample, route_length
from ..images._render import database_metadata
from ..images._writer import DatabaseWriter
from ..options._limits import MAX_POINTS, check_size, grid_count
from ._site import MeshSite, mesh_site

KINDS = ("grid", "route")
BATCH = 16  # poses rendered side by side


def database_poses(
    s: MeshSite, kind: str, spacing: float, band: float | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(N, 2) positions cm, (N,) column-0 headings rad and (N, 2) grid cells (None on a route) of a database; a
    grid's points lie within `band` cm of the route (default the world's band)."""
    if kind == "route":
        p = resample(s.waypoints(), spacing)
        return p, headings_along(p), None
    p = s.field_points(spacing, band, "spacing").astype(np.float64)
    cells = np.round((p - s.arena[:2] - spacing / 2) / spacing).astype(int)
    return p, np.zeros(len(p)), cells


def render_mesh_database(
    world: str | MeshSite,
    out: str | Path,
    *,
    kind: str = "grid",
    spacing: float | None = None,
    band: float | None = None,
    rows: int = 76,
    cols: int = 360,
    colour: bool = False,
    chunk: int = 256,
    max_points: int = MAX_POINTS,
    progress: Callable[[int, int], None] | None = None,
) -> dict:
    """Render a database of `world` (a generated habitat by name, or a `MeshSite`) into `out` (module
    docstring): rows x cols panoramas (default 76 x 360: 1 deg a column, 75/76 deg a row, so that 19 x 90 views
    are 4 x 4 block means), the colours if `colour`, else the green channel; spacing: default the world's grid spacing on a grid, 4 cm on a route; band: a grid's
    points lie within it of the route (cm, default the world's). Returns a summary."""
    s = mesh_site(world) if isinstance(world, str) else world
    if kind not in KINDS:
        raise InputError("kind", kind, f"must be one of {', '.join(KINDS)}")
    spacing = positive((s.spacing if kind == "grid" else 4.0) if spacing is None else spacing, "spacing")
    rows, cols, chunk = positive_int(rows, "rows"), positive_int(cols, "cols"), positive_int(chunk, "chunk")
    if band is not None:
        if kind != "grid":
            raise InputError("band", band, "applies to a grid database")
        band = positive(band, "band")
    estimate = grid_count(s.arena, spacing) if kind == "grid" else int(route_length(s.waypoints()) / spacing) + 2
    check_size(estimate, max_points, "spacing", spacing, "mesh image")  # before the points are made
    pos, heading, cells = database_poses(s, kind, spacing, band)
    if len(pos) < (1 if kind == "grid" else 2):
        raise InputError("spacing", spacing, f"leaves too few {kind} points in {s.name}")
    top, bottom = ANT_BAND_DEG
    eye = Eye(rows=rows, cols=cols, width_deg=360.0, elev_top_deg=top, elev_bottom_deg=bottom)
    cam = Camera(height=s.eye_height, elev_top_deg=top, elev_bottom_deg=bottom, rows=rows, cols=cols)
    keep = (lambda c: c) if colour else (lambda c: jnp.repeat(c[..., 1:2], 3, -1))  # the green channel, as gray
    render = jax.jit(lambda p: to_uint8(keep(mesh_panoramas(s.mesh, eye, p, batch=BATCH))))
    writer = DatabaseWriter(out)
    try:
        for lo in range(0, len(pos), chunk):  # host-side chunks bound the memory; one program for every chunk
            hi = min(lo + chunk, len(pos))
            poses = np.zeros((chunk, 4), np.float32)  # a short last chunk padded: one shape, one program
            poses[: hi - lo] = np.column_stack([pos[lo:hi], np.full(hi - lo, s.eye_height), heading[lo:hi]])
            images = np.asarray(render(poses))[: hi - lo]
            xyz_mm = np.column_stack([pos[lo:hi], np.full(hi - lo, s.eye_height)]) * 10.0
            writer.add(images, xyz_mm, np.degrees(heading[lo:hi]), None if cells is None else cells[lo:hi])
            if progress:
                progress(hi - lo, len(pos))
        extra = {"mesh_triangles": int(np.sum(np.asarray(s.mesh.valid))), "kind": kind,
                 "pixels": "colour" if colour else "green channel"}  # fmt: skip
        writer.commit(
            database_metadata(s.name, s.arena, s.home, spacing, cam, None, Extractor(), s.obstacles(), **extra)
        )
    except BaseException:
        writer.discard()
        raise
    return {"world": s.name, "kind": kind, "images": len(pos), "spacing_cm": spacing, "out": str(out)}
