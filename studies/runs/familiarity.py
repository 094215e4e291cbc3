"""Route following by familiarity beside DELV and MinWarping (beyond the thesis; docs/familiarity.md).

On the rendered robot and natural worlds, a route from the arena's corner to home (the default route of
`delvjax familiarity`) is learnt by perfect memory, InfoMax and (full run, robot world) the mushroom body, which then
follow it from its start (Ardin et al. 2016: scan +-60 deg in 2 deg steps, back onto the route beyond
20 cm, success within 20 cm of its end). DELV and MinWarping home to a snapshot at the route's end from
the same start, on the world's rendered grid database (nearest-snapshot rollouts, docs/images.md §7),
with the same heading noise, step, goal radius and move budget. Each family is also scored on its own
task near the route: the familiarity models' heading against the route's direction, the homing
methods' direction against the direction home. The two tasks differ (a route against one goal), and
so does what each method is given (every route image against one snapshot): the table says which.

A second table repeats route following over seeds (each seed new trial noise, InfoMax weights and mushroom-body
wiring) and up to 90 deg of noise, as one route-following sweep (docs/sweeps.md): the spread over seeds, and
that success can fall far below 100 %.
"""

from __future__ import annotations

import math

import numpy as np

from delvjax.core.images.rollouts import OUTCOMES
from delvjax.core.rollouts.rules import OUTCOMES as RULE_OUTCOMES
from delvjax.core.rollouts.rules import SUCCESS
from delvjax.core.rollouts.success import wilson_pct
from delvjax.familiarity import route_experiments
from delvjax.images import database_rollouts, database_vector_map
from delvjax.plots import subplots
from delvjax.sweeps import parse_sweep, run_sweep

from ._images_common import database, preview
from .hybrid import LABEL, options

TITLE = "Route following by familiarity beside DELV and MinWarping (beyond the thesis)"
COST = 600  # rough seconds of a full run (2 CPU cores, two studies side by side; 950 s with 40 trials and the
# mushroom body in both worlds, beside a test suite)
STEPS = 4  # the robot world, the natural world, the table, the seeds
NEAR_CM = 20.0  # "near the route": within a trial's off-route distance
FAMILIARITY = ("perfect-memory", "infomax", "mushroom-body")
HOMING = ("delv", "minwarping")


def familiarity_rows(world: str, model: str, noises, trials: int, seed: int, grid: float | None) -> list[dict]:
    """Route following of `model` at every heading noise, and its heading field near the route."""
    rows = []
    for noise in noises:
        r = route_experiments(world, model, trials=trials, heading_noise_deg=noise, seed=seed, grid_spacing=grid)
        s = r.summary()
        rows.append({"world": world, "method": model, "given": f"{s['route_images']} route images",
                     "noise °": noise, "trials": s["trials"], "successes": round(s["success_pct"] * s["trials"] / 100),
                     "success %": s["success_pct"], "95 % interval": "{:.1f}-{:.1f}".format(*s["success_ci95_pct"]),
                     "failed by": failures(np.asarray(r.trials.outcome), RULE_OUTCOMES),
                     "returns to route": s["mean_route_errors"],
                     "error near route ° (vs route)": s["median_error_deg_near_route"], "error near route ° (vs home)": "",
                     "_route": r})  # fmt: skip
    return rows


def homing_rows(world: str, method: str, route, noises, trials: int, seed: int, db) -> list[dict]:
    """DELV or MinWarping from the route's start to its end (home) on the world's grid database."""
    vm = database_vector_map(db, method, **options(method, world))
    pos = np.asarray(db.rings.positions)
    points = np.asarray(route.route.positions, np.float64)
    near = np.min(np.linalg.norm(pos[:, None] - points[None], axis=-1), 1) <= NEAR_CM
    err = np.asarray(vm.error_deg)[near & np.asarray(vm.valid) & np.asarray(vm.included)]
    length = float(np.sum(np.linalg.norm(np.diff(points, axis=0), axis=-1)))
    step = float(np.linalg.norm(points[1] - points[0]))
    rows = []
    for noise in noises:
        paths = database_rollouts(db, vm, np.repeat(points[:1], trials, 0), step=step, home_radius=NEAR_CM,
                                  max_steps=math.ceil(2.1 * length / step), motion_heading_noise_deg=noise, seed=seed)  # fmt: skip
        outcome = np.asarray(paths.outcome)
        k = int(np.sum(outcome == SUCCESS))
        lo, hi = wilson_pct(k, trials)
        rows.append({"world": world, "method": LABEL[method], "given": "1 snapshot (home)", "noise °": noise,
                     "trials": trials, "successes": k, "success %": 100.0 * k / trials, "95 % interval": f"{lo:.1f}-{hi:.1f}",
                     "failed by": failures(outcome, OUTCOMES),
                     "returns to route": "", "error near route ° (vs route)": "",
                     "error near route ° (vs home)": float(np.median(err)) if len(err) else float("nan")})  # fmt: skip
    return rows


