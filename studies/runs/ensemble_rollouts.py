"""World ensembles of the rollout claims: step distance, success rates and quantization over every world the
thesis's words allow (beyond the thesis; docs/reproduce.md "Ensembles: step distance, success rates,
quantization").

The `ensembles` study judges the claims its catchment sweeps make; this one judges those resting on the step
distance d (claims 3, 4), on success rates by release distance (8, 9, 20), on the distance levels (12) and on
the layouts of Fig 4.14 at three levels (13). Each is a handful of sweeps (`_ensemble_rollouts_keys`): env1's
members for d = 20..150 cm and the levels as catchments, success rates of DELV (levels, rule sets), image
matching and the compass methods, and the vector maps of env2, ring3, ring6 and `edge4` (home slightly outside
the hull, a family of its own) at three levels. MEMBERS members per family in SEED_SLICES slices, slice j under
the run's seed + j (a rollout number is never from one seed); each member's numbers take the keys the point runs
record, and a claim's check runs on every member (`_ensemble_stats.claim_rows`).
"""

from __future__ import annotations

import numpy as np

from delvjax.envs import ensemble_envs
from delvjax.sweeps import run_sweep

from ..claims import WORLD_FAILS, WORLD_HOLDS
from ._ensemble_rollouts_keys import LAYOUTS, SWEEPS, edge_layouts, sweep_numbers, sweep_specs
from ._ensemble_rollouts_report import (
    number_rows,
    step_figure,
    step_rows,
    success_curves,
    success_figure,
    thesis_rows,
)
from ._ensemble_stats import BAND, claim_rows
from ._settings_design import MASK_ROWS
from .ensembles import (
    CLAIMS_TABLE_NOTE,
    EVERY_METHOD,
    LANES,
    MEMBERS,
    PREVIEW_SPACING,
    QUICK_MEMBERS,
    SEED_SLICES,
    SPACING,
    record_claims,
)

TITLE = "World ensembles: step distance, success rates and quantization over the worlds (beyond the thesis)"
COST = 240  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = len(SWEEPS)
TRIALS = 20  # trials per release distance and member (the point run: 100); see docs/reproduce.md
PREVIEW_TRIALS = 4
PREVIEW_SWEEPS = ("steps",)  # one program (about 15 s cold): claims 3 and 4
CLAIM_IDS = (
    "step_distance_rarely_matters",
    "small_step_slightly_better",
    "delv_success_over_90",
    "delv_beats_warping_success",
    "fewer_levels_more_failures_three_suffice",
    "surrounding_landmarks_lower_error",
    "delv_compass_success_near_far",
)


def plan(ctx) -> tuple[tuple[str, ...], int, float, int, int]:
    """(sweeps, members per family, spacing, trials per release distance, seed slices) of this run: the full
    ensembles, or under --quick or a grid coarser than SPACING a preview (QUICK_MEMBERS members, one slice)."""
    if ctx.config.quick or ctx.config.spacing > SPACING:
        trials = min(PREVIEW_TRIALS, ctx.config.trials)
        return PREVIEW_SWEEPS, QUICK_MEMBERS, max(ctx.config.spacing, PREVIEW_SPACING), trials, 1
    return SWEEPS, MEMBERS, SPACING, min(TRIALS, ctx.config.trials), SEED_SLICES


def sharing(name: str, lanes: int, full: bool = True) -> dict:
    """`run_sweep`'s arguments of a sweep: DELV's catchments (d, levels) in the `ensembles` study's compiled program
    (its methods, masks and lanes: a full run's LANES, a preview's the run's), the landmark methods' success rates
    in one program; the numbers are the same (a cell's trials do not depend on the program's other methods)."""
    if name in ("steps", "levels"):
        return {"lanes": min(LANES, lanes) if full else lanes, "method_set": EVERY_METHOD, "mask_rows": MASK_ROWS}
    if name in ("levels_success", "rules_success", "compass_success"):
        return {"lanes": lanes, "method_set": EVERY_METHOD}
    return {"lanes": lanes}


