"""The tables and figures of the `ensemble_maps` study: each number's median and 5-95 % band over the members
beside the built-in world's, error curves over the worlds, the visual compass's catchments per member, and the
grid check (what the compasses' coarse grid moves on the built-in worlds against the band). Plain NumPy and
Matplotlib on the members' numbers."""

from __future__ import annotations

import math

import numpy as np

from delvjax.plots import subplots

from ..claims import CHECKS, Missing
from ._common import LABEL
from ._ensemble_stats import BAND
from .visual_compass import BACKGROUNDS, TRUE, visual_key

FAMILIES = ("env1", "env2", "env3")
CURVE_PANELS = (("delv", "warping"), ("delv-compass", "acv", "alv"))  # claims 7 and 19, env1
CLAIMS_NOTE = (
    "holds: in at least {holds:g} % of members; fails: it holds or partly holds in at most {fails:g} %; partly: it "
    "holds or partly holds in at least {holds:g} %; else depends on the world, with the world property that best separates the members where it holds (AUC: 1 or 0 separates them fully, 0.5 not at "
    "all); cannot tell: most members at a ceiling. A member is one world of each family with its own seed; built-in "
    "worlds: the check on our named worlds on the same grids and seed. {sizes}"
)


def _values(worlds: dict, labels, key: str, index: int | None = None) -> list[float]:
    """The value of `key` (its `index`-th element for a list) in every world of `labels` that has it."""
    out = []
    for label in labels:
        v = worlds.get(label, {}).get(key)
        if isinstance(v, list):
            v = v[index] if index is not None and index < len(v) else None
        if v is not None and not math.isnan(v):
            out.append(float(v))
    return out


def band_row(worlds: dict, members: int, slices: int, key: str, index: int | None = None, **ids) -> dict | None:
    """One table row: `ids`, then the median and BAND of `key` over the first `members` members of the
    family `ids["family"]`, the built-in world's value under the run's seed and its range over the slices'."""
    fam = ids["family"]
    sample = _values(worlds, [f"{fam}-m{i}" for i in range(members)], key, index)
    builtin = _values(worlds, [fam], key, index)
    if not sample:
        return None
    lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
    seeds = _values(worlds, [fam, *(f"{fam}@{j}" for j in range(1, slices))], key, index)
    return {
        **ids,
        "members": len(sample),
        "median": float(med),
        "5 %": float(lo),
        "95 %": float(hi),
        "built-in world": builtin[0] if builtin else None,
        "built-in over seeds": f"{min(seeds):.1f}-{max(seeds):.1f} ({len(seeds)} seeds)" if seeds else "",
    }


def curve_rows(worlds: dict, members: int, slices: int) -> list[dict]:
    """env1's error curves per method and distance bin (claims 7, 19), then DELV's e > 45 rates inside and
    outside the landmarks' hull per family (claim 2)."""
    rows = []
    for m in dict.fromkeys(m for panel in CURVE_PANELS for m in panel):
        key = f"error_curve:env1:{m}"
        n_bins = max((len(worlds.get(f"env1-m{i}", {}).get(key, [])) for i in range(members)), default=0)
        for b in range(n_bins):  # a dozen bins
            where = {
                "family": "env1",
                "method": LABEL[m],
                "quantity": "mean error °",
                "bin (cm)": f"{50 * b}-{50 * (b + 1)}",
            }
            rows.append(band_row(worlds, members, slices, key, b, **where))
    for fam in FAMILIES:
        for where in ("inside", "outside"):
            key = f"map:{fam}:delv:gt45_{where}_hull_pct"
            ids = {"family": fam, "method": "DELV", "quantity": f"e>45 % {where} hull", "bin (cm)": "all"}
            rows.append(band_row(worlds, members, slices, key, **ids))
    return [r for r in rows if r is not None]


def distribution_rows(worlds: dict, members: int, visual_members: int, slices: int) -> list[dict]:
    """The visual compass's numbers per family, background and method (catchments over `visual_members`,
    mean errors over `members`), the true compass's beside them, and env1's heading errors."""
    rows = []
    for fam in FAMILIES:
        for m in TRUE:
            for q, key, n in (
                ("catchment % (true compass)", f"catchment:{fam}:{m}", members),
                ("mean error ° (true compass)", f"map:{fam}:{m}:mean_error_deg", members),
                ("catchment % (compass noise 45°)", f"compass_noise:{fam}:{m}:catchment", members),
            ):
                index = -1 if "noise" in q else None
                rows.append(
                    band_row(worlds, n, slices, key, index, family=fam, background="-", method=LABEL[m], quantity=q)
                )
        for bg in BACKGROUNDS:
            for m in TRUE:
                prefix = f"{visual_key(fam, bg)}:{m}"
                for q, key, n in (
                    ("catchment %", f"{prefix}:catchment", visual_members),
                    ("catchment % physical", f"{prefix}:catchment:physical", visual_members),
                    ("mean error °", f"{prefix}:mean_error_deg", members),
                ):
                    rows.append(
                        band_row(worlds, n, slices, key, family=fam, background=bg, method=LABEL[m], quantity=q)
                    )
    for bg in BACKGROUNDS:
        for q in ("heading_error_gt5_pct", "heading_error_mean_deg"):
            label = "heading error > 5° %" if "gt5" in q else "mean |heading error| °"
            key = f"visual:{bg}:{q}"
            rows.append(
                band_row(worlds, members, slices, key, family="env1", background=bg, method="-", quantity=label)
            )
    return [r for r in rows if r is not None]


