"""Ensemble ranges: how each claim's share of worlds changes when the families' distance and radius ranges are
narrowed or widened by a third (SPEC §8; beyond the thesis; docs/reproduce.md "Ensembles").

The families' ranges (docs/model.md §6.1) are our reading of the thesis's words, so a verdict over worlds is
only as firm as the ranges. Here the claims that the `ensembles` study's default sweep decides on env1-3 (claims
1, 17, 18, 21-23, 25-27 and 34) are judged again on members of env1-3 with the distance and radius ranges scaled
about their centres by 2/3 and 4/3 (`Family.scaled`), and, like for like, at factor 1 on the same member
indices, grid, seeds and compiled program: one catchment sweep holds every factor's members (`{ensemble = ...,
factor = F}` tables, docs/sweeps.md). Member i of every factor comes from the same key, so the three samples are
paired. Per claim: the share of members where it holds at each factor with its Wilson interval and verdict, the
paired sign test against the default, and whether the verdict changes (`verdict_change_lines`: one line per
claim, for the report).
"""

from __future__ import annotations

import math
import re

import numpy as np

from delvjax.envs import family, member_layouts, world_properties
from delvjax.plots import subplots
from delvjax.sweeps import parse_sweep, run_sweep

from .. import thesis
from ..claims import CHECKS, WORLD_FAILS, WORLD_HOLDS, Missing, world_verdict
from ..claims._common import HOLDS as HOLDS_TEXT
from ._ensemble_stats import claim_rows
from .ensembles import EVERY_METHOD, LANES, PREVIEW_SPACING, SPACING, Group, member_numbers, shared_cells, skipped_cells

TITLE = "Ensemble ranges: each claim over worlds with the families' ranges narrowed or widened by a third"
COST = 120  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
# (measured: alone 168.5 CPU-s cold; in a full run a third of its cells are read from `ensembles`' shared cells)
FACTORS = (2 / 3, 1.0, 4 / 3)  # SPEC §8: "narrowed or widened by a third"; 1: the default ranges, like for like
FACTOR_NAMES = {2 / 3: "narrowed ×2/3", 1.0: "default ×1", 4 / 3: "widened ×4/3"}
ENVS = ("env1", "env2", "env3")  # no claim of the ensembles reads ring4's numbers
# One program: env1-3 at the three factors, every method, k = 0..2 (the `ensembles` study's default sweep). The
# rings (claims 24, 28, 29 read ring3, 5 and 6 beside env1-3) would add two programs and, with 11 members, 230 s of
# CPU (measured): left out.
GROUP = Group(ENVS, EVERY_METHOD, 2)
MEMBERS = 22  # per family and factor: Wilson 95 % half-width <= 19.3 points (at 50 %; 15.6 at 18 or 82 %; 7.4 at 0 %)
SLICES = 2  # slices of 11, slice j under the run's seed + j: factor 1's members are the `ensembles` study's first 22
STEPS = 2 * SLICES  # per slice: the scaled factors' sweep, then factor 1's (read from `ensembles`' cells if run)
# factor 1's cells last: in a full run the `ensembles` study (started first) has finished them (`shared_cells`)
ORDER = ((FACTORS[0], FACTORS[2]), (FACTORS[1],))
QUICK_MEMBERS = 1  # the preview (--quick, the test suite's tiny run): one member per family and factor, a 200 cm grid
# the claims of the `ensembles` study's default-setting sweeps that read env1-3 only: 1, 17, 18, 21-23, 25-27, 34
CLAIMS = (
    "delv_nocompass_catchment_all_envs",
    "compass_slightly_smaller_error",
    "compass_catchment_env2_similar_env3_better",
    "matching_tolerates_unequal_landmark_numbers",
    "occlusion_increases_errors",
    "acv_error_grows_faster_than_delv",
    "acv_larger_catchment_small_occlusion",
    "occlusion_catchment_both_severely_decrease",
    "acv_catchment_shrinks_faster",
    "delv_acv_similar_without_occlusion",
)


