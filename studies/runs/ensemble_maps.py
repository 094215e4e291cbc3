"""World ensembles, second part: the claims on the visual compass, the error curves and the landmark hull over
the worlds the thesis's words allow (beyond the thesis; docs/reproduce.md "Ensembles: visual compass, error
curves and the landmark hull").

The `ensembles` study judges the claims its catchment sweeps make; this one those that need per-point errors
(error curves by distance from home, error points inside and outside the landmarks' hull: claims 2, 7, 19),
the visual compass (claims 30-33) and compass noise. The same families and members as `ensembles` (env1-3;
member i of every family, members in seed slices, layouts from the run's seed): per-point vector maps on the
point run's 25 cm grid (`sweeps.point_errors`), the visual and true compass on the ensembles' 100 cm grid
(vector maps, heading errors and the visual compass's rollouts, which cost 50 times a vector map, for every
member; the built-in worlds' rollouts in the first slice), each kind of run one compiled program for every member. The built-in worlds
run in every slice under its seed, beside the members (the grid check: what the coarse grid moves). Claim 11:
DELV's per-point maps on env1's members with Q = 1..5 distance levels (one sweep per slice, `levels` an axis);
claims 5 and 6: DELV's and image matching's in seeded random layouts of 3, 4 and 5 landmarks, member i's nested
(one sweep)."""

from __future__ import annotations

import jax
import numpy as np

from delvjax.core.maps import grid_points
from delvjax.envs import ensemble_envs, world_properties
from delvjax.options import make_sensor
from delvjax.sweeps import parse_sweep, point_errors, run_sweep

from ..claims import WORLD_FAILS, WORLD_HOLDS
from ._ensemble_maps import (
    compass_keys,
    curve_keys,
    heading_errors,
    heading_stats,
    level_keys,
    member_label,
    merge,
    random_worlds,
    stacked_env,
    visual_keys,
    with_continuous,
)
from ._ensemble_maps_report import (
    CLAIMS_NOTE,
    builtin_verdict,
    curve_rows,
    curves_figure,
    distribution_rows,
    visual_figure,
)
from ._ensemble_stats import claim_rows
from ._settings_design import MASK_ROWS
from .ensembles import EVERY_METHOD, LANES, record_claims
from .visual_compass import BACKGROUNDS, TRUE, VISUAL

TITLE = (
    "World ensembles: the visual compass, error curves and the landmark hull over every world the thesis's words "
    "allow (beyond the thesis)"
)
COST = 500  # rough seconds of a full run: 300 before the visual catchments of every slice (about +145 CPU-s a slice)
FAMILIES = ("env1", "env2", "env3")
MAP_METHODS = ("delv", "delv-compass", "acv", "alv", "warping")  # per-point maps: claims 2, 7, 19
SIGMAS = (0.0, 45.0)  # compass noise (claim 33 reads the catchment lost from 0 to 45 degrees)
MEMBERS = 44  # members per family (as `ensembles`), in SLICES seed slices of 11
SLICES = 4
VISUAL_SLICES = SLICES  # slices whose members run the visual compass's rollouts (claims 31, 33: all 44 members)
MAP_SPACING = 25.0  # cm: the per-point maps' grid, the point run's (error curves need points in every bin)
SPACING = (
    100.0  # cm: the compasses' grid, the ensembles' (128 trials advance side by side: a coarser one costs as much)
)
PREVIEW = {"members": 2, "slices": 1, "map_spacing": 200.0, "spacing": 200.0}  # --quick and the test suite's tiny run
FULL = {"members": MEMBERS, "slices": SLICES, "map_spacing": MAP_SPACING, "spacing": SPACING}
# claims judged over every member; over the members of the visual slices (they read the visual compass's catchments)
CLAIMS = {
    "errors_outside_landmark_hull",
    "delv_smaller_error_than_warping",
    "delv_vs_acv_alv_error_mixed",
    "visual_compass_not_exact",
    "visual_compass_error_order",
    "quantized_error_small_and_level_insensitive",  # claim 11: DELV's quantized levels on env1's members
    "few_landmarks_error_below_90",  # claims 5, 6: random layouts of 3, 4 and 5 landmarks
    "warping_sensitive_to_landmark_number",
}
VISUAL_CLAIMS = {"visual_compass_catchment_order", "delv_least_compass_dependent"}
LEVELS = (1, 2, 3, 4, 5)  # DELV's distance levels Q (the `quantization` study's; continuous: the maps' own DELV)
COUNTS = (3, 4, 5)  # landmarks of the random layouts (the `landmark_number` study's)
RANDOM_METHODS = ("delv", "warping")  # claims 5 (DELV) and 6 (image matching against DELV)
RANDOM_BASE = 1000  # member i's random layouts: seed RANDOM_BASE * (run seed + 1) + i, one seed for 3, 4 and 5
POINT_RUN_SEED = 100  # `landmark_number` draws n landmarks under seed 100 + n: the built-in `random`
STEPS = 6


