"""World ensembles of the robot images: claims 14-16 over every robot arena the thesis's words allow (beyond the
thesis; docs/reproduce.md "Ensembles: the robot images").

The `robot_images` study judges the claims of §4.4.1 (DELV errs more on images than on ideal rings but still
homes; DELV beats predictive image matching; quantized distances err about as much) on one reconstructed arena.
Here MEMBERS members of the `robot` world family (env1's rules in the 1.8 m arena, docs/model.md §6.1) become
image worlds like the built-in one (`robot_arena`: red cylinders 50 cm tall, the textured walls, camera noise),
their databases are rendered, and DELV, image matching (gray ring) and DELV with 1, 2, 4, 5 distance levels give
image maps, nearest-snapshot catchments and the ideal ring-model maps, each one program over every member
(`_ensemble_robot`). Member i's images carry the camera noise of seed + i // SLICE (slices of the run's seeds, as
the other ensemble studies); the built-in world runs in the same programs beside them under the run's seed, and
its numbers are `robot_images`'s to the last bit (the table says so).
"""

from __future__ import annotations

import numpy as np

from delvjax.envs import family, world_properties
from delvjax.images._worlds import robot_arena
from delvjax.plots import subplots

from ..claims import CHECKS, WORLD_FAILS, WORLD_HOLDS, Missing
from ..claims._common import HOLDS as HOLDS_TEXT
from ._ensemble_robot import (
    Members,
    catchments,
    ideal_maps,
    image_maps,
    map_numbers,
    member_worlds,
    render_members,
    robot_layouts,
)
from ._ensemble_stats import BAND, claim_rows, deciding_property
from ._images_common import LABEL, ROBOT_SCALE
from .ensembles import CLAIMS_TABLE_NOTE, MEMBERS, QUICK_MEMBERS, SEED_SLICES, record_claims

