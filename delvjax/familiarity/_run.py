"""The route experiments of a familiarity model (docs/familiarity.md §3) in a colour or mesh world: train on
the route's images, then (a) the heading field on a grid, (b) route-following trials (Ardin et al.
2016), (c) catchment areas along the route (BoB's `calculate_ca`, `calculate_rca`). Every setting is
checked before any work."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import non_negative, positive, positive_int, seed_value
from ..core.errors import InputError
from ..core.familiarity.base import FamiliarityModel
from ..core.familiarity.catchment import route_catchments
from ..core.familiarity.fields import HeadingField, heading_field, stored_view_field
from ..core.familiarity.following import Following, StoredViews, Surroundings, Trials, ViewSource, follow_route
from ..core.familiarity.route import Route
from ..core.polyline import headings_along
from ..core.rollouts.rules import OUTCOMES, SUCCESS
from ..core.rollouts.success import wilson_pct
from ..images._render import world_grid
from ..images._worlds import ImageWorld
from ..mesh._site import MeshSite
from ._models import make_model, model_settings
from ._routes import RouteImages, route_from_database, view_source
from ._setup import any_world, following_setup

OFF_ROUTE = 20.0  # cm: "near the route" in the summary, the distance at which a trial counts an error


@dataclass
class FamiliarityResult:
    """What `familiarity` computed, with the settings it ran with."""

    world: str
    model: str
    settings: dict
    route: RouteImages
    points: np.ndarray
    field: HeadingField
    rules: Following | None
    trials: Trials | None
    catchments: dict = field(default_factory=dict)
    arena: np.ndarray = field(default_factory=lambda: np.zeros(4))
    obstacles: dict = field(default_factory=dict)
    on_database: bool = False  # the field's reference is the nearest route image's column-0 heading
    footprint: np.ndarray | None = None  # a mesh world's triangles seen from above (T, 3, 2) cm, for figures
    trained: FamiliarityModel | None = None  # the model trained on the route (more trials: `follow_route`)
    source: ViewSource | None = None  # the views the trials read

    def field_columns(self) -> dict:
        """The heading field, one row per grid point."""
        f = self.field
        return {
            "x_cm": self.points[:, 0],
            "y_cm": self.points[:, 1],
            "heading_deg": np.degrees(np.asarray(f.heading)),
            "unfamiliarity": np.asarray(f.value),
            "best_image": np.where(np.asarray(f.snapshot) >= 0, np.asarray(f.snapshot), np.nan),  # none kept: empty
            ("route_image_heading_deg" if self.on_database else "route_direction_deg"): np.degrees(
                np.asarray(f.route_direction)
            ),
            "distance_to_route_cm": np.asarray(f.distance),
            "error_deg": np.asarray(f.error_deg),
        }

    def ridf_columns(self) -> dict:
        """The RIDF at every field point, one row per point and turn (long form): the world heading of the view
        (deg, counter-clockwise from +x; on a database, column 0's) and its unfamiliarity."""
        f = self.field
        curve = np.asarray(f.curve, np.float64)  # (P, R)
        p, r = curve.shape
        heading = np.degrees(np.asarray(f.curve_start, np.float64))[:, None] + 360.0 * np.arange(r)[None] / r
        return {
            "point": np.repeat(np.arange(p), r),
            "x_cm": np.repeat(self.points[:, 0], r),
            "y_cm": np.repeat(self.points[:, 1], r),
            "heading_deg": np.mod(heading, 360.0).ravel(),
            "unfamiliarity": curve.ravel(),
        }

    def trial_columns(self) -> dict:
        """The route-following trials, one row each (none on an image database)."""
        t = self.trials
        if t is None:
            return {"trial": [], "outcome": [], "steps": [], "errors": []}
        return {
            "trial": np.arange(len(t.outcome)),
            "outcome": [OUTCOMES[int(c)] for c in np.asarray(t.outcome)],
            "steps": np.asarray(t.steps),
            "errors": np.asarray(t.errors),
        }

    def catchment_columns(self) -> dict:
        """Catchment areas along the route, one row per route image as the goal (sizes in images)."""
        p = np.asarray(self.route.route.positions)
        return {"image": np.arange(len(p)), "x_cm": p[:, 0], "y_cm": p[:, 1],
                **{k: np.asarray(v) for k, v in self.catchments.items()}}  # fmt: skip

    def summary(self) -> dict:
        """The headline numbers (and the settings) as JSON-ready values."""
        outcome = np.asarray([] if self.trials is None else self.trials.outcome)
        n, k = len(outcome), int(np.sum(outcome == SUCCESS))
        lo, hi = wilson_pct(k, n) if n else (math.nan, math.nan)
        near = np.asarray(self.field.distance) <= OFF_ROUTE
        err = np.asarray(self.field.error_deg)
        c = {k: np.asarray(v) for k, v in self.catchments.items()}
        spacing = float(self.settings["route_spacing"])
        return {
            "world": self.world,
            "model": self.model,
            "route_images": self.route.n_images,
            "route_length_cm": float(self.route.route.length()),
            "trials": n,
            "success_pct": 100.0 * k / n if n else None,
            "success_ci95_pct": [float(lo), float(hi)] if n else None,
            "mean_route_errors": float(np.mean(np.asarray(self.trials.errors))) if n else None,
            "field_points": int(len(err)),
            "median_error_deg_near_route": float(np.median(err[near])) if near.any() else None,
            "share_error_below_45_near_route": float(np.mean(err[near] < 45.0)) if near.any() else None,
            "median_error_deg_all": float(np.median(err)),
            "median_ca_on_route_cm": float(np.median(c["ca_size_on_route"]) * spacing),
            "median_rca_on_route_cm": float(np.median(c["rca_size_on_route"]) * spacing),
            "ca_reaching_a_route_end": int(np.sum(~np.isfinite(c["ca_size"]))),
            "rca_reaching_a_route_end": int(np.sum(~np.isfinite(c["rca_size"]))),
            "settings": self.settings,
        }


def route_experiments(
    world: str | ImageWorld | MeshSite = "robot",
    model: str = "perfect-memory",
    *,
    route=None,
    route_spacing: float = 4.0,
    view_rows: int | None = None,
    view_cols: int = 90,
    grid_spacing: float | None = None,
    trials: int = 20,
    heading_noise_deg: float = 10.0,
    step: float | None = None,
    max_steps: int | None = None,
    seed: int = 0,
    progress: Callable[[str], None] | None = None,
    **model_options,
) -> FamiliarityResult:
    """Train `model` on a route through `world` and run the three route experiments (module docstring).

    world: a colour world or environment by name, a generated habitat (`habitat<seed>`) or a `MeshSite`;
    route: waypoints [[x, y], ...] cm (default: `_routes.default_waypoints`, a mesh world's recorded route);
    route_spacing: cm between route images; view_rows x view_cols: the views (rendered at 4x in a colour world,
    2x in a mesh world, block-averaged; view_rows default 10, in a mesh world 19); grid_spacing: the heading
    field's grid (default: the world's spacing; in a mesh world within `band` cm of the route); trials,
    heading_noise_deg, step (default: the route spacing), max_steps (default: 2.1 route lengths): the
    route-following trials; seed: the trials' noise, InfoMax's weights and the mushroom body's wiring; model_options: the model's
    settings (`_models.SETTINGS`)."""
    say = progress or (lambda _: None)
    iw = any_world(world)
    spacing = positive(iw.spacing if grid_spacing is None else grid_spacing, "grid_spacing")
    points = iw.field_points(spacing) if isinstance(iw, MeshSite) else world_grid(iw, spacing)[0]
    if len(points) == 0:
        raise InputError("grid_spacing", spacing, f"leaves no grid point clear of the obstacles in {iw.name}")
    say(f"checking the settings and rendering the route in {iw.name} ...")
    setup = following_setup(iw, model, route=route, route_spacing=route_spacing, view_rows=view_rows,
                            view_cols=view_cols, trials=trials, heading_noise_deg=heading_noise_deg, step=step,
                            max_steps=max_steps, seed=seed, **model_options)  # fmt: skip
    ri, trained, rules, vc, s = setup.route, setup.trained, setup.rules, setup.camera, setup.settings
    say(f"{model}: heading field at {len(points)} points, {s['trials']} route-following trials, catchments ...")
    source = view_source(iw, vc)
    hf = heading_field(trained, source, ri.route, jnp.asarray(points, jnp.float32), n_turns=s["view_cols"])
    starts = jnp.repeat(ri.route.positions[:1], s["trials"], 0)
    heads = jnp.repeat(ri.route.headings[:1], s["trials"], 0)
    tr = follow_route(trained, source, ri.route, rules, starts, heads, jax.random.key(s["seed"]))
    ca = route_catchments(jnp.asarray(ri.views), s.get("kind", "abs"))
    mesh = isinstance(iw, MeshSite)
    run_settings = {**s, "grid_spacing": float(spacing), **({"eye_height_cm": iw.eye_height} if mesh else {})}
    arena = np.asarray(iw.arena if mesh else iw.world.arena)
    result = FamiliarityResult(iw.name, model, run_settings, ri, points, hf, rules, tr, ca, arena, iw.obstacles(),
                               footprint=iw.footprint if mesh else None, trained=trained, source=source)  # fmt: skip
    for name, a in (("field", hf.error_deg), ("unfamiliarity", hf.value), ("trials", tr.steps)):
        if not np.all(np.isfinite(np.asarray(a, np.float64))):
            raise InputError(model, name, "gave a non-finite number (a constant view or an empty mask)")
    return result


def database_experiments(
    route_db,
    model: str = "perfect-memory",
    *,
    test_db=None,
    view_rows: int = 10,
    view_cols: int = 90,
    trials: int = 20,
    heading_noise_deg: float = 10.0,
    seed: int = 0,
    progress: Callable[[str], None] | None = None,
    **model_options,
) -> FamiliarityResult:
    """The route experiments on image databases (docs/familiarity.md §3.4): `model` trained on a route
    database (`images.load_database(..., panoramas=True)`, a route); the heading at every image of
    `test_db` (a grid or route database of the same camera), or, without one, trained on the route's
    even images and tested on its odd ones; on a grid `test_db`, route-following `trials` on its stored
    views (the nearest image, rolled); catchment areas along the route."""
    say = progress or (lambda _: None)
    settings = model_settings(model, **model_options)
    seed = seed_value(seed)
    trials = positive_int(trials, "trials")
    noise = non_negative(heading_noise_deg, "heading_noise_deg")
    if route_db.kind != "route":
        raise InputError("images", route_db.name, f"must be a route database (its metadata says {route_db.kind})")
    shape = (positive_int(view_rows, "view_rows"), positive_int(view_cols, "view_cols"))
    ri = route_from_database(route_db, shape)
    if test_db is None:
        if ri.n_images < 4:
            raise InputError("images", route_db.name, "needs at least 4 images to train on half and test on the rest")
        train = ri.views[0::2]
        test = RouteImages(ri.name, Route(ri.route.positions[1::2], ri.route.headings[1::2]), ri.views[1::2], None)
    else:
        pano = test_db.rings.snapshots.panorama
        if pano is None or pano.shape[-2:] != route_db.rings.snapshots.panorama.shape[-2:]:
            raise InputError("test_images", test_db.name, "must hold panoramas of the route's size")
        test = route_from_database(test_db, shape)  # a grid's images in the same form
        train = ri.views
    say(f"{model}: trained on {len(train)} route images, headings at {test.n_images} images, catchments ...")
    trained = make_model(model, shape, seed, **settings).train(jnp.asarray(train))
    r = test.route
    hf = stored_view_field(trained, jnp.asarray(test.views), r.headings, r.positions, ri.route)
    ca = route_catchments(jnp.asarray(ri.views), settings.get("kind", "abs"))
    points = np.asarray(ri.route.positions, np.float64)
    spacing = float(np.median(np.hypot(*np.diff(points, axis=0).T)))
    rules = tr = None
    if test_db is not None and test_db.kind == "grid":
        rules, tr = stored_trials(trained, test, ri.route, route_db, trials, noise, spacing, seed)
    run_settings = {"route_spacing": spacing, "view_rows": shape[0], "view_cols": shape[1], "seed": seed,
                    "trials": trials if tr is not None else 0, "heading_noise_deg": float(noise),
                    "tested_on": "odd route images" if test_db is None else test_db.name, **settings}  # fmt: skip
    return FamiliarityResult(
        route_db.name, model, run_settings, ri, np.asarray(r.positions), hf, rules, tr, ca,
        np.asarray(route_db.arena), route_db.obstacles, on_database=True,
    )  # fmt: skip


def stored_trials(
    model, test: RouteImages, route: Route, route_db, trials: int, noise: float, spacing: float, seed: int
):
    """Route-following trials on a grid database's stored views (`following.StoredViews`) from the route's
    start, a route spacing a move, 2.1 route lengths of moves; column 0 of the route's images looks
    `camera_offset` left of the direction of travel (their circular mean)."""
    p = np.asarray(route.positions, np.float64)
    travel = headings_along(p)
    offset = float(np.angle(np.mean(np.exp(1j * (np.asarray(route.headings, np.float64) - travel)))))
    length = float(np.sum(np.hypot(*np.diff(p, axis=0).T)))
    rules = Following(
        step=spacing, heading_noise_deg=noise, camera_offset=offset, max_steps=math.ceil(2.1 * length / spacing)
    )
    obs = route_db.obstacles
    area = Surroundings(
        jnp.asarray(route_db.arena, jnp.float32),
        jnp.asarray(np.asarray(obs.get("cylinders") or [[0.0, 0.0, -1.0]], np.float32).reshape(-1, 3)),
        jnp.asarray(np.asarray(obs.get("boxes") or [[0.0, 0.0, -1.0, -1.0]], np.float32).reshape(-1, 4)),
    )
    source = StoredViews(jnp.asarray(test.views), test.route.positions, test.route.headings, area)
    starts = jnp.repeat(route.positions[:1], trials, 0)
    heads = jnp.full((trials,), travel[0] + offset, jnp.float32)
    return rules, follow_route(model, source, route, rules, starts, heads, jax.random.key(seed))