def plan(ctx) -> dict:
    """The run's sizes: FULL, or under --quick or a grid coarser than SPACING (the test suite's tiny run) the
    PREVIEW (2 members on a 200 cm grid, the per-point maps of the landmark methods only)."""
    preview = ctx.config.quick or ctx.config.spacing > SPACING
    return dict(PREVIEW if preview else FULL, preview=preview)


def sweep_text(kind: str, envs: list[str], methods, spacing: float, seed: int, **axes) -> str:
    """A sweep file (docs/sweeps.md): `envs` as written on the env axis, one spacing and seed, more axes."""
    quoted = lambda names: "[" + ", ".join(f'"{n}"' for n in names) + "]"  # noqa: E731
    extra = "".join(f"{k} = {quoted(v) if isinstance(v[0], str) else list(v)}\n" for k, v in axes.items())
    metrics = {
        "catchment": '["catchment_pct", "catchment_physical_pct", "mean_error_deg"]',
        "vector-map": '["mean_error_deg"]',
    }[kind]
    return (
        f'[sweep]\nkind = "{kind}"\nmetrics = {metrics}\n[axes]\nenv = [{", ".join(envs)}]\n'
        f"method = {quoted(methods)}\nspacing = [{spacing}]\nseed = [{seed}]\n{extra}"
    )


def slice_envs(size: int, j: int, seed: int, families=FAMILIES) -> list[str]:
    """The env axis of slice j: `size` members of every family from member j * size (layouts from the run's
    seed), and the built-in worlds (in every slice: one shape for every slice's program)."""
    members = [f'{{ensemble = "{f}", members = {size}, first = {j * size}, seed = {seed}}}' for f in families]
    return members + [f'"{f}"' for f in families]


def run_slice(ctx, sizes: dict, j: int, size: int, worlds: dict) -> None:
    """One seed slice (the run's seed + j): the per-point maps, and on the full run the true compass's
    catchments, the visual compass's vector maps and heading errors, and in the visual slices its rollouts
    (the built-in worlds' in the first)."""
    seed, lanes = ctx.config.seed + j, ctx.config.lanes
    envs = slice_envs(size, j, ctx.config.seed)
    suffix = f"@{j}" if j else ""  # the built-in worlds of slice j: `env1@j` (their seed spread)
    methods = MAP_METHODS[:4] if sizes["preview"] else MAP_METHODS
    spec = parse_sweep(sweep_text("vector-map", envs, methods, sizes["map_spacing"], seed), "maps")
    add(worlds, curve_keys(point_errors(spec), methods, spec.axes["env"]), suffix)
    envs1 = slice_envs(size, j, ctx.config.seed, families=("env1",))  # claim 11: one program over every Q
    spec = parse_sweep(sweep_text("vector-map", envs1, ["delv"], sizes["map_spacing"], seed, levels=LEVELS), "levels")
    add(worlds, level_keys(point_errors(spec), spec.axes["env"], LEVELS), suffix)
    if sizes["preview"]:
        return
    text = sweep_text("catchment", envs, TRUE, sizes["spacing"], seed, compass_noise_deg=SIGMAS)
    # the `ensembles` study's compiled program (its methods, masks and lanes): no program of its own
    shared = {"lanes": min(LANES, lanes), "method_set": EVERY_METHOD, "mask_rows": MASK_ROWS}
    add(worlds, compass_keys(run_sweep(parse_sweep(text, "compass"), **shared), TRUE, SIGMAS), suffix)
    for bg in BACKGROUNDS:  # three sweeps of one program per method (the background a traced leaf)
        text = sweep_text("vector-map", envs, VISUAL, sizes["spacing"], seed, background=[bg])
        add(worlds, visual_keys(run_sweep(parse_sweep(text, "visual")), zip(TRUE, VISUAL), bg, False), suffix)
        if j < VISUAL_SLICES:  # the built-in worlds' catchments in the first slice only (the same program)
            where = envs if j == 0 else envs[: len(FAMILIES)]
            text = sweep_text("catchment", where, VISUAL, sizes["spacing"], seed, background=[bg])
            ds = run_sweep(parse_sweep(text, "visual"), lanes=lanes)
            add(worlds, visual_keys(ds, zip(TRUE, VISUAL), bg, True), suffix)
    add(worlds, heading_keys(ctx, size, j, sizes["spacing"], seed), suffix)