def seed_rows(worlds, models, noises, seeds: int, trials: int, seed: int) -> list[dict]:
    """Route following of every model over `seeds` seeds from `seed` on (one route-following sweep): per world,
    model and noise the mean success over the seeds, their range, and the Wilson interval of the pooled trials."""
    text = (
        f'[sweep]\nkind = "route-following"\ntrials = {trials}\n[axes]\nenv = {list(worlds)}\n'
        f"method = {list(models)}\nheading_noise_deg = {list(noises)}\nseed = {{start = {seed}, stop = {seed + seeds - 1}}}\n"
    )
    ds = run_sweep(parse_sweep(text))
    rows = []
    for world in worlds:
        for model in models:
            for noise in noises:
                at = {"env": world, "homing_method": model, "heading_noise_deg": noise}
                cell = ds.sel({k: v for k, v in at.items() if k in ds.dims})  # an axis of one value is no dimension
                pct = np.atleast_1d(cell.route_success_pct.values)
                k = int(round(float(np.sum(pct * trials / 100.0))))
                lo, hi = wilson_pct(k, trials * len(pct))
                rows.append({"world": world, "method": model, "noise °": noise, "seeds": len(pct),
                             "trials a seed": trials, "success % (mean over seeds)": float(np.mean(pct)),
                             "range over seeds %": f"{pct.min():.0f}-{pct.max():.0f}",
                             "pooled 95 % interval": f"{lo:.1f}-{hi:.1f}",
                             "returns to route": float(np.mean(cell.mean_route_errors.values))})  # fmt: skip
    return rows


def failures(outcome: np.ndarray, names) -> str:
    """ "timeout 3, landmark 1": how the trials that did not succeed ended."""
    counts = {names[c]: int(np.sum(outcome == c)) for c in np.unique(outcome) if c != SUCCESS}
    return ", ".join(f"{k} {v}" for k, v in counts.items())


def success_errorbar(ax, rows: list[dict], x, label: str) -> None:
    """The success of `rows` at `x` with their 95 % Wilson intervals (the rows' "95 % interval": "lo-hi")."""
    y = np.array([r["success %"] for r in rows], np.float64)
    ci = np.array([[float(v) for v in r["95 % interval"].split("-")] for r in rows])
    ax.errorbar(x, y, yerr=[y - ci[:, 0], ci[:, 1] - y], marker="o", capsize=3, label=label)


def success_figure(rows: list[dict], worlds, noises):
    """Success from the route's start against heading noise, one panel a world, one line a method."""
    fig, axes = subplots(1, len(worlds), figsize=(5.5 * len(worlds), 4.2), squeeze=False)
    for ax, world in zip(axes[0], worlds):
        for method in dict.fromkeys(r["method"] for r in rows if r["world"] == world):
            mine = [r for r in rows if r["world"] == world and r["method"] == method]
            success_errorbar(ax, mine, [r["noise °"] for r in mine], method)
        ax.set(xlabel="heading noise per move (°)", ylabel="success from the route's start (%)", ylim=(-5, 105),
               xticks=list(noises), title=world)  # fmt: skip
        ax.legend(fontsize=8)
    fig.set_layout_engine("tight")
    return fig


def run(ctx) -> None:
    seed = ctx.config.seed
    quick = preview(ctx)
    worlds = ("robot",) if quick else ("robot", "natural")
    noises = (30.0,) if quick else (30.0, 60.0)
    trials = 10 if quick else 30
    rows = []
    for world in worlds:
        grid = 60.0 if quick else None
        models = FAMILIARITY[:2] if quick or world != "robot" else FAMILIARITY  # the mushroom body: robot world only
        mine = [row for m in models for row in familiarity_rows(world, m, noises, trials, seed, grid)]
        route = mine[0]["_route"].route
        db = database(world, seed=seed, panoramas=True)
        for method in HOMING:
            mine += homing_rows(world, method, route, noises, trials, seed, db)
        for row in mine:
            tag = f"familiarity:{world}:{row['method']}:{row['noise °']:g}"
            ctx.number(f"{tag}:success_pct", row["success %"])
        rows += mine
        ctx.step(world)
    if quick:
        ctx.step("the natural world: full run only")
    for row in rows:
        row.pop("_route", None)
    ctx.figure(
        "familiarity_success.png",
        success_figure(rows, worlds, noises),
        "Success from the route's start to its end against the heading noise of every move (95 % Wilson "
        "intervals): familiarity models trained on the route, DELV and MinWarping homing to its end.",
    )
    ctx.table(
        "familiarity_routes",
        "Familiarity models on a route, DELV and MinWarping homing to its end",
        rows,
        source="beyond the thesis (Ardin et al. 2016; bob_robotics)",
        note="Familiarity models: trained on the route's images every 4 cm, scan +-60 deg in 2 deg steps; a return "
        f"to the route beyond {NEAR_CM:g} cm counts. DELV, MinWarping: the world's grid database, nearest-snapshot "
        "rollouts with the same step, noise, goal radius and move budget, a trial ending in an obstacle failed (a homing "
        "method heads straight for home; the route bends around the obstacles). Errors: medians over the points within "
        f"{NEAR_CM:g} cm of the route, against the route's direction (familiarity) or home (homing methods).",
    )
    ctx.step("table")
    seeds = 2 if quick else 5
    sweep_models = FAMILIARITY[:2]  # perfect memory and InfoMax (the mushroom body: the first table)
    spread = seed_rows(
        worlds, sweep_models, (30.0, 90.0) if quick else (30.0, 60.0, 90.0), seeds, 4 if quick else 20, seed
    )
    for row in spread:
        ctx.number(
            f"familiarity_seeds:{row['world']}:{row['method']}:{row['noise °']:g}:success_pct",
            row["success % (mean over seeds)"],
        )
    ctx.table(
        "familiarity_seeds",
        f"Route following over {seeds} seeds (a route-following sweep)",
        spread,
        source="beyond the thesis (Ardin et al. 2016; bob_robotics)",
        note="Each seed draws new trial noise and InfoMax's initial weights; the route and its images are the same. "
        "Mean and range of the success over the seeds, and the 95 % Wilson interval of all the seeds' trials pooled.",
    )
    ctx.step("seeds")
