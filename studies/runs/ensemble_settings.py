"""Which unstated settings the thesis's numbers imply: a joint estimate over the settings and rule sets,
scored on the world ensembles (beyond the thesis; docs/reproduce.md "Which settings the thesis's numbers
imply").

The thesis gives no bearing noise, odometry noise, home radius or rule for landmark contacts. Here they
vary jointly (`_settings_design`: the full factorial of the sensing and homing settings, 24 runs, each under
both rule sets from the same trials: 48 combinations), each combination on the same worlds of env1, env2 and
env3 (docs/model.md §6.1), member i under the run's seed + i. Every combination is scored by
how near our distribution over the members comes to each thesis number of Figs 4.5, 5.5, 5.10 and Tables
5.1, 5.3 on those worlds (`_settings_estimate`: the mean CRPS, in points), so worlds and seeds are averaged,
not one world. The members are resampled with replacement to give each score its band, how often each
combination and each setting value is best (a setting's value scored by its best combination: its profile),
the combinations not distinguishable from the best, and per setting whether the thesis's numbers identify it.
"""

from __future__ import annotations

import time

import numpy as np

from ._settings_design import FAMILIES, PAIRS, SETTINGS, combination, design, numbers, rollouts, targets
from ._settings_estimate import (
    BAND,
    GAP,
    SHARE,
    combinations,
    crps,
    identify,
    percentile_offsets,
    resample_weights,
    scores,
    sentence,
)
from ._settings_tables import design_rows, identified_rows, settings_figure, unreached_rows, value_rows

TITLE = (
    "Which unstated settings the thesis's numbers imply: a joint estimate over the world ensembles (beyond the thesis)"
)
COST = 200  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
RUNS = 24  # runs of the full factorial (each under both rule sets)
STEPS = RUNS + 1
# a full run: members per family, grid spacing (cm: 8 x 8), resamples, runs (None: every one), rollout lanes
# (no number depends on them: 128 lanes run these cells of 50-350 trials 15 % faster than 256 on 2 cores)
FULL = {"members": 8, "spacing": 125.0, "draws": 2000, "runs": None, "lanes": 128}
# --quick and the test suite's tiny run: 2 members on a 200 cm grid (the ensembles' preview's: the same compiled
# program), four runs in which every setting takes each of its values (value indices of SETTINGS but the rules)
PREVIEW = {
    "members": 2,
    "spacing": 200.0,
    "draws": 200,
    "runs": [(0, 0, 0), (1, 1, 1), (2, 2, 0), (3, 0, 1)],
    "lanes": None,
}
SPACING = 125.0


def plan(ctx) -> dict:
    """The run's sizes: FULL, or under --quick or a grid coarser than SPACING (the test suite's) PREVIEW."""
    preview = ctx.config.quick or ctx.config.spacing > SPACING
    return dict(PREVIEW if preview else FULL, preview=preview)


