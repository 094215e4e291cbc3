"""The tables and figures of the `ensemble_rollouts` study (docs/reproduce.md "Ensembles: step distance, success
rates, quantization"): every number its sweeps make over the members (median, band, the built-in world over the
slices' seeds), the thesis's printed success bound, the step-distance and success-rate curves over the worlds, and
what the members' fewer trials move on the built-in world. Plain NumPy on the members' numbers."""

from __future__ import annotations

import numpy as np

from delvjax.plots import subplots

from .. import thesis
from ._common import LABEL
from ._ensemble_rollouts_keys import COMPASS, DS, LAYOUTS, LEVELS
from ._ensemble_stats import BAND, percentile_of

# --- the tables ------------------------------------------------------------------------------------------

# (row label, key, what it is): every number the sweeps make for a member, in the tables' order
QUANTITIES = (
    *((f"DELV d = {d:g} cm: mean error °", f"map:env1:delv:d={d:g}:mean_error_deg") for d in DS),
    *((f"DELV d = {d:g} cm: catchment %", f"catchment:env1:delv:d={d:g}") for d in DS),
    *((f"DELV {q} level{'s' * (q > 1)}: catchment %", f"catchment:env1:delv:Q{q}") for q in LEVELS),
    *((f"DELV {q} level{'s' * (q > 1)}: success %", f"success_overall:env1:delv:Q{q}") for q in LEVELS),
    ("DELV continuous: success %", "success_overall:env1:delv"),
    ("DELV, physical rules: success %", "success_overall:env1:delv:physical"),
    ("DELV, homing first move: success %", "success_overall:env1:delv:homing"),
    ("image matching: success %", "success_overall:env1:warping"),
    ("image matching: catchment %", "catchment:env1:warping"),
    *((f"{LABEL[m]}: success %", f"success_overall:env1:{m}") for m in COMPASS),
    *((f"DELV 3 levels, {fam}: mean error °", f"map:{fam}:delv:Q3:mean_error_deg") for fam in LAYOUTS),
)


def _family(key: str) -> str:
    return key.split(":")[1]


def number_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """Per quantity of QUANTITIES the sweeps made: median, band and share at 100 % over the members, and the
    built-in world's range over the slices' seeds."""
    rows = []
    for label, key in QUANTITIES:
        fam = _family(key)
        sample = [worlds[w][key] for w in (f"{fam}-m{i}" for i in range(members)) if key in worlds.get(w, {})]
        if not sample:
            continue
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
        builtin = [v[key] for w, v in worlds.items() if (w == fam or w.startswith(f"{fam}@")) and key in v]
        rows.append(
            {
                "number": label,
                "key": key,
                "median": float(med),
                f"{BAND[0]:g} %": float(lo),
                f"{BAND[1]:g} %": float(hi),
                "members": len(sample),
                "at 100 % share": None if key.startswith("map:") else 100.0 * float(np.mean(np.asarray(sample) >= 100)),
                "built-in world over seeds": f"{min(builtin):.1f}-{max(builtin):.1f} ({len(builtin)} seeds)"
                if builtin
                else "",
                "built-in world mean": float(np.mean(builtin)) if builtin else None,
            }
        )
    return rows


def thesis_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """Fig 4.10b's printed bound (DELV > 90 % at every release distance): each member's lowest success rate over
    the distances under the default and the physical rules, our median and band, the bound's percentile."""
    bound = thesis.OTHER["fig4_10b_delv_success_rate"]["value"]
    rows = []
    for rules, tail in (("default", ""), ("physical", ":physical")):
        key = f"success:env1:delv{tail}"
        sample = [min(worlds[w][key]) for w in (f"env1-m{i}" for i in range(members)) if key in worlds.get(w, {})]
        if not sample:
            continue
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
        rows.append(
            {
                "source": "Fig 4.10b (§4.2)",
                "quantity": f"DELV lowest success over distances, {rules} rules %",
                "thesis": f"> {bound:g}",
                "ours median": float(med),
                f"ours {BAND[0]:g} %": float(lo),
                f"ours {BAND[1]:g} %": float(hi),
                "thesis percentile": percentile_of(bound, sample),
                "members above the bound %": 100.0 * float(np.mean(np.asarray(sample) > bound)),
                "members": len(sample),
            }
        )
    return rows


CURVES = (  # (panel, line label, key)
    *(("Fig 4.10b", LABEL[m], f"success:env1:{m}") for m in ("delv", "warping")),
    ("Fig 4.10b", "DELV, physical rules", "success:env1:delv:physical"),
    *(("Fig 4.13b", f"{q} level{'s' * (q > 1)}", f"success:env1:delv:Q{q}") for q in LEVELS),
    ("Fig 4.13b", "continuous", "success:env1:delv:continuous"),
    *(("Fig 5.7b", LABEL[m], f"success:env1:{m}") for m in COMPASS),
)
DISTANCES_CM = tuple(float(v) for v in range(50, 451, 50))