def grid_check_rows(worlds: dict, flat: dict) -> list[dict]:
    """Per number of the compasses' coarse grid that the point run also records (the `visual_compass` study,
    same keys): the built-in world's value on both grids, their difference and the members' 5-95 % band
    width: the coarse grid is good enough where the shift is well inside the band (as `ensembles` checks its
    grid). `flat`: every study's numbers."""
    out = []
    for fam in FAMILIES:
        members = sorted(label for label in worlds if label.startswith(f"{fam}-m"))
        for key, coarse in worlds.get(fam, {}).items():
            coarse_grid = key.startswith(("visual:", "catchment:")) or (
                key.startswith("map:") and key.split(":")[2] in TRUE
            )
            fine = flat.get(key) if coarse_grid else None
            if not isinstance(fine, (int, float)) or not isinstance(coarse, (int, float)):
                continue
            sample = _values(worlds, members, key)
            if len(sample) < 2:
                continue
            lo, hi = np.percentile(sample, BAND)
            out.append(
                {
                    "number": key,
                    "built-in, point run's grid": float(fine),
                    "built-in, ensemble's grid": float(coarse),
                    "shift": abs(float(fine) - float(coarse)),
                    "band width": float(hi - lo),
                    "shift <= band": bool(abs(float(fine) - float(coarse)) <= hi - lo),
                }
            )
    return out


def builtin_verdict(worlds: dict, claim_id: str) -> str:
    """The claim's check on the built-in worlds of the run (their numbers on the members' grids, the run's
    seed; `random`: the `landmark_number` study's layouts): beside the members' share, what the point run's
    verdict becomes on these grids."""
    flat: dict = {}
    for fam in (*FAMILIES, "random"):
        flat.update(worlds.get(fam, {}))

    def get(key):
        if flat.get(key) is None:
            raise Missing(key)
        return flat[key]

    try:
        return CHECKS[claim_id](get)[1]
    except Missing:
        return "n/a"


# --- figures ---------------------------------------------------------------------------------------


def curves_figure(rows: list[dict]):
    """env1's error curves over the members (median, band) and the built-in world's, one panel per claim."""
    fig, axes = subplots(1, len(CURVE_PANELS), figsize=(6.2 * len(CURVE_PANELS), 4.2), squeeze=False)
    for ax, panel in zip(axes[0], CURVE_PANELS):
        for c, m in enumerate(panel):
            sub = [r for r in rows if r["method"] == LABEL[m] and r["bin (cm)"] != "all"]
            if not sub:
                continue
            x = np.array([float(r["bin (cm)"].split("-")[0]) + 25.0 for r in sub])
            colour = f"C{c}"
            ax.fill_between(x, [r["5 %"] for r in sub], [r["95 %"] for r in sub], color=colour, alpha=0.2, lw=0)
            ax.plot(x, [r["median"] for r in sub], color=colour, marker="o", ms=3, label=f"{LABEL[m]}: members")
            builtin = [np.nan if r["built-in world"] is None else r["built-in world"] for r in sub]
            ax.plot(x, builtin, color=colour, ls="--", lw=1, label=f"{LABEL[m]}: built-in env1")
        ax.set_xlabel("distance from home (cm, bin centre)")
        ax.set_ylabel("mean angular error (°)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    return fig


def visual_figure(worlds: dict, visual_members: int):
    """Per family a panel: the visual compass's catchment per member for every background and method."""
    fig, axes = subplots(1, len(FAMILIES), figsize=(5.0 * len(FAMILIES), 4.2), sharey=True, squeeze=False)
    for ax, fam in zip(axes[0], FAMILIES):
        ticks = []
        for g, bg in enumerate(BACKGROUNDS):
            for c, m in enumerate(TRUE):
                x = 4 * g + c
                key = f"{visual_key(fam, bg)}:{m}:catchment"
                v = np.array(_values(worlds, [f"{fam}-m{i}" for i in range(visual_members)], key))
                jitter = np.linspace(-0.25, 0.25, len(v)) if len(v) > 1 else np.zeros(len(v))
                ax.scatter(x + jitter, v, s=6, color=f"C{c}", alpha=0.6, label=LABEL[m] if g == 0 else None)
                if len(v):
                    ax.plot([x - 0.35, x + 0.35], [np.median(v)] * 2, color="black", lw=1.5)
                builtin = _values(worlds, [fam], key)
                if builtin:
                    ax.plot(x, builtin[0], "x", color="black", ms=6, label="built-in world" if g == c == 0 else None)
            ticks.append((4 * g + 1, bg))
        ax.set_xticks([t for t, _ in ticks], [b for _, b in ticks], fontsize=8)
        ax.set_xlabel("background setting (per method: DELV, ACV, ALV)", fontsize=8)
        ax.set_title(f"{fam}: {visual_members} members", fontsize=9)
        ax.set_ylabel("catchment with the visual compass (%)")
        ax.set_ylim(-3, 103)
        ax.grid(alpha=0.3, axis="y")
    axes[0][0].legend(fontsize=7, loc="lower left")
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    return fig
