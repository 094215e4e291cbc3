"""The validated setup of route following in a colour world (docs/familiarity.md §3): the model's settings,
the views' camera, the route and its rendered images, the trained model and the rules of a trial. Shared
by `route_experiments` and the route-following sweep kind (docs/sweeps.md "Route-following sweeps"), so
that both check every setting the same way before any work and a sweep cell runs the trials
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
from ..core.familiarity.views import ViewCamera, view_camera
from ..images._worlds import ImageWorld, image_world
from ._models import make_model, model_settings
from ._routes import RouteImages, default_waypoints, plan_route, route_in_world

MAX_TRIALS = 10000
RENDERED = 8  # routes whose images are kept for the next setup (a sweep's cells share a few routes)
_rendered: dict[str, RouteImages] = {}


@dataclass
class FollowingSetup:
    """What a run of route following needs, checked: `settings` holds every setting it ran with."""

    world: ImageWorld
    model: str
    camera: ViewCamera
    route: RouteImages
    trained: FamiliarityModel
    rules: Following
    settings: dict


def render_factor(cols: int) -> int:
    """Rendered pixels per view pixel: at least 4, and a multiple of what makes the 2 deg scan step whole
    rendered columns (90 columns: 4, 1 deg a rendered column; 36: 5; 72: 5)."""
    unit = 180 // math.gcd(cols, 180)
    return unit * math.ceil(4 / unit)


def rendered_route(iw: ImageWorld, points: np.ndarray, vc: ViewCamera) -> RouteImages:
    """`route_in_world`, its images kept for the RENDERED routes last asked for (by the world's arrays, the
    points and the camera: a sweep renders each route once, not once a cell)."""
    h = hashlib.sha256(np.asarray(points, np.float64).tobytes())
    for leaf in jax.tree.leaves((iw.world, vc)):
        h.update(np.asarray(leaf).tobytes())
    h.update(repr((iw.name, vc.factor, vc.camera.rows, vc.camera.cols)).encode())
    key = h.hexdigest()
    if key not in _rendered:
        while len(_rendered) >= RENDERED:
            _rendered.pop(next(iter(_rendered)))
        _rendered[key] = route_in_world(iw, points, vc)
    return _rendered[key]


def following_setup(
    world: str | ImageWorld = "robot",
    model: str = "perfect-memory",
    *,
    route=None,
    route_spacing: float = 4.0,
    view_rows: int = 10,
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
    iw = image_world(world) if isinstance(world, str) else world
    settings = model_settings(model, **model_options)
    rows, cols = positive_int(view_rows, "view_rows"), positive_int(view_cols, "view_cols")
    if 360 % cols:
        raise InputError("view_cols", cols, "must divide 360 (a turn of the heading field is one view column)")
    trials = positive_int(trials, "trials")
    if trials > MAX_TRIALS:
        raise InputError("trials", trials, f"must be at most {MAX_TRIALS}")
    noise = non_negative(heading_noise_deg, "heading_noise_deg")
    seed = seed_value(seed)
    vc = view_camera(rows, cols, render_factor(cols))
    points = plan_route(iw, route, route_spacing)
    length = float(np.sum(np.hypot(*np.diff(points, axis=0).T)))
    step = positive(route_spacing if step is None else step, "step")
    n_steps = math.ceil(2.1 * length / step) if max_steps is None else positive_int(max_steps, "max_steps")
    rules = Following(step=step, heading_noise_deg=noise, max_steps=n_steps)
    ri = rendered_route(iw, points, vc)
    trained = make_model(model, (rows, cols), seed, **settings).train(jnp.asarray(ri.views))
    used = default_waypoints(iw, route_spacing) if route is None else np.asarray(route, float).reshape(-1, 2)
    run = {"route_spacing": float(route_spacing), "view_rows": rows, "view_cols": cols, "trials": trials,
           "heading_noise_deg": float(noise), "step": float(step), "max_steps": n_steps, "seed": seed,
           "route": used.round(2).tolist(), **settings}  # fmt: skip
    return FollowingSetup(iw, model, vc, ri, trained, rules, run)