def success_curves(worlds: dict[str, dict], members: int) -> list[dict]:
    """Rows (panel, line, distance, median, band) of every success curve the sweeps made, over the members."""
    rows = []
    for panel, line, key in CURVES:
        sample = np.array([worlds[w][key] for w in (f"env1-m{i}" for i in range(members)) if key in worlds.get(w, {})])
        if not len(sample):
            continue
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]], axis=0)
        for i, d in enumerate(DISTANCES_CM[: sample.shape[1]]):
            rows.append(
                {
                    "panel": panel,
                    "line": line,
                    "distance cm": d,
                    "median %": float(med[i]),
                    "band lo %": float(lo[i]),
                    "band hi %": float(hi[i]),
                }
            )
    return rows


def step_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """Per step distance d: the mean error and catchment's median and band over the env1 members, and the
    built-in world's (first seed)."""
    rows = []
    for d in DS:
        for what, key in (
            ("mean error °", f"map:env1:delv:d={d:g}:mean_error_deg"),
            ("catchment %", f"catchment:env1:delv:d={d:g}"),
        ):
            sample = [worlds[w][key] for w in (f"env1-m{i}" for i in range(members)) if key in worlds.get(w, {})]
            lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
            builtin = worlds.get("env1", {}).get(key)
            rows.append(
                {
                    "d cm": d,
                    "quantity": what,
                    "median": float(med),
                    "band lo": float(lo),
                    "band hi": float(hi),
                    "built-in world": builtin,
                }
            )
    return rows


def step_figure(rows: list[dict]):
    """Two panels over d: the mean error and the catchment, median, band and built-in world."""
    fig, axes = subplots(1, 2, figsize=(8.0, 3.8), squeeze=False)
    for ax, what in zip(axes[0], ("mean error °", "catchment %")):
        sel = [r for r in rows if r["quantity"] == what]
        x = np.array([r["d cm"] for r in sel])
        ax.vlines(x, [r["band lo"] for r in sel], [r["band hi"] for r in sel], color="0.7", lw=6, label="5-95 % band")
        ax.plot(x, [r["median"] for r in sel], "o-", color="black", ms=4, label="median over worlds")
        ax.plot(
            x,
            [np.nan if r["built-in world"] is None else r["built-in world"] for r in sel],
            "x",
            color="tab:blue",
            label="built-in env1",
        )
        ax.set_xlabel("step distance d (cm)")
        ax.set_ylabel(what.replace(" °", " (°)").replace(" %", " (%)"))
        ax.set_xticks(x)
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3, frameon=False)
    fig.tight_layout()
    return fig


def success_figure(rows: list[dict]):
    """One panel per thesis figure: each line's median over the members (lines a few cm apart, so that equal
    medians stay visible) and its band."""
    panels = list(dict.fromkeys(r["panel"] for r in rows))
    fig, axes = subplots(1, len(panels), figsize=(4.4 * len(panels), 4.0), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        lines = list(dict.fromkeys(r["line"] for r in rows if r["panel"] == panel))
        for i, line in enumerate(lines):
            sel = [r for r in rows if r["panel"] == panel and r["line"] == line]
            x = np.array([r["distance cm"] for r in sel]) + 4.0 * (i - (len(lines) - 1) / 2)
            (drawn,) = ax.plot(x, [r["median %"] for r in sel], marker="osd^v"[i % 5], ms=3, lw=1, label=line)
            lo, hi = [r["band lo %"] for r in sel], [r["band hi %"] for r in sel]
            ax.fill_between(x, lo, hi, color=drawn.get_color(), alpha=0.12)
        ax.set_xlabel("release distance from home (cm)")
        ax.set_ylabel("success rate (%)")
        ax.set_ylim(-2, 104)
        ax.set_title(f"{panel} over the worlds", fontsize=9)
        ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=3, frameon=False)
    fig.tight_layout()
    return fig


# --- what the fewer trials move ----------------------------------------------------------------------


def trials_check_rows(rows: list[dict], flat: dict) -> list[dict]:
    """Per overall success rate of `number_rows` (the table's rows): the built-in world's value at the members'
    trials (mean over the slices' seeds) beside the point run's (`flat`: 100 trials per release distance, the
    same release distances; image_matching, quantization, comparators), their difference and the members'
    5-95 % band width: the fewer trials are good enough where the shift is well inside the band."""
    out = []
    for r in rows:
        point = flat.get(r["key"])
        if not r["key"].startswith("success_overall:") or not isinstance(point, (int, float)):
            continue
        width = r[f"{BAND[1]:g} %"] - r[f"{BAND[0]:g} %"]
        shift = abs(point - r["built-in world mean"])
        out.append(
            {
                "number": r["number"],
                "built-in, point run's trials": point,
                "built-in, members' trials (mean over seeds)": r["built-in world mean"],
                "shift": shift,
                "band width": width,
                "shift <= band": bool(shift <= width),
            }
        )
    return out
