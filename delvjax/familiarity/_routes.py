"""Routes for the familiarity experiments (docs/familiarity.md §3): a polyline through waypoints in a
colour world, resampled every `spacing` cm, its images rendered facing along it; or the images of a
route database. Checked before any work (`InputError` naming the field and the value)."""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import finite, positive, positive_int
from ..core.errors import InputError
from ..core.familiarity.route import Route
from ..core.familiarity.views import ViewCamera, downsample, view_camera, views_at
from ..images._worlds import ImageWorld

MAX_IMAGES = 20000  # a route longer than this many images is refused (memory of the perfect memory)


@dataclass
class RouteImages:
    """A route and the (N, H, W) 8-bit gray views along it (float), each facing along the route."""

    name: str
    route: Route
    views: np.ndarray
    camera: ViewCamera | None

    @property
    def n_images(self) -> int:
        return int(self.views.shape[0])


BENDS = (0.2, -0.2, 0.35, -0.35, 0.0)  # the default route's bend, the first that is clear of every obstacle


def default_waypoints(iw: ImageWorld, spacing: float = 4.0) -> np.ndarray:
    """(3, 2) cm: from 15 % into the arena's south-west corner to the world's home, bent sideways by the
    first of BENDS (a share of its length, to the left) that keeps the route clear of every obstacle."""
    a = np.asarray(iw.world.arena, np.float64)
    start = a[:2] + 0.15 * (a[2:] - a[:2])
    goal = np.asarray(iw.home, np.float64)
    v = goal - start
    tries = [np.stack([start, (start + goal) / 2 + b * np.array([-v[1], v[0]]), goal]) for b in BENDS]
    return next((w for w in tries if iw.clear(resample(w, spacing)).all()), tries[0])


def resample(waypoints: np.ndarray, spacing: float) -> np.ndarray:
    """(N, 2): points every `spacing` cm along the polyline (the last waypoint included)."""
    seg = np.diff(waypoints, axis=0)
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*seg.T))])
    s = np.append(np.arange(0.0, cum[-1], spacing), cum[-1])
    s = s[np.append(np.diff(s) > 1e-6 * spacing, True)]
    return np.stack([np.interp(s, cum, waypoints[:, k]) for k in range(2)], -1)


def headings_along(points: np.ndarray) -> np.ndarray:
    """(N,) rad: the direction to the next point (the last repeats the one before)."""
    d = np.diff(points, axis=0)
    h = np.arctan2(d[:, 1], d[:, 0])
    return np.append(h, h[-1])


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


def plan_route(iw: ImageWorld, waypoints=None, spacing: float = 4.0) -> np.ndarray:
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


def route_in_world(iw: ImageWorld, points: np.ndarray, vc: ViewCamera | None = None) -> RouteImages:
    """The route through `points` (N, 2) (`plan_route`) and its views, each facing along the route."""
    vc = view_camera() if vc is None else vc
    route = Route(jnp.asarray(points, jnp.float32), jnp.asarray(headings_along(points), jnp.float32))
    render = jax.jit(jax.vmap(lambda p, h: views_at(iw.world, vc, p, h, jnp.zeros(1))[0]))
    return RouteImages(iw.name, route, np.asarray(render(route.positions, route.headings)), vc)


def route_from_database(db, view_shape: tuple[int, int] = (10, 90)) -> RouteImages:
    """The images of a loaded database (`images.load_database(..., panoramas=True)`; a route, or a grid to test on), block-averaged
    to `view_shape` (rows, cols must divide the panorama's), in the order they were recorded."""
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