def plan(ctx) -> tuple[int, float, int]:
    """(members, spacing, slices) of this run: the full study on the ensembles' grid, or under --quick or a grid
    coarser than it a preview (QUICK_MEMBERS, one slice, PREVIEW_SPACING)."""
    if ctx.config.quick or ctx.config.spacing > SPACING:
        return QUICK_MEMBERS, max(ctx.config.spacing, PREVIEW_SPACING), 1
    return MEMBERS, SPACING, SLICES


def factor_tag(factor: float) -> str:
    """The part a factor adds to a member's family name (`ensemble_envs`): "" at 1, "x0.666667" at 2/3."""
    return "" if factor == 1.0 else f"x{factor:g}"


def range_texts(group: Group, members: int, spacing: float, seed: int, slices: int, factors=FACTORS) -> list[str]:
    """The catchment sweep files of one group: every factor's members of every family of the group in one env
    axis (one program), cut into `slices` slices, slice j under the run's seed + j like `ensembles.sweep_texts`
    (so factor 1's members are the ensembles study's first ones); layouts from the run's seed. No built-in worlds."""
    quoted = lambda names: "[" + ", ".join(f'"{n}"' for n in names) + "]"  # noqa: E731
    size = -(-members // slices)
    texts = []
    for j in range(slices):  # a handful of sweep calls of one program: input preparation
        first, count = j * size, min(size, members - j * size)
        if count <= 0:
            continue
        envs = [
            f'{{ensemble = "{f}", members = {count}, first = {first}, seed = {seed}, factor = {x!r}}}'
            for x in factors
            for f in group.families
        ]
        texts.append(
            '[sweep]\nkind = "catchment"\nmetrics = ["catchment_pct", "gt45_pct", "gt90_pct", "mean_error_deg"]\n'
            f"[axes]\nenv = [{', '.join(envs)}]\nmethod = {quoted(group.methods)}\n"
            f"occlude = {list(range(group.k_max + 1))}\nspacing = [{spacing}]\n"
            f"seed = {[seed + j + s for s in group.seeds]}\ncollisions = {quoted([group.collisions])}\n"
            f"bearing_noise_deg = [{group.bearing_noise_deg}]\n"
        )
    return texts


def numbers_by_factor(ds, group: Group, factors=FACTORS) -> dict[float, dict[str, dict]]:
    """{factor: {member label: {claims key: value}}} of one sweep: each factor's members relabelled as the default
    family's members by index (`env1x0.666667-s3-m3` -> `env1-m3`), so the claims' checks read them under their
    own keys (`ensembles.member_numbers`)."""
    labels = [str(v) for v in ds.env.values]
    out: dict[float, dict[str, dict]] = {}
    for factor in factors:
        tag = re.escape(factor_tag(factor))
        pattern = re.compile(rf"^({'|'.join(group.families)}){tag}(-s\d+)?(-m\d+)$")
        found = [(label, pattern.match(label)) for label in labels]
        mine = [(label, m.group(1) + m.group(3)) for label, m in found if m]  # by index, whatever the layouts' seed
        if not mine:
            continue
        sub = ds.sel({"env": [a for a, _ in mine]}).assign_coords(env=[b for _, b in mine])
        out[factor] = member_numbers(sub, group)
    return out


def factor_layouts(families, members: int, seed: int, factor: float) -> dict[str, np.ndarray]:
    """{family: (members, n, 3)} the layouts of the members at `factor` (for their world properties)."""
    return {
        f: member_layouts(family(f) if factor == 1.0 else family(f).scaled(factor), members, seed) for f in families
    }


def member_holds(worlds: dict, members: int, ids=CLAIMS) -> dict[str, np.ndarray]:
    """{claim id: (members,) bool}: whether the claim's check says "holds" in member i (the i-th world of every
    family), as `claim_rows` counts it; a claim whose numbers some member lacks is left out."""
    families = sorted({label.rsplit("-m", 1)[0] for label in worlds if "-m" in label})
    out = {}
    for cid in ids:
        held = []
        for i in range(members):  # plain checks on recorded numbers (no array program)
            flat = {k: v for f in families for k, v in worlds.get(f"{f}-m{i}", {}).items() if v is not None}

            def get(key, flat=flat):
                if key not in flat:
                    raise Missing(key)
                return flat[key]

            try:
                held.append(CHECKS[cid](get)[1] == HOLDS_TEXT)
            except Missing:
                break
            except (TypeError, ValueError, IndexError, ZeroDivisionError):
                held.append(False)
        if len(held) == members:
            out[cid] = np.array(held, bool)
    return out


def sign_test(gained: int, lost: int) -> float:
    """Two-sided exact sign test (McNemar's exact test) of paired members: the probability of a split of the
    `gained + lost` members whose verdict differs at least this uneven if either way were equally likely."""
    n = gained + lost
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, i) for i in range(min(gained, lost) + 1)) / 2**n
    return min(1.0, 2 * tail)