def run(ctx) -> None:
    sizes = plan(ctx)
    seed, members = ctx.config.seed, sizes["members"]
    levels = design(sizes["runs"])  # (C, 5): every combination, the defaults first
    runs = levels[:: len(SETTINGS["rules"][1])]
    t0, c0 = time.perf_counter(), time.process_time()
    values = rollouts(
        runs,
        members,
        sizes["spacing"],
        seed,
        sizes["lanes"] or ctx.config.lanes,
        tick=lambda n: ctx.step(f"row {n} of {len(runs)}"),
    )
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    for _ in range(RUNS - len(runs)):  # a preview: the progress bar still ends at its total
        ctx.step("the other rows: full run only")
    items = targets()
    x = numbers(values, items)  # (C, N, M)
    t = np.array([r[5] for r in items], float)
    s = scores(x, t, resample_weights(members, sizes["draws"], seed))  # (1 + draws, C)
    comb = combinations(s)
    found = {name: identify(s, levels[:, j], len(SETTINGS[name][1]), members) for j, name in enumerate(SETTINGS)}
    per_number = crps(x, t)  # (C, N)
    offsets = percentile_offsets(x, t)
    ctx.step("the estimate")

    labels = {n: SETTINGS[n][0] for n in SETTINGS}
    shown = {n: [fmt_value(v, SETTINGS[n][2]) for v in SETTINGS[n][1]] for n in SETTINGS}
    text = sentence(found, labels, shown, members)
    best = comb["best"]
    ctx.number("ensemble_settings:members", members)
    ctx.number("ensemble_settings:combinations", len(levels))
    ctx.number("ensemble_settings:spacing", sizes["spacing"])
    ctx.number("ensemble_settings:thesis_numbers", len(items))
    ctx.number("ensemble_settings:resamples", sizes["draws"])
    ctx.number("ensemble_settings:best", [best, comb["score"][best], comb["lo"][best], comb["hi"][best]])
    ctx.number("ensemble_settings:score:default", float(comb["score"][0]))
    ctx.number("ensemble_settings:score:best", float(comb["score"][best]))
    ctx.number("ensemble_settings:indistinct", int(comb["indistinct"].sum()))
    ctx.number("ensemble_settings:identified", sum(f["identified"] for f in found.values()))
    for name, f in found.items():
        ctx.number(f"ensemble_settings:best:{name}", numeric(name, combination(levels[best])[name]))
        ctx.number(
            f"ensemble_settings:identified:{name}",
            [int(f["identified"]), numeric(name, SETTINGS[name][1][f["best"]]), float(f["share_best"][f["best"]])],
        )
    ctx.number("ensemble_settings:seconds", [seconds, cpu])  # the rollouts' wall and CPU seconds

    note = (
        f"{members} worlds per family ({', '.join(FAMILIES)}; docs/model.md §6.1), member i under the run's seed + i "
        f"and the same in every combination, grid spacing {sizes['spacing']:g} cm, {len(items)} thesis numbers "
        f"(Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3), {sizes['draws']} resamples of the members. Score: the mean over "
        "the thesis's numbers of the CRPS of our members' values against the thesis's (points; a single world's "
        "CRPS is |ours - thesis|, the old fit's objective); band: its 5-95 % over the resamples."
    )
    ctx.table(
        "settings_design",
        "Every combination of the unstated settings, scored against the thesis's numbers over the members",
        design_rows(levels, comb, per_number, offsets, items),
        source="Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3",
        note=note + f" Not distinguishable from the best: its gap to the best combination is not above 0 in "
        f"{100 - GAP:g} % of the resamples. Rows from the best; # is the combination's number (0: every default).",
    )
    ctx.table(
        "settings_identified",
        "Which unstated settings the thesis's numbers identify",
        identified_rows(found, shown),
        source="Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3",
        note=text,  # exactly the sentence: the report quotes it (delvjax/reproduce/_report.py `ensemble_more`)
    )
    ctx.table(
        "settings_values",
        "Each setting value's score over the combinations with it, with its resample band",
        value_rows(found, shown),
        source="Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3",
        note=f"A setting's score per value is the score of the best combination with that value, the others free "
        f"(its profile; in the full factorial every value meets the same combinations of the others). Identified: one "
        f"value is best in at least {SHARE:g} % of the resamples and every other value's gap to it is above 0 in "
        f"{100 - GAP:g} % of them (a two-sided 1 % test per setting). Score: the best combination's with the value. Gap bound: the {GAP:g}th percentile over the resamples of "
        "the value's score minus the best value's: a value whose bound is above 0 is excluded by the thesis's numbers.",
    )
    unreached = unreached_rows(x, items, levels)
    ctx.table(
        "settings_unreached",
        "Thesis numbers outside our band over the members under every combination of the settings",
        unreached,
        source="Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3",
        note=f"Band: the {BAND[0]:g}-{BAND[1]:g} % of the members' values. Nearest: the combination whose band comes "
        f"nearest the thesis's number. {len(unreached)} of {len(items)} thesis numbers: no unstated setting tried "
        "explains their gaps.",
    )
    ctx.number("ensemble_settings:unreached", len(unreached))
    ctx.figure(
        "settings_identified.png",
        settings_figure(found, labels, shown),
        "The mean CRPS (points) of the thesis's numbers under the best combination with each value of a setting (dot), "
        f"its {BAND[0]:g}-{BAND[1]:g} % band over the resamples of the members (bar); the best value in black, "
        "values its resamples do not exclude in grey, excluded ones in red (by the paired gap to the best value in "
        "each resample, which the bars' overlap does not show). Lower: our members' distribution nearer the thesis's "
        "numbers.",
    )
    ctx.json(
        "ensemble_settings.json",
        {
            "sizes": {k: v for k, v in sizes.items()},
            "settings": {n: list(SETTINGS[n][1]) for n in SETTINGS},
            "design": levels.tolist(),
            "thesis": [list(r) for r in items],
            "pairs": [list(p) for p in PAIRS],
            "numbers": x.tolist(),
            "sentence": text,
            "seconds": {"wall": seconds, "cpu": cpu},
        },
    )


def fmt_value(v, unit: str = "") -> str:
    """A setting value as the tables show it, with its unit."""
    return v if isinstance(v, str) else f"{v:g}{unit}"


def numeric(name: str, value) -> float:
    """A setting value as a number of the report: a named value (odometry noise, the rule set) as its index in
    SETTINGS (0: none / the default rules, 1: noisy / the physical rules), else the value."""
    return float(SETTINGS[name][1].index(value)) if isinstance(value, str) else float(value)
