"""World ensembles of claim 10: image matching's failures outside the landmarks' hull over every world the thesis's
words allow (beyond the thesis; docs/reproduce.md "Ensembles: failures outside the landmarks' hull").

The `image_matching` study finds, on the built-in env1, that predictive image matching fails from release points
outside the landmarks' convex hull far more often than from inside, and more often there than DELV (Fig 4.11,
claim 10). A catchment sweep sums each trial's outcome over the grid, so here the sweep's trials come back point
by point (`delvjax.sweeps.point_outcomes`): DELV and image matching ("warping", image_matching's settings, the
default rules) on MEMBERS members of the env1 family as one catchment sweep per seed slice, each member's counted
release points split by its own landmark hull (`_ensemble_maps.hull_inside`, one array operation over the
members). Each member's failure rates take the keys the point run records (`fail_inside_hull:env1:warping`, ...)
and claim 10's check runs on every member (`_ensemble_stats.claim_rows`); a member whose hull holds no counted
grid point cannot tell (the check's rule).
"""

from __future__ import annotations

import numpy as np

from delvjax.envs import ensemble_envs
from delvjax.plots import subplots
from delvjax.sweeps import parse_sweep, point_outcomes

from ..claims import WORLD_FAILS, WORLD_HOLDS
from ._common import LABEL
from ._ensemble_maps import hull_inside, member_label
from ._ensemble_stats import BAND, claim_rows
from .ensembles import CLAIMS_TABLE_NOTE, MEMBERS, PREVIEW_SPACING, QUICK_MEMBERS, SPACING, record_claims

TITLE = "World ensembles: image matching's failures outside the landmarks' hull over the worlds (beyond the thesis)"
COST = 45  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
SLICES = 2  # seed slices of a full run (slice j under the run's seed + j): 22 members per program call
METHODS = ("delv", "warping")
FAMILY = "env1"  # Fig 4.11's world; claim 10's check reads env1's keys
CLAIM_IDS = ("warping_fails_outside_hull",)
REGIONS = ("inside", "outside")
STEPS = SLICES


def plan(ctx) -> tuple[int, float, int]:
    """(members, grid spacing, seed slices) of this run: the full ensemble, or under --quick or a grid coarser than
    SPACING (the test suite's tiny run) a preview of QUICK_MEMBERS members on the PREVIEW_SPACING grid."""
    if ctx.config.quick or ctx.config.spacing > SPACING:
        return QUICK_MEMBERS, max(ctx.config.spacing, PREVIEW_SPACING), 1
    return MEMBERS, SPACING, SLICES


def sweep_text(count: int, first: int, seed: int, slice_: int, spacing: float) -> str:
    """The catchment sweep of one seed slice: `count` members from `first` (layouts from the run's seed, trials
    under seed + slice), the built-in env1 in the first slice; DELV and image matching, default rules."""
    envs = [f'{{ensemble = "{FAMILY}", members = {count}, first = {first}, seed = {seed}}}']
    envs += [f'"{FAMILY}"'] if slice_ == 0 else []
    methods = ", ".join(f'"{m}"' for m in METHODS)
    return (
        f'[sweep]\nkind = "catchment"\n[axes]\nenv = [{", ".join(envs)}]\nmethod = [{methods}]\n'
        f"spacing = [{spacing}]\nseed = [{seed + slice_}]\n"
    )