def paired(held: dict[float, dict[str, np.ndarray]], cid: str) -> dict[float, tuple[int, int, float]]:
    """{factor: (members holding only there, members holding only at 1, sign-test p)} for 2/3 and 4/3."""
    base = held[1.0][cid]
    out = {}
    for f in (FACTORS[0], FACTORS[2]):
        gained, lost = int(np.sum(held[f][cid] & ~base)), int(np.sum(~held[f][cid] & base))
        out[f] = (gained, lost, sign_test(gained, lost))
    return out


def interval(row: dict) -> tuple[float, float]:
    lo, hi = (float(v) for v in row["95 % interval"].split("-"))
    return lo, hi


def change_text(verdicts: list[str], p_values: list[float]) -> str:
    """The table's "verdict changes" cell: "no", or the verdict at the factor that moves it with the paired sign
    test's p against the default (p >= 0.05: within the sampling error of these members)."""
    if len(set(verdicts)) == 1:
        return "no"
    parts = [
        f"{name}: {verdicts[i]} (paired p = {p:.2g})"
        for i, name, p in ((0, "narrowed", p_values[0]), (2, "widened", p_values[1]))
        if verdicts[i] != verdicts[1]
    ]
    return "yes: " + "; ".join(parts)


def verdict_change_lines(flat: dict) -> list[str]:
    """One line per claim whose verdict over worlds differs between the ranges narrowed or widened by a third and
    the default (SPEC §8), from the recorded `ensemble_ranges:<id>` = [holds % at 2/3, 1, 4/3] (with
    `:cannot_tell`, `:partly`, `:interval` and `:paired_p` where recorded); [] when the study was not run or no verdict
    changes."""
    lines = []
    for number, claim in enumerate(thesis.CLAIMS, 1):
        key = f"ensemble_ranges:{claim['id']}"
        held = flat.get(key)
        if not isinstance(held, list) or len(held) != len(FACTORS):
            continue
        ceiling = flat.get(f"{key}:cannot_tell") or [0.0] * len(FACTORS)
        partly = flat.get(f"{key}:partly") or [0.0] * len(FACTORS)
        verdicts = [world_verdict(p, c, q) for p, c, q in zip(held, ceiling, partly)]
        if len(set(verdicts)) == 1:
            continue
        bounds = flat.get(f"{key}:interval")
        where = (
            [f" [{bounds[2 * i]:.0f}-{bounds[2 * i + 1]:.0f} %]" for i in range(len(FACTORS))]
            if isinstance(bounds, list) and len(bounds) == 2 * len(FACTORS)
            else [""] * len(FACTORS)
        )
        p = flat.get(f"{key}:paired_p")
        test = [f", paired p = {v:.2g}" for v in p] if isinstance(p, list) and len(p) == 2 else ["", ""]
        lines.append(
            f"Claim {number} ({claim['id']}): {verdicts[1]} at the default ranges ({held[1]:.0f} % of worlds{where[1]}); "
            f"narrowed by a third {verdicts[0]} ({held[0]:.0f} %{where[0]}{test[0]}), widened by a third {verdicts[2]} "
            f"({held[2]:.0f} %{where[2]}{test[1]})."
        )
    return lines