def random_layouts(ctx, sizes: dict, worlds: dict) -> dict[str, np.ndarray]:
    """Claims 5 and 6: DELV's and image matching's per-point maps in `members` seeded random layouts of 3, 4 and
    5 landmarks (member i: one seed, its fewer landmarks the first of its more: nested) and in the
    `landmark_number` study's three (the built-in `random`: separate seeds), one sweep; their layouts (W, n, 3)
    per count (`random<n>`, for the property that decides a claim). The preview: DELV only."""
    base = RANDOM_BASE * (ctx.config.seed + 1)
    envs = [f"{{random = {sizes['members']}, landmarks = {list(COUNTS)}, seed = {base}}}"]
    envs += [f"{{random = 1, landmarks = [{n}], seed = {POINT_RUN_SEED + n}}}" for n in COUNTS]
    methods = RANDOM_METHODS[:1] if sizes["preview"] else RANDOM_METHODS
    spec = parse_sweep(sweep_text("vector-map", envs, methods, sizes["map_spacing"], ctx.config.seed), "random")
    res = point_errors(spec)
    merge(worlds, random_worlds(curve_keys(res, methods, spec.axes["env"]), res["landmarks"], base))
    members = range(base, base + sizes["members"])
    return {f"random{n}": np.stack([res["landmarks"][f"random{s}-{n}"] for s in members]) for n in COUNTS}


def add(worlds: dict, more: dict, suffix: str) -> None:
    """Merge a sweep's numbers; a built-in world (no `-m`) of slice j under `<name>@j`."""
    merge(worlds, {k: v for k, v in more.items() if "-m" in k})
    merge(worlds, {k: v for k, v in more.items() if "-m" not in k}, suffix)


def heading_keys(ctx, size: int, j: int, spacing: float, seed: int) -> dict[str, dict]:
    """The visual compass's heading errors on env1's members of slice j and the built-in env1 (claim 30 reads
    env1's): one program over every world and background (`_ensemble_maps.heading_errors`)."""
    members = ensemble_envs("env1", size, ctx.config.seed, first=j * size)
    envs = stacked_env([*members, "env1"], pad=4)
    sensors = jax.tree.map(lambda *x: np.stack(x), *[make_sensor(background=bg) for bg in BACKGROUNDS])
    points = grid_points(np.asarray(envs.arena[0]), spacing)
    err, included = heading_errors(envs, points, jax.random.PRNGKey(seed), sensors)
    stats = heading_stats(np.asarray(err), np.asarray(included))
    labels = [member_label(m["name"]) for m in members] + ["env1"]
    return {
        label: {f"visual:{bg}:{name}": float(v[w, b]) for name, v in stats.items() for b, bg in enumerate(BACKGROUNDS)}
        for w, label in enumerate(labels)
    }


