"""Routes for the familiarity experiments (docs/familiarity.md §3): a polyline through waypoints in a
colour world or a mesh world (docs/mesh.md §6), resampled every `spacing` cm, its images rendered facing along
it; or the images of a route database. Checked before any work (`InputError` naming the field and the value)."""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import finite, positive, positive_int
from ..core.errors import InputError
from ..core.familiarity.following import MeshViews, WorldViews
from ..core.familiarity.mesh_views import MeshCamera, mesh_camera
from ..core.familiarity.route import Route
from ..core.familiarity.views import ViewCamera, downsample, view_camera
from ..core.polyline import headings_along, resample
from ..images._worlds import ImageWorld
from ..mesh._site import MeshSite

MESH_BATCH = 16  # mesh views rendered side by side
MAX_IMAGES = 20000  # a route longer than this many images is refused (memory of the perfect memory)


@dataclass
class RouteImages:
    """A route and the (N, H, W) 8-bit gray views along it (float), each facing along the route."""

    name: str
    route: Route
    views: np.ndarray
    camera: ViewCamera | MeshCamera | None

    @property
    def n_images(self) -> int:
        return int(self.views.shape[0])


BENDS = (0.2, -0.2, 0.35, -0.35, 0.0)  # the default route's bend, the first that is clear of every obstacle


def default_waypoints(iw: ImageWorld | MeshSite, spacing: float = 4.0) -> np.ndarray:
    """(3, 2) cm: from 15 % into the arena's south-west corner to the world's home, bent sideways by the
    first of BENDS (a share of its length, to the left) that keeps the route clear of every obstacle. A mesh
    world's: its recorded route."""
    if isinstance(iw, MeshSite):
        return iw.waypoints()
    a = np.asarray(iw.world.arena, np.float64)
    start = a[:2] + 0.15 * (a[2:] - a[:2])
    goal = np.asarray(iw.home, np.float64)
    v = goal - start
    tries = [np.stack([start, (start + goal) / 2 + b * np.array([-v[1], v[0]]), goal]) for b in BENDS]
    return next((w for w in tries if iw.clear(resample(w, spacing)).all()), tries[0])


def check_waypoints(waypoints) -> np.ndarray:
    """(K, 2) finite waypoints, K >= 2, each pair of neighbours apart."""
    try:
        w = np.asarray(waypoints, np.float64).reshape(-1, 2)
    except (TypeError, ValueError):
        raise InputError("route", waypoints, "must be pairs x, y (cm)") from None
    if w.shape[0] < 2:
        raise InputError("route", waypoints, "needs at least two waypoints (a route of fewer than two images)")
    for k, v in enumerate(w.ravel()):
        finite(float(v), f"route[{k // 2}]")
    if np.any(np.hypot(*np.diff(w, axis=0).T) <= 0):
        raise InputError("route", waypoints, "has two equal neighbouring waypoints")
    return w


def plan_route(iw: ImageWorld | MeshSite, waypoints=None, spacing: float = 4.0) -> np.ndarray:
    """(N, 2) cm: the route through `waypoints` (default `default_waypoints`) every `spacing` cm, checked:
    at least two images, at most MAX_IMAGES, none in an obstacle (+ the world's clearance) or outside.
    """
    spacing = positive(spacing, "route_spacing")
    w = default_waypoints(iw, spacing) if waypoints is None else check_waypoints(waypoints)
    points = resample(w, spacing)
    if points.shape[0] < 2:
        raise InputError("route_spacing", spacing, f"leaves fewer than two images on a route {w.tolist()} long")
    if points.shape[0] > MAX_IMAGES:
        raise InputError("route_spacing", spacing, f"makes {points.shape[0]} images (at most {MAX_IMAGES})")
    bad = ~iw.clear(points)
    if bad.any():
        at = points[int(np.argmax(bad))].round(1).tolist()
        raise InputError("route", w.round(1).tolist(), f"passes through an obstacle or leaves the arena at {at}")
    return points


def view_source(iw: ImageWorld | MeshSite, vc: ViewCamera | MeshCamera) -> WorldViews | MeshViews:
    """The views of a world at any pose (`following.WorldViews` or `following.MeshViews`)."""
    if isinstance(iw, MeshSite):
        return MeshViews(iw.mesh, vc, jnp.asarray(iw.arena, jnp.float32))
    return WorldViews(iw.world, vc)


def route_in_world(
    iw: ImageWorld | MeshSite, points: np.ndarray, vc: ViewCamera | MeshCamera | None = None
) -> RouteImages:
    """The route through `points` (N, 2) (`plan_route`) and its views, each facing along the route."""
    vc = (mesh_camera(height=iw.eye_height) if isinstance(iw, MeshSite) else view_camera()) if vc is None else vc
    route = Route(jnp.asarray(points, jnp.float32), jnp.asarray(headings_along(points), jnp.float32))
    source = view_source(iw, vc)
    one = lambda p, h: source(p, h, jnp.zeros(1))[0]  # noqa: E731
    if isinstance(iw, MeshSite):  # MESH_BATCH poses side by side: a mesh view's work grows with its triangles
        render = jax.jit(lambda p, h: jax.lax.map(lambda a: one(*a), (p, h), batch_size=MESH_BATCH))
    else:
        render = jax.jit(jax.vmap(one))
    return RouteImages(iw.name, route, np.asarray(render(route.positions, route.headings)), vc)


def route_from_database(db, view_shape: tuple[int, int] = (10, 90)) -> RouteImages:
    """The images of a loaded database (`images.load_database(..., panoramas=True)`; a route, or a grid to test
    on), block-averaged to `view_shape` (rows, cols must divide the panorama's), in the order they were recorded."""
    pano = db.rings.snapshots.panorama
    if pano is None:
        raise InputError("images", db.name, "holds no panoramas: load it with panoramas=True")
    rows, cols = (positive_int(v, n) for v, n in zip(view_shape, ("view_rows", "view_cols")))
    h, w = pano.shape[-2:]
    if h % rows or w % cols or h // rows != w // cols:
        raise InputError(
            "view_rows and view_cols", [rows, cols], f"must divide the panoramas ({h} x {w}) by one factor"
        )
    views = np.asarray(downsample(jnp.asarray(pano, jnp.float32), h // rows))
    pos = np.asarray(db.rings.positions, np.float64)
    if pos.shape[0] < 2:
        raise InputError("images", db.name, "a route needs at least two images")
    route = Route(jnp.asarray(pos, jnp.float32), jnp.asarray(db.rings.headings, jnp.float32))
    return RouteImages(db.name, route, views, None)