def claim_table(by_factor: dict[float, dict[str, dict]], held: dict[float, dict[str, np.ndarray]]) -> list[dict]:
    """One row per claim judged at every factor: share, interval and verdict per factor, the paired comparison of
    each scaled factor with the default, and whether the verdict changes."""
    rows = []
    ids = [c["id"] for c in thesis.CLAIMS if all(c["id"] in by_factor[f] and c["id"] in held[f] for f in FACTORS)]
    for cid in ids:
        per = [by_factor[f][cid] for f in FACTORS]
        row = {"#": per[1]["#"], "id": cid, "section": per[1]["section"], "members": per[1]["members"]}
        for f, r in zip(FACTORS, per):
            name = FACTOR_NAMES[f]
            row[f"{name}: holds %"] = r["holds %"]
            row[f"{name}: 95 % interval"] = r["95 % interval"]
            row[f"{name}: partly %"] = r.get("partly %", 0.0)
            row[f"{name}: cannot tell %"] = r["cannot tell %"]
            row[f"{name}: verdict"] = r["verdict over worlds"]
        tests = paired(held, cid)
        for f, (gained, lost, p) in tests.items():
            row[f"{FACTOR_NAMES[f]} vs ×1: members gained / lost"] = f"{gained} / {lost}"
            row[f"{FACTOR_NAMES[f]} vs ×1: sign test p"] = p
        row["verdict changes"] = change_text([r["verdict over worlds"] for r in per], [t[2] for t in tests.values()])
        rows.append(row)
    return rows


def range_rows(layouts: dict[float, dict[str, np.ndarray]]) -> list[dict]:
    """Per family and factor: the scaled ranges and the members' medians of the world properties that move."""
    rows = []
    for factor, by_family in layouts.items():
        for f, lay in by_family.items():
            fam = family(f) if factor == 1.0 else family(f).scaled(factor)
            props = world_properties(lay, fam.home)
            rows.append(
                {
                    "family": f,
                    "factor": FACTOR_NAMES[factor],
                    "distance cm": f"{fam.distance[0]:.1f}-{fam.distance[1]:.1f}",
                    "radius cm": f"{fam.radius[0]:.2f}-{fam.radius[1]:.2f}",
                    "members": len(lay),
                    **{f"median {k}": float(np.median(props[k])) for k in ("nearest_cm", "farthest_cm", "centroid_cm")},
                    "median radius_ratio": float(np.median(props["radius_ratio"])),
                }
            )
    return rows


