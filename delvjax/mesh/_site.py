"""A mesh world with a route, ready for the familiarity experiments (docs/mesh.md §6): the generated habitat by
name (`habitat`, `habitat<seed>`) or the user's files (a world and a recorded ant route). It answers what the
route experiments ask of a world (`familiarity/_run.py`): a name, an arena, a home (the route's end), which
points are clear (inside the arena: an agent walks through the grass) and the heading field's grid (points
within `band` cm of the route). Checked before any work (`InputError` naming the field and the value)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.errors import InputError
from ..core.grid import grid_points
from ..core.mesh.mesh import Mesh
from ..core.polyline import distance_to
from ..options._limits import MAX_POINTS, check_size, grid_count
from ._files import MeshFile, read_mesh, read_route
from ._habitat import Habitat, habitat
from ._world import mesh_world

HABITAT = re.compile(r"habitat(\d*)$")
EYE_HEIGHT = 1.0  # cm: the ant eye above the ground (Ardin et al. 2016; InvertSy's test_img.mat)


@dataclass
class MeshSite:
    """mesh: the world; route (N, 3) [x, y cm, heading rad] as recorded; arena (4,) cm; spacing: the heading
    field's grid (cm); band: its points lie within this of the route (cm); footprint (T, 3, 2): the triangles'
    corners seen from above (figures)."""

    name: str
    mesh: Mesh
    route: np.ndarray
    arena: np.ndarray
    footprint: np.ndarray
    eye_height: float = EYE_HEIGHT
    spacing: float = 20.0
    band: float = 100.0

    @property
    def world(self) -> Mesh:
        return self.mesh

    @property
    def home(self) -> tuple[float, float]:
        return float(self.route[-1, 0]), float(self.route[-1, 1])

    def waypoints(self) -> np.ndarray:
        """(N, 2) the recorded route's points, repeated neighbours dropped (an ant that stood still)."""
        p = self.route[:, :2]
        keep = np.append(True, np.hypot(*np.diff(p, axis=0).T) > 1e-9)
        return p[keep]

    def clear(self, points: np.ndarray) -> np.ndarray:
        """(N,) True where a point (N, 2) is inside the arena (nothing else stops an agent)."""
        a = self.arena
        x, y = points[:, 0], points[:, 1]
        return (x >= a[0]) & (x <= a[2]) & (y >= a[1]) & (y <= a[3])

    def obstacles(self) -> dict[str, list]:
        return {"cylinders": [], "boxes": []}

    def field_points(self, spacing: float, band: float | None = None, field: str = "grid_spacing") -> np.ndarray:
        """(P, 2) grid points every `spacing` cm of the arena within `band` cm (default the site's) of the route;
        a grid of more than MAX_POINTS cells is refused before it is built (`InputError` naming `field`)."""
        check_size(grid_count(self.arena, spacing), MAX_POINTS, field, spacing)
        pts = grid_points(self.arena, spacing)
        return pts[distance_to(pts, self.route) <= (self.band if band is None else band)]


def site(source: Habitat | MeshFile, mesh: Mesh, route: np.ndarray, arena: np.ndarray, name: str) -> MeshSite:
    """A `MeshSite`, its route checked: at least two points, finite, inside the arena."""
    route = np.asarray(route, np.float64)
    s = MeshSite(name, mesh, route, np.asarray(arena, np.float64), np.asarray(source.vertices)[..., :2])
    if len(s.waypoints()) < 2:
        raise InputError("ant_route", name, "needs at least two distinct points")
    out = ~s.clear(route[:, :2])
    if out.any():
        at = route[int(np.argmax(out)), :2].round(1).tolist()
        raise InputError("ant_route", name, f"leaves the world at {at} (its arena is {s.arena.round(1).tolist()})")
    return s


def is_mesh_name(name: str) -> bool:
    """Whether `name` names a generated habitat (habitat, habitat0, habitat17, ...)."""
    return bool(HABITAT.match(name))


def mesh_site(name: str) -> MeshSite:
    """The generated habitat `habitat<seed>` (`habitat` is habitat0) with its route (docs/mesh.md §4)."""
    m = HABITAT.match(name)
    if not m:
        raise InputError("world", name, "is no generated habitat (habitat, habitat0, habitat1, ...)")
    if len(m.group(1)) > 9:
        raise InputError("world", name, "must have a seed below 10**9 (habitat<seed>)")
    h = habitat(int(m.group(1) or 0))
    return site(h, mesh_world(h), h.route, h.arena, h.name)


def given_files(
    world: str | None, mesh: str | None, ant_route: str | None, route_name: str, world_field: str = "world"
) -> MeshSite | None:
    """The user's mesh world and route (the CLI's --mesh and --ant-route, which go together and replace the
    world named `world_field`) as a site, or None when neither is given."""
    if mesh is None and ant_route is None:
        return None
    if world is not None:
        raise InputError(world_field, world, "give a world or --mesh, not both")
    if mesh is None or ant_route is None:
        raise InputError("mesh" if mesh is None else "ant_route", None, "--mesh and --ant-route go together")
    return file_site(mesh, ant_route, route_name)


def file_site(
    mesh: str | Path, ant_route: str | Path, route_name: str = "Ant1_Route1", colours: str = "matlab"
) -> MeshSite:
    """The user's mesh world file (`read_mesh`) and recorded route (`read_route`); the arena: the mesh's extent
    seen from above, to whole cm."""
    f = read_mesh(mesh)
    xy = f.vertices[..., :2].reshape(-1, 2)
    arena = np.concatenate([np.floor(xy.min(0)), np.ceil(xy.max(0))])
    route = read_route(ant_route, route_name)
    stem = route_name if Path(ant_route).suffix.lower() == ".mat" else Path(ant_route).stem
    return site(f, mesh_world(f, colours), route, arena, f"{Path(f.source).stem}:{stem}")
