"""Route following in the ant's world: familiarity models and MinWarping on triangle-mesh habitats (beyond the
thesis; docs/mesh.md §6-8).

Each generated habitat (`habitat<seed>`, docs/mesh.md §4: grass tussocks and a few trees, a meandering 8 m route
from the Seville routes' start to their nest) and, when DELVJAX_ANTWORLD names a folder holding the Seville world
(world5000_gray.mat or .bin) and AntRoutes.mat, the real world and Ant1_Route1, is rendered inside the program
with the ant eye's band of elevation (-15 to 60 deg, 4 deg pixels over the full circle, green channel, 1 cm above
the ground). Perfect memory, InfoMax and the mushroom body learn the route's views every 4 cm and follow it as
Ardin et al. (2016) run them (scan +-60 deg in 2 deg steps, 30 deg of heading noise a move, back onto the route
beyond 20 cm, success within 20 cm of the nest), starting 50, 100, 200 and 400 cm before the nest along the route
and at its start. MinWarping homes to one snapshot at the nest from the same starts, on a grid database of the world
(every 20 cm within 150 cm of the route, the green channel as the models see it; nearest-snapshot rollouts with the same step, noise, goal radius and
move budget; a trial that leaves the mapped band fails). The tasks differ (a route against one snapshot), and
the table says what each method is given. DELV is not run: the ant world has no landmarks its extractor can
segment (every triangle is grass green).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from delvjax.core.familiarity.following import follow_route
from delvjax.core.polyline import distance_to
from delvjax.core.rollouts.rules import SUCCESS
from delvjax.core.rollouts.success import wilson_pct
from delvjax.familiarity import route_experiments
from delvjax.images import database_rollouts, database_vector_map, load_database
from delvjax.mesh import MeshSite, file_site, mesh_site, render_mesh_database
from delvjax.plots import subplots

from ._images_common import MINWARPING, preview
from .familiarity import success_errorbar

TITLE = "Route following in the ant's world: familiarity and MinWarping on mesh habitats (beyond the thesis)"
COST = 1300  # rough seconds of a full run on 2 CPU cores (three habitats: 1290 s alone; the Seville world adds 650)
STEPS = 4  # three habitats (one in a preview) and the table; the Seville world adds one
NOISE = 30.0  # deg of heading noise a move
GOAL_CM = 20.0  # success radius and the off-route distance (Ardin et al. 2016)
MAPPED_BAND = 150.0  # cm about the route: MinWarping's grid database
SEVILLE = "DELVJAX_ANTWORLD"  # a folder with the Seville world and AntRoutes.mat (not shipped: docs/mesh.md §3)


def worlds(quick: bool) -> list[MeshSite | str]:
    """The generated habitats, and the Seville world when SEVILLE names a folder that holds it."""
    sites: list[MeshSite | str] = ["habitat0"] if quick else ["habitat0", "habitat1", "habitat2"]
    folder = os.environ.get(SEVILLE)
    if folder:
        mesh = next((Path(folder) / f for f in ("world5000_gray.mat", "world5000_gray.bin")
                     if (Path(folder) / f).is_file()), None)  # fmt: skip
        if mesh is not None and (Path(folder) / "AntRoutes.mat").is_file():
            sites.append(file_site(mesh, Path(folder) / "AntRoutes.mat", "Ant1_Route1"))
    return sites


def starts_before_nest(points: np.ndarray, distances) -> tuple[np.ndarray, np.ndarray]:
    """(D, 2) the route's points `distances` cm before its end along it (the route's start where it is shorter,
    and for an infinite distance), and (D,) the route's direction there, rad."""
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    at = np.clip(arc[-1] - np.asarray(distances, np.float64), 0.0, arc[-1])
    i = np.minimum(np.searchsorted(arc, at, side="right") - 1, len(points) - 2)
    d = points[i + 1] - points[i]
    return points[i] + ((at - arc[i]) / np.maximum(arc[i + 1] - arc[i], 1e-9))[:, None] * d, np.arctan2(
        d[:, 1], d[:, 0]
    )


def row(world: str, method: str, given: str, start: str, outcome: np.ndarray, returns, error, **extra) -> dict:
    """One row of the table: success with its Wilson interval."""
    k, n = int(np.sum(outcome == SUCCESS)), len(outcome)
    lo, hi = wilson_pct(k, n)
    return {"world": world, "method": method, "given": given, "start": start, "trials": n, "successes": k,
            "success %": 100.0 * k / n, "95 % interval": f"{lo:.1f}-{hi:.1f}", "returns to route": returns,
            "median error near route °": error, **extra}  # fmt: skip


def familiarity_rows(site, model: str, distances, trials: int, seed: int, grid: float) -> tuple[list[dict], object]:
    """`model` trained on the route; trials from every start; its heading field and catchments."""
    r = route_experiments(site, model, trials=trials, heading_noise_deg=NOISE, seed=seed, grid_spacing=grid)
    s = r.summary()
    p = np.asarray(r.route.route.positions, np.float64)
    xy, heads = starts_before_nest(p, distances)
    starts, headings = np.repeat(xy, trials, 0), np.repeat(heads, trials)
    t = follow_route(r.trained, r.source, r.route.route, r.rules, jnp.asarray(starts, jnp.float32),
                     jnp.asarray(headings, jnp.float32), jax.random.key(seed + 1))  # fmt: skip
    given = f"{s['route_images']} route images"
    extra = {"median CA cm": s["median_ca_on_route_cm"], "median RCA cm": s["median_rca_on_route_cm"]}
    rows = []
    for k, d in enumerate(distances):
        sl = slice(k * trials, (k + 1) * trials)
        rows.append(row(s["world"], model, given, label(d), np.asarray(t.outcome)[sl],
                        float(np.mean(np.asarray(t.errors)[sl])), s["median_error_deg_near_route"], **extra))  # fmt: skip
    rows.append(row(s["world"], model, given, "route start", np.asarray(r.trials.outcome), s["mean_route_errors"],
                    s["median_error_deg_near_route"], **extra))  # fmt: skip
    return rows, r