def hull_numbers(res: dict, envs: list[str]) -> dict[str, dict]:
    """{world label: {claims key: value}} of one slice's per-point outcomes (`point_outcomes` of `sweep_text`,
    axes env x method): per method the failed trials (%) among the counted release points inside and outside the
    world's landmark hull (NaN where a region holds none), their counts, and the catchment."""
    shape = res["successes"].shape
    w, m, p = shape[0], shape[1], shape[-1]
    ok, trials, counted = (np.asarray(res[k]).reshape(w, m, p) for k in ("successes", "trials", "counted"))
    slots = max(len(res["landmarks"][e]) for e in envs)
    centres = np.zeros((w, slots, 2))
    valid = np.zeros((w, slots), bool)
    for i, e in enumerate(envs):  # input preparation: a few landmarks per world
        lms = np.asarray(res["landmarks"][e])[:, :2]
        centres[i, : len(lms)], valid[i, : len(lms)] = lms, True
    hull = hull_inside(centres, valid, res["points"])  # (W, P)
    out: dict[str, dict] = {member_label(e): {} for e in envs}
    regions = {"inside": counted & hull[:, None, :], "outside": counted & ~hull[:, None, :]}
    for region, where in regions.items():
        n = where.sum(axis=-1)  # (W, M) counted points
        tried = (trials * where).sum(axis=-1)
        with np.errstate(invalid="ignore", divide="ignore"):
            fail = np.where(tried > 0, 100.0 * (1.0 - (ok * where).sum(axis=-1) / np.maximum(tried, 1)), np.nan)
        for i, e in enumerate(envs):
            for j, method in enumerate(METHODS):
                key = f"fail_{region}_hull:{FAMILY}:{method}"
                out[member_label(e)][key] = float(fail[i, j])
                out[member_label(e)][f"n:{key}"] = [int(n[i, j])]
    catch = 100.0 * (ok * counted).sum(axis=-1) / np.maximum((trials * counted).sum(axis=-1), 1)
    for i, e in enumerate(envs):
        for j, method in enumerate(METHODS):
            out[member_label(e)][f"catchment:{FAMILY}:{method}"] = float(catch[i, j])
    return out