def run(ctx) -> None:
    sizes = plan(ctx)
    members, slices = sizes["members"], sizes["slices"]
    size = -(-members // slices)
    worlds: dict[str, dict] = {}
    for j in range(slices):  # a handful of seed slices of the same programs: input preparation
        run_slice(ctx, sizes, j, size, worlds)
        ctx.step(f"slice {j + 1} of {slices}")
    with_continuous(worlds)
    random = random_layouts(ctx, sizes, worlds)
    ctx.step("random layouts of 3, 4 and 5 landmarks")
    for _ in range(STEPS - slices - 1):
        ctx.step("preview: the other slices are the full run's")
    seed = ctx.config.seed
    layouts = {
        fam: np.array(
            [[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in ensemble_envs(fam, members, seed)]
        )
        for fam in FAMILIES
    } | random
    visual_members = min(members, VISUAL_SLICES * size)
    claims = claim_rows(worlds, members, layouts, ids=CLAIMS)
    claims += [] if sizes["preview"] else claim_rows(worlds, visual_members, layouts, ids=VISUAL_CLAIMS)
    claims.sort(key=lambda r: r["#"])
    ctx.number("ensemble_maps:members", [members, 0 if sizes["preview"] else visual_members])
    ctx.number("ensemble_maps:spacing", [sizes["map_spacing"], sizes["spacing"]])
    ctx.json(
        "ensemble_maps_worlds.json",
        {
            "settings": {**{k: v for k, v in sizes.items()}, "seed": seed, "visual_members": visual_members},
            "layouts": {fam: lay.tolist() for fam, lay in layouts.items()},
            "properties": {
                fam: {k: v.tolist() for k, v in world_properties(lay).items()} for fam, lay in layouts.items()
            },
            "numbers": worlds,
        },
    )
    record_claims(
        ctx,
        claims,
        "claims_over_worlds",
        "Claims over the worlds: visual compass, error curves and the landmark hull",
        CLAIMS_NOTE.format(holds=WORLD_HOLDS, fails=WORLD_FAILS, sizes=sizes_text(sizes, visual_members)),
        extra=lambda r: {"built-in worlds": builtin_verdict(worlds, r["id"])},
    )
    rows = curve_rows(worlds, members, slices)
    ctx.table(
        "error_curves_over_worlds",
        "Error curves and error points inside and outside the landmarks' hull over the worlds",
        rows,
        source="Figs 4.3, 4.4, 4.10a, 5.7a",
        note=f"Per-point vector maps on a {sizes['map_spacing']:g} cm grid; median and 5-95 % band over the "
        f"{members} members of each family; built-in world: its value under the run's seed, with the range "
        f"over the {slices} slices' seeds.",
    )
    ctx.figure(
        "error_curves_over_worlds.png",
        curves_figure(rows),
        "Mean angular error by distance from home over the members (median line, 5-95 % band) beside the built-in "
        "world (dashed), env1: DELV against image matching (claim 7) and DELV with compass against ACV and ALV "
        "(claim 19).",
    )
    if not sizes["preview"]:
        rows = distribution_rows(worlds, members, visual_members, slices)
        ctx.table(
            "visual_compass_over_worlds",
            "The visual compass over the worlds: catchments, mean errors and heading errors",
            rows,
            source="Figs 5.11-5.12, §5.4",
            note=f"Grid {sizes['spacing']:g} cm; catchments over the {visual_members} members of the first seed "
            f"slice, mean and heading errors over all {members}; physical: the same trials restated under the "
            "physical rules (catchment_physical_pct). Built-in world: our named world on the same grid, with the "
            "range over the slices' seeds.",
        )
        ctx.figure(
            "visual_compass_over_worlds.png",
            visual_figure(worlds, visual_members),
            "Catchment with the visual compass per member (dots) and its median (bar), per world family and "
            "background (default rules); crosses: the built-in world on the same grid.",
        )


def sizes_text(sizes: dict, visual_members: int) -> str:
    """The run's sizes in words, for the claims table's note."""
    if sizes["preview"]:
        return (
            f"A preview: {sizes['members']} members per family, per-point maps of the landmark methods on a "
            f"{sizes['map_spacing']:g} cm grid, DELV's quantization levels on env1's members and DELV in "
            f"{sizes['members']} random layouts of 3, 4 and 5 landmarks; the visual compass and image matching are "
            "the full run's."
        )
    return (
        f"{sizes['members']} members per family in {sizes['slices']} seed slices; per-point maps on a "
        f"{sizes['map_spacing']:g} cm grid; the compasses on a {sizes['spacing']:g} cm grid, the visual compass's "
        f"catchments (claims 31, 33) over the first {visual_members} members. Claim 11: DELV on env1's members "
        f"with Q = 1-5 levels (continuous: its per-point map); claims 5, 6: DELV and image matching in "
        f"{sizes['members']} seeded random layouts of 3, 4 and 5 landmarks, member i's nested (one seed: the 3 "
        "landmarks are the first of its 4, the 4 of its 5, so only the number changes); built-in: the "
        "`landmark_number` study's three layouts (separate seeds: claim 6 cannot tell)."
    )


__all__ = ["CLAIMS", "TITLE", "VISUAL_CLAIMS", "run"]
