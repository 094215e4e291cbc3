"""World ensembles: every thesis number of Figs 4.5/5.5 and Tables 5.1-5.4 over the worlds the thesis's
words allow, and each claim's probability (beyond the thesis; docs/reproduce.md "Ensembles").

The thesis gives no coordinates, so one reconstructed world per environment is an anecdote. Here each
of its worlds is a family (`delvjax.envs.FAMILIES`, docs/model.md §6.1): MEMBERS layouts per family,
each with its own seed (a member's release headings come from it), evaluated as catchment sweeps (one
compiled program per landmark count: every world, method and occlusion choice of a group in one
array program, `delvjax.sweeps`). The built-in world of each family runs beside its members on the
same grid. Reported: per thesis number our median and 5-95 % band over members, where the thesis
number falls in it (its percentile) and the built-in world's value; per claim whose numbers the
ensemble makes, the share of members in which the check of `studies/claims` holds (Wilson 95 %
interval), and for claims that depend on the world the world property that separates the members
where they hold from those where they fail.
"""

from __future__ import annotations

import atexit
import re
import shutil
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from delvjax.envs import FAMILIES, ensemble_envs, world_properties
from delvjax.plots import subplots
from delvjax.sweeps import parse_sweep, run_sweep

from ..claims import WORLD_FAILS, WORLD_HOLDS
from ._common import LABEL
from ._ensemble_gaps import cause_counts, gap_cause, gaps_text
from ._ensemble_stats import (
    BAND,
    IDENTIFIES,
    NOISE_DEG,
    SEED_SPREAD,
    claim_rows,
    distribution_rows,
    settings_rows,
    settings_text,
    thesis_numbers,
)

TITLE = "World ensembles: the thesis's numbers and claims over every world its words allow (beyond the thesis)"
COST = 330  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first


@dataclass(frozen=True)
class Group:
    """One sweep of the study: the members of `families` (and, with `builtin`, their built-in worlds), or
    with `members_too` False the built-in worlds alone; every method, k = 0..k_max, rule set
    (`collisions`: "ignore" the default rules, "fail" the physical ones, docs/model.md §5) and seed offset."""

    families: tuple[str, ...]
    methods: tuple[str, ...]
    k_max: int
    collisions: str = "ignore"
    seeds: tuple[int, ...] = (0,)
    members_too: bool = True
    bearing_noise_deg: float = 0.0

    @property
    def tail(self) -> str:
        """The suffix of this group's keys: "" for the default setting, ":physical" for the physical rules,
        ":bearing<sigma>" for bearing noise (SETTINGS)."""
        if self.collisions == "fail":
            return ":physical"
        return f":bearing{self.bearing_noise_deg:g}" if self.bearing_noise_deg else ""


FOUR = ("env1", "env2", "env3", "ring4")
EVERY_METHOD = ("delv", "delv-compass", "acv", "alv")
COMPASS_METHODS = ("delv-compass", "acv", "alv")
# Two programs: Figs 4.5/5.5, Tables 5.1/5.3 and Table 5.2's L = 3 (ring3 padded to four landmark slots, its DELV
# cells skipped: one program with env1-3) with the built-in worlds under four more seeds, the same under 2° of
# bearing noise; Table 5.4's L = 5, 6 rings (six slots, 20 masks).
# The catchments under the physical rules (the rule set is a setting the thesis leaves unstated) come from the
# default groups' own trials (`catchment_physical_pct`: a trial that touches a landmark fails), every k and world.
GROUPS = (
    Group((*FOUR, "ring3"), EVERY_METHOD, 2),
    Group(FOUR, EVERY_METHOD, 2, seeds=SEED_SPREAD, members_too=False),
    Group(FOUR, EVERY_METHOD, 2, bearing_noise_deg=NOISE_DEG),
    Group(FOUR, EVERY_METHOD, 2, seeds=SEED_SPREAD, members_too=False, bearing_noise_deg=NOISE_DEG),
    Group(("ring5", "ring6"), COMPASS_METHODS, 3),
)
QUICK_GROUPS = (Group(("env1", "env2", "env3"), EVERY_METHOD, 2),)  # a preview: --quick stays under a minute
# the default sweeps: their env1-3 cells are `ensemble_ranges`' factor-1 cells, read from `shared_cells`
SHARED_GROUPS = (GROUPS[0], QUICK_GROUPS[0])
STEPS = len(GROUPS)
MEMBERS = 44  # full run: members per family (Wilson 95 % half-width <= 14.6 points at any share)
QUICK_MEMBERS = 2
LANES = 128  # a full run's rollout lanes (no number depends on them): 128 run these cells faster than 256
SEED_SLICES = 4  # a full run's members run in this many slices, each under its own seed (`sweep_texts`)
PREVIEW_SPACING = 200.0  # cm: the preview's grid (5 x 5), the test suite's tiny run's too (one program for both)
# cm: the members' grid (10 x 10). A 25 cm grid costs 16 times as much; the built-in worlds' numbers at 25 cm
# (the occlusion study) beside those at this spacing show what the coarse grid moves (docs/reproduce.md "Ensembles")
SPACING = 100.0