def run_members(members: int, spacing: float, slices: int, seed: int, lanes: int, step=None) -> dict[str, dict]:
    """{world label: {claims key: value}} of every member (and the built-in env1) over the seed slices: one
    catchment sweep per slice, its trials point by point."""
    size = -(-members // slices)
    worlds: dict[str, dict] = {}
    for j in range(slices):  # a handful of sweep calls of the same programs: input preparation
        first, count = j * size, min(size, members - j * size)
        spec = parse_sweep(sweep_text(count, first, seed, j, spacing), "ensemble_hull")
        res = point_outcomes(spec, lanes=lanes, method_set=METHODS)  # one compiled program for both methods
        worlds.update(hull_numbers(res, list(spec.axes["env"])))
        if step is not None:
            step(f"seed slice {j + 1} of {slices}")
    return worlds


def band_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """Per method and region: the failure rate's median and band over the members, the built-in env1's, and how
    many members have no counted release point there."""
    rows = []
    for method in METHODS:
        for region in REGIONS:
            key = f"fail_{region}_hull:{FAMILY}:{method}"
            vals = np.array([worlds[f"{FAMILY}-m{i}"][key] for i in range(members)])
            counts = np.array([worlds[f"{FAMILY}-m{i}"][f"n:{key}"][0] for i in range(members)])
            known = vals[~np.isnan(vals)]
            lo, med, hi = np.percentile(known, [BAND[0], 50.0, BAND[1]]) if len(known) else (np.nan,) * 3
            rows.append(
                {
                    "method": LABEL[method],
                    "release points": f"{region} the hull",
                    "fail % median": float(med),
                    f"fail % {BAND[0]:g} %": float(lo),
                    f"fail % {BAND[1]:g} %": float(hi),
                    "built-in env1": worlds.get(FAMILY, {}).get(key, np.nan),
                    "members": members,
                    "members without a counted point": int((counts == 0).sum()),
                    "counted points per member (median)": float(np.median(counts)),
                }
            )
    return rows


def member_figure(worlds: dict[str, dict], members: int):
    """Per member: image matching's failures outside against inside the hull (left) and against DELV's outside
    (right), the claim's two margins (dashed: 10 points); the built-in env1 as a cross."""
    get = lambda label, key: worlds.get(label, {}).get(key, np.nan)  # noqa: E731
    labels = [f"{FAMILY}-m{i}" for i in range(members)]
    wo = np.array([get(w, f"fail_outside_hull:{FAMILY}:warping") for w in labels])
    fig, axes = subplots(1, 2, figsize=(8.0, 3.6))
    for ax, other, name in (
        (axes[0], f"fail_inside_hull:{FAMILY}:warping", "image matching, inside the hull"),
        (axes[1], f"fail_outside_hull:{FAMILY}:delv", "DELV, outside the hull"),
    ):
        x = np.array([get(w, other) for w in labels])
        ax.scatter(x, wo, s=12, color="tab:blue", label="members")
        ax.plot(get(FAMILY, other), get(FAMILY, f"fail_outside_hull:{FAMILY}:warping"), "x", color="tab:red", ms=8)
        ax.plot([0, 90], [10, 100], "--", color="0.5", lw=1)
        ax.set_xlim(-3, 103)
        ax.set_ylim(-3, 103)
        ax.set_xlabel(f"failed releases (%): {name}", fontsize=8)
        ax.set_ylabel("image matching's failed releases outside the hull (%)", fontsize=8)
    fig.tight_layout()
    return fig


def run(ctx) -> None:
    members, spacing, slices = plan(ctx)
    seed = ctx.config.seed
    worlds = run_members(members, spacing, slices, seed, ctx.config.lanes, ctx.step)
    for _ in range(STEPS - slices):  # a preview: the progress bar still ends at its total
        ctx.step("the other seed slice: full run only")
    layouts = {
        FAMILY: np.array(
            [[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in ensemble_envs(FAMILY, members, seed)]
        )
    }
    ctx.number("ensemble_hull:members", members)
    ctx.number("ensemble_hull:spacing", spacing)
    sizes = (
        f"{members} env1 worlds in {slices} seed slice{'s' * (slices > 1)}, grid spacing {spacing:g} cm, one "
        "release per counted grid point, default rules"
    )
    rows = band_rows(worlds, members)
    empty = max(r["members without a counted point"] for r in rows)
    ctx.number("ensemble_hull:members_without_inside_point", rows[0]["members without a counted point"])
    for r, (method, region) in zip(rows, ((m, g) for m in METHODS for g in REGIONS)):  # the grid check's inputs
        key = f"fail_{region}_hull:{FAMILY}:{method}"
        band = [r[f"fail % {BAND[0]:g} %"], r["fail % median"], r[f"fail % {BAND[1]:g} %"]]
        if np.isfinite(band).all() and np.isfinite(r["built-in env1"]):  # a region empty in every world: none
            ctx.number(f"ensemble_hull:band:{key}", band)
            ctx.number(f"ensemble_hull:builtin:{key}", r["built-in env1"])
    ctx.json(
        "ensemble_hull_worlds.json",
        {
            "settings": {"members": members, "spacing": spacing, "seed": seed, "slices": slices},
            "layouts": {fam: lay.tolist() for fam, lay in layouts.items()},
            "numbers": worlds,
        },
    )
    ctx.table(
        "hull_failures_over_worlds",
        "Failed releases inside and outside the landmarks' hull over the env1 worlds",
        rows,
        source="§4.2, Fig 4.11",
        note=f"{sizes}; failures among the counted release points (those the catchment counts) inside and outside "
        f"each world's own landmark hull; band: the {BAND[0]:g}-{BAND[1]:g} % percentiles over the members with a "
        f"counted point in the region; built-in env1: on the same grid, first slice. The thesis prints no numbers.",
    )
    ctx.figure(
        "hull_failures_over_worlds.png",
        member_figure(worlds, members),
        "Claim 10 per env1 world: image matching's failed releases outside the landmarks' hull against inside "
        f"(left) and against DELV's outside (right); above the dashed line by the check's 10 points; the built-in "
        f"env1 (x); {sizes}.",
    )
    record_claims(
        ctx,
        claim_rows(worlds, members, layouts, ids=set(CLAIM_IDS)),
        "claims_over_worlds_hull",
        "Claim 10 over the worlds: the share of env1 members in which image matching fails more often outside the "
        "landmarks' hull",
        CLAIMS_TABLE_NOTE.format(holds=WORLD_HOLDS, fails=WORLD_FAILS)
        + f" {sizes}. Cannot tell also where a member's hull holds no counted grid point ({empty} of {members} "
        "members here).",
        figure="claims_decided_by_hull.png",
    )
