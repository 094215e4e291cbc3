"""DELV, MinWarping and their hybrid (thesis §6.3.3's future work; docs/model.md §4.7-4.8), on rendered
images of the robot and natural worlds.

The thesis closes (§6.3.3) with "combining two methods in a complementary manner" as future work: DELV
where its landmark matching converges, an image method where it does not. Here the image method is
MinWarping (Möller 2009), the holistic method the field measures itself against. The three are
compared by mean angular error, error classes (e > 45°, e > 90°) and catchment (nearest-snapshot
rollouts from every image, docs/images.md §7), on the robot world (four red cylinders) with every
choice of k = 0, 1, 2 of them hidden in the current views (the home record sees all, as in thesis
Table 5.3) and on the natural world. Camera noise as in the other image studies; no compass.
"""

from __future__ import annotations

import dataclasses
from itertools import combinations

import equinox as eqx
import jax
import numpy as np

from delvjax.core.maps import VectorMap
from delvjax.core.methods.hybrid import HybridGate, combine
from delvjax.images import database_catchment, database_success_rate, database_vector_map, image_world
from delvjax.images._evaluate import catchment_numbers
from delvjax.images._render import render_rings
from delvjax.plots import database_map_figure, subplots

from ._images_common import CAMERA_NOISE, ROBOT_SCALE, database, numbers, preview

TITLE = "DELV, MinWarping and the hybrid of thesis §6.3.3, on rendered images"
COST = 130  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
HIDDEN = (0, 1, 2)  # cylinders hidden from the robot database's current views (a preview: 0 and 1)
STEPS = len(HIDDEN) + 2  # a step per number hidden, then the natural database and the table
METHODS = ("delv", "minwarping", "hybrid")
LABEL = {"delv": "DELV", "minwarping": "MinWarping", "hybrid": "hybrid"}
GRID = {"n_alpha": 90, "n_psi": 90}  # 360-column panoramas: 96 does not divide 360, 90 does
DISTANCES = (30.0, 50.0, 70.0)  # cm from home, release distances in the 1.8 m arena


def options(method: str, world: str) -> dict:
    """The settings of each method: MinWarping's grid on 360 columns, DELV's scale in the small arena."""
    out = dict(GRID) if method != "delv" else {}
    if world == "robot" and method != "minwarping":
        out["scale"] = ROBOT_SCALE
    return out


def occluded(full, world: str, hidden: tuple[int, ...], seed: int):
    """The database `full` rendered again with the cylinders `hidden` removed (height 0: never hit)."""
    iw = image_world(world)
    cyl = np.asarray(iw.world.cylinders).copy()
    cyl[list(hidden), 3] = 0.0
    iw = dataclasses.replace(iw, world=eqx.tree_at(lambda w: w.cylinders, iw.world, jax.numpy.asarray(cyl)))
    ex = dataclasses.replace(full.extractor, panorama=True)
    pos = np.asarray(full.rings.positions)
    rings = render_rings(iw, CAMERA_NOISE, pos, np.zeros(len(pos), np.float32), jax.random.PRNGKey(seed), ex)
    return dataclasses.replace(full, rings=rings)


def maps(db, full, world: str) -> dict:
    """The vector maps of METHODS on `db`. The hybrid's is put together from DELV's, MinWarping's and
    where DELV converged (`hybrid_map`): MinWarping's search, nearly all of the time, runs once."""
    out = {m: database_vector_map(db, m, home_rings=full.rings, **options(m, world)) for m in ("delv", "minwarping")}
    gate = database_vector_map(db, HybridGate(), home_rings=full.rings, **options("hybrid", world))
    out["hybrid"] = hybrid_map(out["delv"], gate, out["minwarping"])
    return out