def run_members(sweeps, members: int, spacing: float, trials: int, slices: int, seed: int, lanes: int, step=None):
    """{world label: {claims key: value}} of every sweep over every seed slice (slice j: members j * size ..,
    under seed + j; the built-in worlds in every slice, labelled `<world>@j` beyond the first)."""
    size = -(-members // slices)
    worlds: dict[str, dict] = {}
    for name in sweeps:  # a handful of sweep calls per program: input preparation
        for j in range(slices):
            first, count = j * size, min(size, members - j * size)
            for _, spec in sweep_specs(count, first, seed, j, spacing, trials, (name,), members):
                ds = run_sweep(spec, **sharing(name, lanes, slices > 1))
                for label, nums in sweep_numbers(name, ds, j).items():
                    worlds.setdefault(label, {}).update(nums)
        if step is not None:
            step(name)
    return worlds


def run(ctx) -> None:
    sweeps, members, spacing, trials, slices = plan(ctx)
    seed = ctx.config.seed
    worlds = run_members(sweeps, members, spacing, trials, slices, seed, ctx.config.lanes, ctx.step)
    for _ in range(STEPS - len(sweeps)):  # a preview: the progress bar still ends at its total
        ctx.step("the other sweeps: full run only")
    layouts = {
        fam: np.array(
            [[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in ensemble_envs(fam, members, seed)]
        )
        for fam in ("env1", *LAYOUTS[:-1])
    }
    layouts["edge4"] = edge_layouts(members, seed)
    ctx.number("ensemble_rollouts:members", members)
    ctx.number("ensemble_rollouts:spacing", spacing)
    ctx.number("ensemble_rollouts:trials", trials)
    ctx.json(
        "ensemble_rollouts_worlds.json",
        {
            "settings": {"members": members, "spacing": spacing, "trials": trials, "seed": seed, "slices": slices},
            "sweeps": list(sweeps),
            "layouts": {fam: lay.tolist() for fam, lay in layouts.items()},
            "numbers": worlds,
        },
    )
    sizes = (
        f"{members} worlds per family in {slices} seed slice{'s' * (slices > 1)}, grid spacing {spacing:g} cm, "
        f"{trials} trials per release distance and member"
    )
    rows = number_rows(worlds, members)
    ctx.table(
        "rollout_numbers_over_worlds",
        "Step distance, success rates and levels over the worlds: median and band over the members",
        rows,
        source="Figs 4.6-4.7, 4.10b, 4.12-4.14, 5.7b",
        note=f"{sizes}; band: the {BAND[0]:g}-{BAND[1]:g} % percentiles over the members; built-in world: the "
        "range over the seeds of the slices. Success: overall over the release distances 50-450 cm.",
    )
    bound = thesis_rows(worlds, members)
    if bound:
        ctx.table(
            "thesis_numbers_over_worlds_rollouts",
            "The thesis's printed success bound beside our distribution over the worlds",
            bound,
            source="§4.2, Fig 4.10b",
            note="The thesis prints no success numbers, only the bound '> 90 %' for DELV (line 600). Ours: each "
            f"member's lowest success rate over the release distances ({trials} trials each); the thesis "
            "percentile is the share of members below 90 (ties half).",
        )
    steps = step_rows(worlds, members)
    ctx.figure(
        "step_distance_over_worlds.png",
        step_figure(steps),
        "DELV without compass by step distance d over the env1 worlds (Figs 4.6-4.7): the median over the members "
        f"(line), their {BAND[0]:g}-{BAND[1]:g} % band (bar) and the built-in world (x, first seed); {sizes}.",
    )
    ctx.csv("step_distance_over_worlds.csv", rows=steps)
    success = success_curves(worlds, members)
    if success:
        ctx.figure(
            "success_over_worlds.png",
            success_figure(success),
            f"Success rate by release distance over the worlds (Figs 4.10b, 4.13b, 5.7b): the median over the "
            f"members (line; the lines a few cm apart, so that equal medians stay visible) and their "
            f"{BAND[0]:g}-{BAND[1]:g} % band (shaded); {sizes}.",
        )
        ctx.csv("success_over_worlds.csv", rows=success)
    record_claims(
        ctx,
        claim_rows(worlds, members, layouts, ids=set(CLAIM_IDS)),
        "claims_over_worlds_rollouts",
        "Claims of step distance, success rates and levels over the worlds: the share of members in which each "
        "claim's check holds",
        CLAIMS_TABLE_NOTE.format(holds=WORLD_HOLDS, fails=WORLD_FAILS)
        + f" {sizes}. Member i: the i-th world of every family (claim 13: env2, ring3, ring6 against edge4, home "
        "slightly outside the hull, docs/reproduce.md).",
        figure="claims_decided_by_rollouts.png",
    )