def label(d: float) -> str:
    return f"{d:g} cm before the nest"


def minwarping_rows(site: MeshSite, route_points: np.ndarray, distances, trials: int, seed: int, spacing: float):
    """MinWarping homing to the nest's snapshot from every start, on a grid database of the band (its home: the
    grid image nearest the nest, at most spacing / sqrt(2) from it; a coarser grid than the goal radius would
    leave an agent in the home image's cell without a direction)."""
    with tempfile.TemporaryDirectory() as tmp:
        render_mesh_database(site, Path(tmp) / "db", spacing=spacing, band=MAPPED_BAND)
        db = load_database(
            Path(tmp) / "db", panoramas=True, home=site.home, warn=lambda _: None
        )  # home: the nearest image
    vm = database_vector_map(db, "minwarping", **MINWARPING)
    pos = np.asarray(db.rings.positions, np.float64)
    near = (distance_to(pos, site.route) <= GOAL_CM) & np.asarray(vm.valid) & np.asarray(vm.included)
    rows = []
    xy, _ = starts_before_nest(route_points, distances)
    step = float(np.hypot(*(route_points[1] - route_points[0])))
    for d, start in zip(distances, xy):
        length = min(d, float(np.sum(np.hypot(*np.diff(route_points, axis=0).T))))
        paths = database_rollouts(db, vm, np.repeat(start[None], trials, 0), step=step, home_radius=GOAL_CM,
                                  max_steps=math.ceil(2.1 * length / step), motion_heading_noise_deg=NOISE, seed=seed)  # fmt: skip
        outcome = np.asarray(paths.outcome)
        path = np.asarray(paths.path, np.float64)
        left = distance_to(path.reshape(-1, 2), site.route).reshape(path.shape[:2]).max(1) > MAPPED_BAND
        outcome = np.where(left, -1, outcome)  # leaving the mapped band: failed
        close = near & (np.linalg.norm(pos - np.asarray(site.home), axis=-1) <= length)
        err = float(np.median(np.asarray(vm.error_deg)[close])) if close.any() else float("nan")
        rows.append(row(site.name, "MinWarping", "1 snapshot (the nest)", label(d) if np.isfinite(d) else "route start",
                        outcome, "", err, **{"left the band": int(left.sum())}))  # fmt: skip
    return rows


def figure(rows: list[dict], names: list[str]):
    """Success against the start's distance before the nest, one panel a world, one line a method."""
    fig, axes = subplots(1, len(names), figsize=(5.0 * len(names), 4.0), squeeze=False)
    for ax, world in zip(axes[0], names):
        mine = [r for r in rows if r["world"] == world]
        starts = list(dict.fromkeys(r["start"] for r in mine))
        for method in dict.fromkeys(r["method"] for r in mine):
            sel = [next(r for r in mine if r["method"] == method and r["start"] == s) for s in starts]
            success_errorbar(ax, sel, range(len(starts)), method)
        ax.set_xticks(range(len(starts)), [s.replace(" before the nest", "") for s in starts], fontsize=8)
        ax.set(xlabel="start (along the route, before the nest)", ylabel="success (%)", ylim=(-5, 105), title=world)
        ax.legend(fontsize=8)
    fig.set_layout_engine("tight")
    return fig


def run(ctx) -> None:
    seed = ctx.config.seed
    quick = preview(ctx)
    models = ("perfect-memory",) if quick else ("perfect-memory", "infomax", "mushroom-body")
    distances = (100.0,) if quick else (50.0, 100.0, 200.0, 400.0)
    trials = 2 if quick else 10
    rows, names = [], []
    for world in worlds(quick):
        site = mesh_site(world) if isinstance(world, str) else world
        mine = []
        for model in models:
            got, r = familiarity_rows(site, model, distances, trials, seed, 60.0 if quick else 20.0)
            mine += got
        route_points = np.asarray(r.route.route.positions, np.float64)
        mine += minwarping_rows(site, route_points, (*distances, np.inf), trials, seed, 20.0)
        for x in mine:
            ctx.number(f"ant_world:{x['world']}:{x['method']}:{x['start']}:success_pct", x["success %"])
        rows += mine
        names.append(site.name)
        ctx.step(site.name)
    ctx.figure(
        "ant_world_success.png",
        figure(rows, names),
        f"Success from starts along the route ({NOISE:g} deg of heading noise a move; 95 % Wilson intervals): "
        "familiarity models trained on the route, MinWarping homing to a snapshot at the nest.",
    )
    ctx.table(
        "ant_world",
        "Familiarity models and MinWarping in mesh habitats (generated; the Seville world when given)",
        rows,
        source="beyond the thesis (Ardin et al. 2016; Baddeley et al. 2012; Risse et al.'s Seville world)",
        note=f"Views: 19 x 90 (4 deg pixels, -15 to 60 deg, green channel, 1 cm above the ground). Familiarity models: "
        f"the route's images every 4 cm; scan +-60 deg in 2 deg steps; a return to the route beyond {GOAL_CM:g} cm "
        "counts. MinWarping: a grid database every 20 cm within 150 cm of the route, homing to the image nearest the "
        "nest; a trial that leaves that band fails. Errors: medians over the field points within 20 cm of the route, "
        "against the route's direction (familiarity) or home (MinWarping, points no further from the nest than the "
        "start). CA, RCA: BoB's catchment areas along the route (docs/familiarity.md §3.3).",
    )
    ctx.step("table")
