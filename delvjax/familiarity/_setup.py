"""The validated setup of route following in a colour or mesh world (docs/familiarity.md §3, docs/mesh.md §6):
the model's settings, the views' camera, the route and its rendered images, the trained model and the rules of
a trial. Shared by `route_experiments` and the route-following sweep kind (docs/sweeps.md "Route-following
sweeps"), so that both check every setting the same way before any work and a sweep cell runs the trials
`route_experiments` runs with the same settings, number for number."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import non_negative, positive, positive_int, seed_value
from ..core.errors import InputError
from ..core.familiarity.base import FamiliarityModel
from ..core.familiarity.following import Following
from ..core.familiarity.mesh_views import MeshCamera, mesh_camera
from ..core.familiarity.views import ViewCamera, view_camera
from ..images._worlds import ImageWorld, image_world
from ..mesh._site import MeshSite, is_mesh_name, mesh_site
from ._models import make_model, model_settings
from ._routes import RouteImages, default_waypoints, plan_route, route_in_world

MAX_TRIALS = 10000
RENDERED = 8  # routes whose images are kept for the next setup (a sweep's cells share a few routes)
_rendered: dict[str, RouteImages] = {}


@dataclass
class FollowingSetup:
    """What a run of route following needs, checked: `settings` holds every setting it ran with."""

    world: ImageWorld | MeshSite
    model: str
    camera: ViewCamera | MeshCamera
    route: RouteImages
    trained: FamiliarityModel
    rules: Following
    settings: dict


def render_factor(cols: int, least: int = 4) -> int:
    """Rendered pixels per view pixel: at least `least` (4 in a colour world; 2 in a mesh world, whose views are
    dearer), and a multiple of what makes the 2 deg scan step whole rendered columns (90 columns: 4 or 2; 36: 5)."""
    unit = 180 // math.gcd(cols, 180)
    return unit * math.ceil(least / unit)


def any_world(world: str | ImageWorld | MeshSite) -> ImageWorld | MeshSite:
    """A world by name (a generated habitat, a colour world or an environment) or as given."""
    if not isinstance(world, str):
        return world
    if is_mesh_name(world):
        return mesh_site(world)
    try:
        return image_world(world)
    except InputError as e:
        raise InputError(e.field, e.value, e.expected + "; nor a generated mesh habitat (habitat<seed>)") from None


def camera_of(iw: ImageWorld | MeshSite, rows: int, cols: int) -> ViewCamera | MeshCamera:
    """The views' camera: a colour world's (`view_camera`) or a mesh world's (`mesh_camera`, its eye height)."""
    if isinstance(iw, MeshSite):
        return mesh_camera(rows, cols, render_factor(cols, 2), iw.eye_height)
    return view_camera(rows, cols, render_factor(cols))


def rendered_route(iw: ImageWorld | MeshSite, points: np.ndarray, vc: ViewCamera | MeshCamera) -> RouteImages:
    """`route_in_world`, its images kept for the RENDERED routes last asked for (by the world's arrays, the
    points and the camera: a sweep renders each route once, not once a cell)."""
    h = hashlib.sha256(np.asarray(points, np.float64).tobytes())
    for leaf in jax.tree.leaves((iw.world, vc)):
        h.update(np.asarray(leaf).tobytes())
    h.update(repr((iw.name, vc)).encode())  # the camera's static fields (its arrays are hashed above)
    key = h.hexdigest()
    if key not in _rendered:
        while len(_rendered) >= RENDERED:
            _rendered.pop(next(iter(_rendered)))
        _rendered[key] = route_in_world(iw, points, vc)
    return _rendered[key]


def following_setup(
    world: str | ImageWorld | MeshSite = "robot",
    model: str = "perfect-memory",
    *,
    route=None,
    route_spacing: float = 4.0,
    view_rows: int | None = None,
    view_cols: int = 90,
    trials: int = 20,
    heading_noise_deg: float = 10.0,
    step: float | None = None,
    max_steps: int | None = None,
    seed: int = 0,
    **model_options,
) -> FollowingSetup:
    """Every setting checked (`InputError` naming the field), then the route rendered and the model trained
    (`route_experiments` documents the settings)."""
    iw = any_world(world)
    settings = model_settings(model, **model_options)
    if view_rows is None:
        view_rows = 19 if isinstance(iw, MeshSite) else 10  # a mesh world: the ant eye's 4 deg rows
    rows, cols = positive_int(view_rows, "view_rows"), positive_int(view_cols, "view_cols")
    if 360 % cols:
        raise InputError("view_cols", cols, "must divide 360 (a turn of the heading field is one view column)")
    trials = positive_int(trials, "trials")
    if trials > MAX_TRIALS:
        raise InputError("trials", trials, f"must be at most {MAX_TRIALS}")
    noise = non_negative(heading_noise_deg, "heading_noise_deg")
    seed = seed_value(seed)
    vc = camera_of(iw, rows, cols)
    points = plan_route(iw, route, route_spacing)
    length = float(np.sum(np.hypot(*np.diff(points, axis=0).T)))
    step = positive(route_spacing if step is None else step, "step")
    n_steps = math.ceil(2.1 * length / step) if max_steps is None else positive_int(max_steps, "max_steps")
    rules = Following(step=step, heading_noise_deg=noise, max_steps=n_steps)
    ri = rendered_route(iw, points, vc)
    trained = make_model(model, (rows, cols), seed, **settings).train(jnp.asarray(ri.views))
    if route is not None:
        used = np.asarray(route, float).reshape(-1, 2).round(2).tolist()
    elif isinstance(iw, MeshSite):
        used = f"the recorded route of {iw.name}"
    else:
        used = default_waypoints(iw, route_spacing).round(2).tolist()
    run = {"route_spacing": float(route_spacing), "view_rows": rows, "view_cols": cols, "trials": trials,
           "heading_noise_deg": float(noise), "step": float(step), "max_steps": n_steps, "seed": seed,
           "route": used, **settings}  # fmt: skip
    return FollowingSetup(iw, model, vc, ri, trained, rules, run)