def run(ctx) -> None:
    members, spacing, slices = plan(ctx)
    seed = ctx.config.seed
    worlds: dict[float, dict[str, dict]] = {f: {} for f in FACTORS}
    lanes = min(LANES, ctx.config.lanes) if members == MEMBERS else ctx.config.lanes  # as `ensembles`
    texts = [(fs, t) for fs in ORDER for t in range_texts(GROUP, members, spacing, seed, slices, fs)]
    for j, (factors, text) in enumerate(texts):  # one program, 2 x `slices` calls
        spec = parse_sweep(text, "ensemble_ranges")  # the cells no claim reads are skipped, as in `ensembles`
        ds = run_sweep(spec, lanes=lanes, out=shared_cells(), skip=skipped_cells())
        for factor, found in numbers_by_factor(ds, GROUP, factors).items():
            for label, nums in found.items():
                worlds[factor].setdefault(label, {}).update(nums)
        ctx.step(f"sweep {j + 1} of {len(texts)} (factor {', '.join(f'{f:.3g}' for f in factors)})")
    for _ in range(STEPS - len(texts)):  # a preview: the progress bar still ends at its total
        ctx.step("one slice only in a preview")
    layouts = {f: factor_layouts(ENVS, members, seed, f) for f in FACTORS}
    by_factor = {f: {r["id"]: r for r in claim_rows(worlds[f], members, layouts[f], ids=set(CLAIMS))} for f in FACTORS}
    held = {f: member_holds(worlds[f], members) for f in FACTORS}
    rows = claim_table(by_factor, held)
    ctx.number("ensemble_ranges:members", members)
    ctx.number("ensemble_ranges:spacing", spacing)
    for r in rows:  # read by verdict_change_lines (the report)
        key = f"ensemble_ranges:{r['id']}"
        ctx.number(key, [r[f"{FACTOR_NAMES[f]}: holds %"] for f in FACTORS])
        ctx.number(f"{key}:cannot_tell", [r[f"{FACTOR_NAMES[f]}: cannot tell %"] for f in FACTORS])
        ctx.number(f"{key}:partly", [r[f"{FACTOR_NAMES[f]}: partly %"] for f in FACTORS])
        ctx.number(f"{key}:interval", [v for f in FACTORS for v in interval(by_factor[f][r["id"]])])
        ctx.number(f"{key}:paired_p", [r[f"{FACTOR_NAMES[f]} vs ×1: sign test p"] for f in (FACTORS[0], FACTORS[2])])
    changed = sum(r["verdict changes"] != "no" for r in rows)
    ctx.table(
        "claims_over_ranges",
        "Claims over the worlds with the families' ranges narrowed or widened by a third",
        rows,
        source="studies/claims; SPEC §8",
        note=f"{members} members per family (env1-3) and factor, grid spacing {spacing:g} cm, default rules, members in "
        f"{slices} seed slices; member i of every factor comes from the same key (paired samples). ×2/3 and ×4/3 "
        "scale every family's distance and radius ranges about their centres (docs/model.md §6.1). holds: in at least "
        f"{WORLD_HOLDS:g} % of members; fails: it holds or partly holds in at most {WORLD_FAILS:g} %; partly: it holds "
        f"or partly holds in at least {WORLD_HOLDS:g} %; else depends on the world. gained / lost: "
        "members where the claim holds at that factor only / at ×1 only; sign test p: the two-sided exact test of "
        f"that split (McNemar's). {changed} of {len(rows)} verdicts change. Claims 24, 28 and 29 also read rings and "
        "are not run here (docs/reproduce.md).",
    )
    ctx.table(
        "ranges_by_factor",
        "The families' ranges at each factor and what they do to the members",
        range_rows(layouts),
        source="docs/model.md §6.1",
        note="Medians over the members of the world properties of docs/model.md §6.1 (cm from home).",
    )
    ctx.json(
        "ensemble_ranges.json",
        {
            "settings": {"members": members, "spacing": spacing, "seed": seed, "slices": slices},
            "factors": list(FACTORS),
            "layouts": {f"{f:g}": {k: v.tolist() for k, v in lay.items()} for f, lay in layouts.items()},
            "numbers": {f"{f:g}": w for f, w in worlds.items()},
            "holds": {f"{f:g}": {k: v.tolist() for k, v in h.items()} for f, h in held.items()},
            "claims": rows,
        },
    )
    if rows:
        ctx.figure(
            "claims_over_ranges.png",
            ranges_figure(rows),
            "Each claim's share of worlds where it holds (95 % Wilson interval) with the families' distance and "
            f"radius ranges narrowed by a third (left marker), as they are (middle) and widened by a third (right); "
            f"dashed: the {WORLD_FAILS:g} and {WORLD_HOLDS:g} % verdict lines.",
        )


def ranges_figure(rows: list[dict]):
    """Per claim: holds % with its interval at each factor, the verdict lines across."""
    fig, ax = subplots(1, 1, figsize=(max(5.0, 0.55 * len(rows) + 1.5), 3.4))
    styles = (("tab:blue", "v"), ("black", "o"), ("tab:red", "^"))
    for (factor, (colour, marker)), shift in zip(zip(FACTORS, styles), (-0.22, 0.0, 0.22)):
        name = FACTOR_NAMES[factor]
        x = np.arange(len(rows)) + shift
        y = np.array([r[f"{name}: holds %"] for r in rows])
        bounds = np.array([[float(v) for v in r[f"{name}: 95 % interval"].split("-")] for r in rows])
        ax.errorbar(x, y, yerr=[y - bounds[:, 0], bounds[:, 1] - y], fmt=marker, color=colour, ms=4, lw=1, label=name)
    for level in (WORLD_FAILS, WORLD_HOLDS):
        ax.axhline(level, color="0.6", ls="--", lw=0.8)
    ax.set_xticks(range(len(rows)), [str(r["#"]) for r in rows])
    ax.set_xlabel("claim (number in the claims table)")
    ax.set_ylabel("members where the claim holds (%)")
    ax.set_ylim(-3, 103)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    return fig


__all__ = ["FACTORS", "GROUP", "TITLE", "run", "verdict_change_lines"]