def hybrid_map(delv: VectorMap, gate: VectorMap, image: VectorMap) -> VectorMap:
    """The hybrid's map (docs/model.md §4.8) from DELV's, the `HybridGate`'s (valid where DELV
    converged) and the image method's, point by point as `Hybrid` chooses (`hybrid.combine`)."""
    direction, valid, _ = combine(delv.direction, delv.valid, gate.valid, image.direction, image.valid)
    error, _, _ = combine(delv.error_deg, delv.valid, gate.valid, image.error_deg, image.valid)
    return dataclasses.replace(delv, direction=direction, valid=valid, error_deg=error)


def evaluate(db, vm, seed: int) -> dict:
    """A map's numbers and its catchment (nearest-snapshot rollouts from every image)."""
    _, paths = database_catchment(db, vm, seed=seed)
    return {**numbers(vm), **catchment_numbers(paths), "map": vm}


def maps_figure(db, results: dict, title: str):
    """The three vector maps side by side (Fig 4.18 style)."""
    fig, axes = subplots(1, len(METHODS), figsize=(5.2 * len(METHODS), 5.4))
    for ax, m, tag in zip(axes, METHODS, "abc"):
        r = results[m]
        database_map_figure(db, r["map"], f"({tag}) {LABEL[m]}: mean error {r['mean_error_deg']:.1f}°", ax=ax)
    fig.suptitle(title)
    fig.set_layout_engine("tight")
    return fig


def occlusion_figure(summary: dict, ks):
    """Mean error and catchment against the number of hidden cylinders (robot world), one line a method."""
    fig, (a, b) = subplots(1, 2, figsize=(10.0, 4.0))
    for m, style in zip(METHODS, ("o-", "s--", "^:")):  # dashes: the hybrid often lies on MinWarping
        a.plot(ks, [summary[("robot", k, m)]["mean error °"] for k in ks], style, label=LABEL[m])
        b.plot(ks, [summary[("robot", k, m)]["catchment %"] for k in ks], style, label=LABEL[m])
    a.set(xlabel="cylinders hidden from the current views", ylabel="mean angular error (°)", xticks=list(ks))
    b.set(xlabel="cylinders hidden from the current views", ylabel="catchment (%)", xticks=list(ks), ylim=(0, 100))
    a.legend()
    fig.suptitle("Robot world, every choice of hidden cylinders averaged")
    fig.set_layout_engine("tight")
    return fig