def plan(ctx) -> tuple[tuple, int, float]:
    """(groups, members per family, spacing) of this run: the full ensembles at SPACING, or under --quick or
    a grid coarser than SPACING a preview (QUICK_MEMBERS of env1-3 on a PREVIEW_SPACING grid, default rules, one
    seed)."""
    if ctx.config.quick or ctx.config.spacing > SPACING:
        return QUICK_GROUPS, QUICK_MEMBERS, max(ctx.config.spacing, PREVIEW_SPACING)
    return GROUPS, MEMBERS, SPACING


def sweep_texts(group: Group, members: int, spacing: float, seed: int, slices: int = SEED_SLICES) -> list[str]:
    """The catchment sweep files of one group (docs/sweeps.md; the members are `{ensemble = ...}` tables). The
    members are cut into `slices` slices, slice j under the run's seed + j (with the group's offsets): the
    noise and release headings of a member are never those of every other (issue 52: "noisy settings are never
    reported from one seed"); the built-in worlds run in the first slice. Layouts come from the run's seed."""
    quoted = lambda names: "[" + ", ".join(f'"{n}"' for n in names) + "]"  # noqa: E731
    slices = slices if group.members_too else 1
    physical = ', "catchment_physical_pct"' if group.tail == "" else ""  # the physical rules from the same trials
    size = -(-members // slices)
    texts = []
    for j in range(slices):  # a handful of sweep calls of one program: input preparation
        first, count = j * size, min(size, members - j * size)
        envs = [
            f'{{ensemble = "{f}", members = {count}, first = {first}, seed = {seed}}}'
            for f in group.families
            if group.members_too and count > 0
        ]
        envs += [f'"{f}"' for f in group.families] if j == 0 else []
        if not envs:
            continue
        texts.append(
            f'[sweep]\nkind = "catchment"\nmetrics = ["catchment_pct", "gt45_pct", "gt90_pct", "mean_error_deg"{physical}]\n'
            f"[axes]\nenv = [{', '.join(envs)}]\nmethod = {quoted(group.methods)}\n"
            f"occlude = {list(range(group.k_max + 1))}\nspacing = [{spacing}]\n"
            f"seed = {[seed + j + s for s in group.seeds]}\ncollisions = {quoted([group.collisions])}\n"
            f"bearing_noise_deg = [{group.bearing_noise_deg}]\n"
        )
    return texts


_SHARED: list[Path] = []  # the folder of `shared_cells`, made on first use
_SHARED_LOCK = threading.Lock()


def shared_cells() -> Path:
    """A folder of finished catchment cells the ensemble studies of this process share (`run_sweep(out=...)`,
    docs/sweeps.md "Resuming": a cell is known by a digest of everything that decides its numbers, so a cell one
    study finished is read, not computed, by another; `ensemble_ranges`' factor-1 members are this study's first
    22). One per process (the studies of a run are its threads), removed at exit."""
    with _SHARED_LOCK:
        if not _SHARED:
            path = Path(tempfile.mkdtemp(prefix="delvjax-ensemble-cells-"))
            atexit.register(shutil.rmtree, path, True)
            _SHARED.append(path)
        return _SHARED[0]


def skipped_cells():
    """`run_sweep`'s `skip`: True for a cell no table or claim reads, so it is never computed (its numbers NaN, left
    out by `member_numbers`): a cell is read only where a thesis number has its family, method and k
    (`_ensemble_stats.thesis_numbers`), and so is every cell a claim of `studies/claims` reads (DELV without a compass at k = 0 on
    env1-3 only, none on ring4; the claims read its occlusion rows with a compass). `ensemble_ranges` skips the
    same cells (members of a scaled family, `env1x0.666667-m3`, are their family's)."""
    wanted: dict[tuple[str, str], set[int]] = {}
    for _, fam, m, k, _, _ in thesis_numbers():
        wanted.setdefault((fam, m), set()).add(k)

    def skip(cell: dict) -> bool:
        fam = re.sub(r"(x[0-9.]+)?(-s\d+)?-m\d+$", "", str(cell["env"]))
        return int(cell["occlude"]) not in wanted.get((fam, str(cell["method"])), set())

    return skip


def member_numbers(ds, group: Group) -> dict[str, dict]:
    """{world label: {claims key: value}} of one group's sweep, under the keys the claims read
    (`occlusion:<family>:<method>:gt45|gt90|catchment` over k, `catchment:<family>:<method>` and
    `map:<family>:<method>:mean_error_deg` at k = 0; under the physical rules the catchments with
    `:physical` appended, as the point run's studies record them). A member's label is `<family>-m<i>`;
    with several seeds, the label gets `@<offset>`, the seed's offset from the run's (`Group.seeds`)."""
    out: dict[str, dict] = {}
    tail = group.tail
    seeds = [int(v) for v in np.atleast_1d(ds.seed.values)]
    offset = dict(zip(seeds, group.seeds))  # the run's seed + offset, in the sweep file's order (first slice)
    for name in ds.env.values:
        label = re.sub(r"-s\d+-m(\d+)$", r"-m\1", str(name))  # members by index whatever the layouts' seed
        family = label.rsplit("-m", 1)[0]
        for seed in seeds:
            nums: dict = {}
            for m in group.methods:
                where = {"env": name, "homing_method": m} | ({"seed": seed} if "seed" in ds.dims else {})
                cell = ds.sel(where)  # the axis `method` is the Dataset's `homing_method` (docs/sweeps.md)
                by_k = lambda var: [None if np.isnan(v) else float(v) for v in np.atleast_1d(cell[var].values)]  # noqa: E731
                fields = ("catchment",) if group.collisions == "fail" else ("gt45", "gt90", "catchment")
                for field in fields:
                    nums[f"occlusion:{family}:{m}:{field}{tail}"] = by_k(f"{field}_pct")
                nums[f"catchment:{family}:{m}{tail}"] = by_k("catchment_pct")[0]
                if tail == "" and "catchment_physical_pct" in cell:  # the physical rules, from the same trials
                    nums[f"occlusion:{family}:{m}:catchment:physical"] = by_k("catchment_physical_pct")
                    nums[f"catchment:{family}:{m}:physical"] = by_k("catchment_physical_pct")[0]
                if group.collisions != "fail":
                    nums[f"map:{family}:{m}:mean_error_deg{tail}"] = by_k("mean_error_deg")[0]
            key = str(label) if len(seeds) == 1 else f"{label}@{offset[seed]}"
            kept = {
                k: v
                for k, v in nums.items()
                if v is not None and (not isinstance(v, list) or any(x is not None for x in v))
            }
            out.setdefault(key, {}).update(kept)  # a skipped cell's numbers (None) are left out (`skipped_cells`)
    return out


def run(ctx) -> None:
    groups, members, spacing = plan(ctx)
    seed = ctx.config.seed
    worlds: dict[str, dict] = {}
    lanes = min(LANES, ctx.config.lanes) if groups is GROUPS else ctx.config.lanes  # the preview's: settings'
    for group in groups:  # five groups, two programs (the noise and extra seeds share the first one's)
        for text in sweep_texts(group, members, spacing, seed, 1 if groups is QUICK_GROUPS else SEED_SLICES):
            shared = shared_cells() if group in SHARED_GROUPS else None  # ensemble_ranges reads these cells
            spec = parse_sweep(text, "ensembles")
            ds = run_sweep(spec, lanes=lanes, out=shared, skip=skipped_cells())
            for label, nums in member_numbers(ds, group).items():
                worlds.setdefault(label, {}).update(nums)
        ctx.step(", ".join(group.families) + (f" ({group.collisions})" if group.collisions != "ignore" else ""))
    for _ in range(STEPS - len(groups)):  # a preview: the progress bar still ends at its total
        ctx.step("the other sweeps: full run only")
    layouts = {
        fam: np.array(
            [[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in ensemble_envs(fam, members, seed)]
        )
        for fam in dict.fromkeys(f for g in groups for f in g.families)
    }
    rows = distribution_rows(worlds, members)
    for r in rows:  # every number outside the band gets its cause, or "unexplained"
        r["gap cause"] = gap_cause(r, spacing)
    inside = sum(r["inside band"] for r in rows)
    unexplained = sum(v for k, v in cause_counts(rows).items() if k.startswith("unexplained"))
    ctx.number("ensemble:members", members)
    ctx.number("ensemble:spacing", spacing)
    ctx.number("ensemble:thesis_inside_band", [inside, len(rows)])
    ctx.number("ensemble:thesis_unexplained", [unexplained, len(rows)])
    ctx.json(
        "ensemble_worlds.json",
        {
            "settings": {"members": members, "spacing": spacing, "seed": seed, "band": list(BAND)},
            "layouts": {fam: lay.tolist() for fam, lay in layouts.items()},
            "properties": {
                fam: {k: v.tolist() for k, v in world_properties(lay).items()} for fam, lay in layouts.items()
            },
            "numbers": worlds,
        },
    )
    ctx.table(
        "thesis_numbers_over_worlds",
        "Every thesis number beside our distribution over the worlds its words allow",
        rows,
        source="Figs 4.5, 5.5, Tables 5.1-5.4",
        note=f"{members} worlds per family (docs/model.md §6.1), each with its own seed, grid spacing {spacing:g} cm, "
        f"default rules; band: the {BAND[0]:g}-{BAND[1]:g} % percentiles over the members; thesis percentile: the "
        "share of members below the thesis's number (ties half); built-in world: our named member on the same grid. "
        f"{inside} of {len(rows)} thesis numbers lie inside our band. The thesis's L = 4 rows copy other rows "
        f"(docs/reproduce.md). Gap cause: the first rule of studies/runs/_ensemble_gaps.py that explains a number "
        f"outside the band. {gaps_text(rows)}",
    )
    ctx.figure(
        "thesis_numbers_over_worlds.png",
        bands_figure(rows),
        "Each thesis number (red) against our 5-95 % band (grey bar) and median (black) over the ensemble; "
        "the built-in world's value (blue).",
    )
    implied = settings_rows(rows)
    if implied:
        ctx.table(
            "settings_the_thesis_favours",
            "Which unstated settings the thesis's numbers favour",
            implied,
            source="Figs 4.5, 5.5, Tables 5.1-5.4",
            note=f"A setting is favoured when it puts at least {IDENTIFIES:g} points more of the thesis's numbers inside "
            "its 5-95 % band than the other, and its percentiles lie nearer 50. The physical rules' catchments come "
            f"from the default trials (every k and world); {NOISE_DEG:g}° of bearing noise on env1-3 and ring4. {settings_text(rows)}",
        )
    record_claims(
        ctx,
        claim_rows(worlds, members, layouts),
        "claims_over_worlds",
        "Claims over the worlds: the share of members in which each claim's check holds",
        CLAIMS_TABLE_NOTE.format(holds=WORLD_HOLDS, fails=WORLD_FAILS)
        + " A member is one world of each family with its own seed.",
    )


CLAIMS_TABLE_NOTE = (
    "holds: in at least {holds:g} % of members; fails: it holds or partly holds in at most {fails:g} %; partly: it "
    "holds or partly holds in at least {holds:g} %; else depends on the world, with the world property that best "
    "separates the members where it holds (AUC: 1 or 0 separates them fully, 0.5 not at all); cannot tell: most "
    "members at a ceiling; partly %: the share where the check says partly (not counted in holds %)."
)


def record_claims(
    ctx, claims: list[dict], table: str, title: str, note: str, figure: str = "claims_decided_by.png", extra=None
) -> None:
    """What every ensemble study records of the claims it judges (`_ensemble_stats.claim_rows`): each claim's share
    as `ensemble:claim:<id>` = [holds %, interval low, high, members, cannot tell %, partly %] (the claims table's
    *over worlds* column, studies/claims `over_worlds`), the table `table` (with `extra(row)`'s columns) and, for
    the claims that depend on the world, the figure `figure` of the property that decides them."""
    for r in claims:
        lo, hi = (float(v) for v in r["95 % interval"].split("-"))
        ctx.number(f"ensemble:claim:{r['id']}", [r["holds %"], lo, hi, r["members"], r["cannot tell %"], r["partly %"]])
    if not claims:
        return
    rows = [{**{k: v for k, v in r.items() if k != "decided_by_values"}, **(extra(r) if extra else {})} for r in claims]
    ctx.table(table, title, rows, source="studies/claims", note=note)
    deciding = [r for r in claims if r.get("decided_by")]
    if deciding:
        ctx.figure(
            figure,
            decided_figure(deciding),
            "Claims that depend on the world: the world property that best separates the members where the claim "
            "holds (green) from those where it does not (red).",
        )


# --- figures ---------------------------------------------------------------------------------------


def bands_figure(rows: list[dict]):
    """Per thesis number a row of markers: our band over the worlds, its median, the thesis's value and the
    built-in world's; catchments in the left panel, error point rates in the right."""
    panels = [[r for r in rows if r["quantity"] == "catchment %"], [r for r in rows if r["quantity"] != "catchment %"]]
    panels = [p for p in panels if p] or [[]]
    n = max(len(p) for p in panels) or 1
    fig, axes = subplots(1, len(panels), figsize=(7.5 * len(panels), 0.14 * n + 1.4), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        for i, r in enumerate(panel):
            y = len(panel) - i
            ax.plot([r["ours 5 %"], r["ours 95 %"]], [y, y], color="0.75", lw=4, solid_capstyle="butt")
            ax.plot(r["ours median"], y, "|", color="black", ms=8)
            ax.plot(r["built-in world"], y, "o", color="tab:blue", ms=3)
            ax.plot(r["thesis"], y, "x", color="tab:red", ms=5)
        labels = [
            f"{r['source']} {r['world']} {LABEL.get(r['method'], r['method'])} k={r['k']} {r['quantity']}"
            for r in panel
        ]
        ax.set_yticks(range(len(panel), 0, -1), labels, fontsize=5)
        ax.set_ylim(0.3, len(panel) + 0.7)
        ax.set_ylabel("thesis number (source, world, method, hidden k)", fontsize=7)
        ax.set_xlabel("%")
        ax.set_xlim(-2, 102)
        ax.set_title("thesis (x), our 5-95 % band over worlds (bar), median (|), built-in world (o)", fontsize=7)
    fig.tight_layout()
    return fig


def decided_figure(rows: list[dict]):
    """Per claim that depends on the world: its deciding property per member, coloured by whether it holds."""
    fig, axes = subplots(1, len(rows), figsize=(3.2 * len(rows), 3.0), squeeze=False)
    for ax, r in zip(axes[0], rows):
        d = r["decided_by_values"]
        v, held = np.asarray(d["values"]), np.asarray(d["holds"])
        jitter = np.linspace(-0.15, 0.15, len(v))
        ax.scatter(v[held], 1 + jitter[held], color="tab:green", s=10, label="holds")
        ax.scatter(v[~held], jitter[~held], color="tab:red", s=10, label="does not")
        ax.set_yticks([0, 1], ["no", "yes"])
        ax.set_ylabel("claim holds in the member")
        ax.set_xlabel(f"{d['family']}: {d['property']}", fontsize=7)
        ax.set_title(f"claim {r['#']} ({r['holds %']:.0f} %)", fontsize=8)
    fig.tight_layout()
    return fig


__all__ = ["FAMILIES", "GROUPS", "TITLE", "run"]