TITLE = "World ensembles: the robot images over every arena the thesis's words allow (beyond the thesis)"
COST = 60  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 3
LEVELS = (1, 2, 4, 5)
SLICE = -(-MEMBERS // SEED_SLICES)  # members per camera-noise seed
CLAIM_IDS = (
    "robot_images_delv_errs_more_but_homes",
    "robot_images_delv_beats_warping",
    "robot_images_quantized_similar",
)
# (key tag, method, options, ideal map too) of every map; the tags are robot_images's
MAPS = (
    ("delv", "delv", {}, True),
    ("warping", "warping", {}, True),
    *((f"delv:Q{q}", "delv", {"levels": q, "scale": ROBOT_SCALE}, True) for q in LEVELS),
)
PREVIEW_MAPS = ("delv", "warping", "delv:Q1")  # the preview: the image programs only (no ideal rings)


def plan(ctx) -> tuple[int, bool]:
    """(members, full): the full ensemble, or under --quick or the tests' coarse grid a preview of QUICK_MEMBERS
    members without the ideal ring maps."""
    if ctx.config.quick or ctx.config.spacing > 100:
        return QUICK_MEMBERS, False
    return MEMBERS, True


def run_members(members: int, seed: int, full: bool, step=None) -> tuple[dict[str, dict], Members, np.ndarray]:
    """({world label: {robot_images key: value}}, the databases, the members' layouts): the built-in robot world
    ("robot") and `members` members ("robot-m<i>"), every map one program over all of them."""
    layouts = robot_layouts(members, seed)
    names = [f"robot-m{i}" for i in range(members)]
    worlds = [robot_arena(), *member_worlds(layouts, names)]
    m = render_members(worlds, [seed] + [seed + i // SLICE for i in range(members)])
    if step is not None:
        step("rendered")
    labels = ["robot", *names]
    out: dict[str, dict] = {label: {} for label in labels}

    def put(key: str, values) -> None:
        for label, v in zip(labels, np.asarray(values, float).tolist()):
            out[label][key] = v

    for tag, method, options, ideal in MAPS:  # a handful of method calls, each over every member
        if not full and tag not in PREVIEW_MAPS:
            continue
        vm = image_maps(m, method, **options)
        nums = map_numbers(vm)
        put(f"robot_images:{tag}:mean_error_deg", nums["mean_error_deg"])
        put(f"robot_images:{tag}:gt45_pct", nums["gt45_pct"])
        put(f"robot_images:{tag}:invalid", nums["invalid"])
        if ":" not in tag:  # the continuous methods: catchments
            put(f"robot_images:{tag}:catchment_pct", catchments(m, vm, seed)[0])
        if ideal and full:
            ideal_nums = map_numbers(ideal_maps(m, method, **options))
            put(f"robot_images:{tag}:ideal_mean_error_deg", ideal_nums["mean_error_deg"])
    if step is not None:
        step("maps")
    return out, m, layouts


def member_verdicts(worlds: dict[str, dict], members: int, claim_id: str) -> list[str]:
    """The check's verdict of `claim_id` in every member ("n/a" where a number is missing)."""
    fn = CHECKS[claim_id]
    verdicts = []
    for i in range(members):  # the plain-Python checks of studies/claims, once per member (post-processing)
        flat = worlds[f"robot-m{i}"]

        def get(key, flat=flat):
            if key not in flat:
                raise Missing(key)
            return flat[key]

        try:
            verdicts.append(fn(get)[1])
        except Missing:
            verdicts.append("n/a")
    return verdicts


def robot_claim_rows(worlds: dict[str, dict], members: int, layouts: np.ndarray) -> list[dict]:
    """`_ensemble_stats.claim_rows` of CLAIM_IDS over the robot members, with the deciding property of a claim
    that depends on the world taken about the robot family's home (claim_rows's properties are the 10 m
    worlds')."""
    rows = claim_rows(worlds, members, {"robot": layouts}, ids=set(CLAIM_IDS))
    props = {"robot": world_properties(layouts, family("robot").home)}
    for r in rows:
        r.pop("decided_by_values", None)
        r["decided_by"] = ""
        if r["verdict over worlds"] == "depends on the world":
            held = np.array([v == HOLDS_TEXT for v in member_verdicts(worlds, members, r["id"])])
            best = deciding_property(held, props)
            if best is not None:
                fam, prop, auc, values = best
                r["decided_by"] = f"{fam} {prop} (AUC {auc:.2f})"
                r["decided_by_values"] = {"family": fam, "property": prop, "values": values, "holds": held.tolist()}
        r["built-in robot world"] = member_verdicts({"robot-m0": worlds["robot"]}, 1, r["id"])[0]
    return rows


def number_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """Per recorded quantity: the median and BAND over the members beside the built-in world's value."""
    rows = []
    for key in worlds["robot"]:
        sample = np.array([worlds[f"robot-m{i}"][key] for i in range(members)], float)
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
        tag, _, quantity = key.split(":", 1)[1].rpartition(":")
        method = tag.split(":")[0]
        rows.append(
            {
                "method": LABEL[method] + (f", {tag.split(':')[1][1:]} levels" if ":Q" in tag else ""),
                "quantity": quantity,
                "ours median": float(med),
                "ours 5 %": float(lo),
                "ours 95 %": float(hi),
                "built-in world": worlds["robot"][key],
                "built-in inside band": bool(lo <= worlds["robot"][key] <= hi),
                "members": members,
                "key": key,
            }
        )
    return rows


def member_rows(worlds: dict[str, dict], layouts: np.ndarray) -> list[dict]:
    """One row per member: its cylinders and its numbers (the CSV behind every band)."""
    rows = []
    for i, lay in enumerate(layouts):
        row = {"member": f"robot-m{i}"}
        row.update({f"landmark {j} {c}": float(v) for j, xyr in enumerate(lay) for c, v in zip("xyr", xyr)})
        row.update({k.split(":", 1)[1]: v for k, v in worlds[f"robot-m{i}"].items()})
        rows.append(row)
    return rows


def members_figure(worlds: dict[str, dict], members: int):
    """Per member: (a) DELV's mean error on images against ideal rings, by whether it homes (when the ideal rings
    ran); (b) DELV's against image matching's mean error; (c) each level's mean error minus the continuous one."""
    get = lambda key: np.array([worlds[f"robot-m{i}"][key] for i in range(members)], float)  # noqa: E731
    ideal = "robot_images:delv:ideal_mean_error_deg" in worlds["robot-m0"]
    fig, axes = subplots(1, 3 if ideal else 2, figsize=(15.0 if ideal else 10.0, 4.6))
    img, catch = get("robot_images:delv:mean_error_deg"), get("robot_images:delv:catchment_pct")
    homes = catch >= 75.0
    if ideal:
        x = get("robot_images:delv:ideal_mean_error_deg")
        top = float(max(img.max(), x.max())) * 1.05
        axes[0].scatter(x[homes], img[homes], s=14, color="tab:green", label="catchment >= 75 %")
        axes[0].scatter(x[~homes], img[~homes], s=14, color="tab:red", label="catchment < 75 %")
        axes[0].plot([0, top], [0, top], color="0.5", lw=0.8, label="equal")
        axes[0].plot([0, top], [1, top + 1], color="0.5", lw=0.8, ls="--", label="images = ideal + 1°")
        axes[0].set(xlabel="ideal rings: mean error (°)", ylabel="images: mean error (°)")
        axes[0].set_title("(a) DELV, images vs ideal rings")
        axes[0].legend(fontsize=7, loc="upper left")
    a, b = axes[-2:]
    w = get("robot_images:warping:mean_error_deg")
    top = float(max(img.max(), w.max())) * 1.05
    better = (img <= w - 2.0) & (catch >= get("robot_images:warping:catchment_pct") + 2.0)
    a.scatter(w[better], img[better], s=14, color="tab:green", label="DELV better on both")
    a.scatter(w[~better], img[~better], s=14, color="tab:red", label="not")
    a.plot([0, top], [0, top], color="0.5", lw=0.8, label="equal")
    a.set(xlabel="image matching: mean error (°)", ylabel="DELV: mean error (°)")
    a.set_title(f"({'b' if ideal else 'a'}) DELV vs image matching, images")
    a.legend(fontsize=7, loc="lower right")
    levels = [q for q in LEVELS if f"robot_images:delv:Q{q}:mean_error_deg" in worlds["robot-m0"]]
    for j, q in enumerate(levels):
        d = get(f"robot_images:delv:Q{q}:mean_error_deg") - img
        b.scatter(np.full(members, j) + np.linspace(-0.25, 0.25, members), d, s=8, color="tab:blue")
    b.axhline(10.0, color="tab:red", lw=0.8, ls="--")
    b.axhline(-10.0, color="tab:red", lw=0.8, ls="--")
    b.set_xticks(range(len(levels)), [str(q) for q in levels])
    b.set(xlabel="distance levels", ylabel="mean error − continuous (°)")
    b.set_title(f"({'c' if ideal else 'b'}) DELV, quantized, images")
    fig.set_layout_engine("tight")
    return fig


def run(ctx) -> None:
    members, full = plan(ctx)
    seed = ctx.config.seed
    worlds, _, layouts = run_members(members, seed, full, ctx.step)
    sizes = (
        f"{members} members of the robot family (seed {seed}), camera noise under seeds {seed}.."
        f"{seed + (members - 1) // SLICE}, the built-in world's 20 cm database grid and every database point a "
        "release (as robot_images)"
    )
    ctx.number("ensemble_robot:members", members)
    ctx.json(
        "ensemble_robot_worlds.json",
        {
            "settings": {"members": members, "seed": seed, "slice": SLICE, "full": full},
            "layouts": layouts.tolist(),
            "properties": {k: v.tolist() for k, v in world_properties(layouts, family("robot").home).items()},
            "numbers": worlds,
        },
    )
    ctx.csv("ensemble_robot_members.csv", rows=member_rows(worlds, layouts))
    ctx.table(
        "robot_images_over_worlds",
        "Robot images over the worlds: median and band over the members beside the built-in world",
        number_rows(worlds, members),
        source="Figs 4.18-4.21",
        note=f"{sizes}; band: the {BAND[0]:g}-{BAND[1]:g} % percentiles over the members. Built-in world: the robot "
        "world rendered in the same program as the members, equal to robot_images's numbers (tests/studies/"
        "test_ensemble_robot.py). Only the rows of the extractor's 10° band are rendered: the same rays and noise as "
        "the whole panorama's (the rings are equal). Mean errors over every database point but home.",
    )
    ctx.step("claims")
    rows = robot_claim_rows(worlds, members, layouts)
    record_claims(
        ctx,
        rows,
        "claims_over_worlds_robot",
        "Claims of the robot images over the worlds: the share of robot arenas in which each claim's check holds",
        CLAIMS_TABLE_NOTE.format(holds=WORLD_HOLDS, fails=WORLD_FAILS)
        + f" {sizes}. Deciding property: about the arena's centre (home).",
        figure="claims_decided_by_robot.png",
    )
    ctx.figure(
        "robot_images_over_worlds.png",
        members_figure(worlds, members),
        f"Robot images over the worlds ({sizes}), per member: "
        + (
            "(a) DELV's mean error on the images against the ideal rings of the same layout, green where the "
            "nearest-snapshot catchment reaches 75 % (claim 14); (b) "
            if full
            else "(a) "
        )
        + "DELV's mean error against image matching's, green where DELV is better by 2° and 2 catchment points "
        "(claim 15); "
        + ("(c)" if full else "(b)")
        + " DELV with distance levels minus continuous distances; dashed: ±10° (claim 16)."
        + ("" if full else " A preview: no ideal rings, one level."),
    )