def run(ctx) -> None:
    seed = ctx.config.seed
    ks = HIDDEN[:2] if preview(ctx) else HIDDEN
    rows, summary = [], {}
    full = database("robot", seed=seed, panoramas=True)
    for k in ks:
        subsets = list(combinations(range(4), k))[: 1 if preview(ctx) else None]
        results = {m: [] for m in METHODS}
        for hidden in subsets:
            db = occluded(full, "robot", hidden, seed) if hidden else full
            for m, vm in maps(db, full, "robot").items():
                results[m].append(evaluate(db, vm, seed))
        if k == 0:
            success_table(ctx, full, {m: r[0]["map"] for m, r in results.items()}, seed)
            ctx.figure(
                "hybrid_robot_maps.png",
                maps_figure(full, {m: r[0] for m, r in results.items()}, "Robot world, no cylinder hidden"),
                "DELV, MinWarping and the hybrid on the rendered robot world (no compass; red x: invalid).",
            )
        for m in METHODS:
            r = results[m]
            summary[("robot", k, m)] = row = {
                "world": "robot",
                "hidden k": k,
                "choices": len(r),
                "method": LABEL[m],
                "mean error °": float(np.mean([x["mean_error_deg"] for x in r])),
                "e>45 %": float(np.mean([x["gt45_pct"] for x in r])),
                "e>90 %": float(np.mean([x["gt90_pct"] for x in r])),
                "catchment %": float(np.mean([x["catchment_pct"] for x in r])),
                "catchment range %": f"{min(x['catchment_pct'] for x in r):.1f}-{max(x['catchment_pct'] for x in r):.1f}",
            }
            rows.append(row)
            ctx.number(f"hybrid:robot:k{k}:{m}:mean_error_deg", row["mean error °"])
            ctx.number(f"hybrid:robot:k{k}:{m}:catchment_pct", row["catchment %"])
        ctx.step(f"robot, {k} hidden")
    if len(ks) < len(HIDDEN):  # a preview: the bar still ends at its total
        ctx.step("more cylinders hidden: full run only")
    ctx.figure(
        "hybrid_occlusion.png",
        occlusion_figure(summary, ks),
        "Mean angular error and catchment of DELV, MinWarping and the hybrid against the number of cylinders "
        "hidden from the current views (robot world; each point the mean over every choice).",
    )
    if not preview(ctx):
        nat = database("natural", seed=seed, panoramas=True)
        nat_results = {}
        for m, vm in maps(nat, nat, "natural").items():
            x = nat_results[m] = evaluate(nat, vm, seed)
            summary[("natural", 0, m)] = row = {
                "world": "natural",
                "hidden k": 0,
                "choices": 1,
                "method": LABEL[m],
                "mean error °": x["mean_error_deg"],
                "e>45 %": x["gt45_pct"],
                "e>90 %": x["gt90_pct"],
                "catchment %": x["catchment_pct"],
                "catchment range %": "",
            }
            rows.append(row)
            ctx.number(f"hybrid:natural:{m}:mean_error_deg", x["mean_error_deg"])
            ctx.number(f"hybrid:natural:{m}:catchment_pct", x["catchment_pct"])
        ctx.figure(
            "hybrid_natural_maps.png",
            maps_figure(nat, nat_results, "Natural world"),
            "DELV, MinWarping and the hybrid on the rendered natural world (no compass).",
        )
    ctx.step("natural")
    ctx.table(
        "hybrid_delv_minwarping",
        "DELV, MinWarping and the hybrid (DELV where its matching converges), no compass",
        rows,
        source="thesis §6.3.3 (future work)",
        note=verdict(summary) + " Hidden: cylinders removed from the current views (the home record sees all), "
        "every choice of k averaged. Catchment: nearest-snapshot rollouts from every image.",
    )
    ctx.step("table")


def success_table(ctx, db, maps: dict, seed: int) -> None:
    """Success rate against release distance on the robot world, no cylinder hidden (95 % Wilson)."""
    trials = 20 if preview(ctx) else 100
    rows = []
    for m, vm in maps.items():
        for r in database_success_rate(db, vm, DISTANCES, trials=trials, seed=seed):
            rows.append(
                {
                    "method": LABEL[m],
                    "distance cm": r["distance_cm"],
                    "placed": r["placed"],
                    "successes": r["successes"],
                    "success %": r["success_pct"],
                    "95 % interval": f"{r['ci_lo_pct']:.1f}-{r['ci_hi_pct']:.1f}",
                }
            )
            ctx.number(f"hybrid:robot:success:{m}:{r['distance_cm']:g}", r["success_pct"])
    ctx.table(
        "hybrid_success_rate",
        "Success rate against release distance, robot world, no cylinder hidden",
        rows,
        source="thesis §6.3.3 (future work); Fig 4.10b style",
        note=f"{trials} releases per distance in seeded directions (those inside the arena and clear of the "
        "cylinders are placed); nearest-snapshot rollouts; 95 % Wilson intervals.",
    )


def verdict(summary: dict) -> str:
    """Where the hybrid beats both (lower mean error and a catchment at least as large), in words."""
    wins, losses = [], []
    for world, k in sorted({(w, k) for w, k, _ in summary}):
        h, d, m = (summary[(world, k, x)] for x in ("hybrid", "delv", "minwarping"))
        where = f"{world} k={k}"
        if h["mean error °"] < min(d["mean error °"], m["mean error °"]) and h["catchment %"] >= max(
            d["catchment %"], m["catchment %"]
        ):
            wins.append(where)
        else:
            losses.append(where)
    return (
        f"The hybrid beats both (lower mean error, catchment at least as large) on: {', '.join(wins) or 'none'}; "
        f"not on: {', '.join(losses) or 'none'}."
    )
