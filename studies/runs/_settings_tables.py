"""The tables and figure of the `ensemble_settings` study: the design with its scores, each setting's values
and whether the thesis's numbers identify it, and the thesis numbers no combination brings inside our band."""

from __future__ import annotations

import numpy as np

from delvjax.plots import subplots

from ._common import LABEL
from ._ensemble_stats import SOURCE_LABEL
from ._settings_design import SETTINGS, combination
from ._settings_estimate import BAND


def _settings(levels) -> dict:
    """A combination's settings under their names with units (the design table's columns)."""
    return {
        SETTINGS[n][0] + (f" ({SETTINGS[n][2].strip()})" if SETTINGS[n][2] else ""): v
        for n, v in combination(levels).items()
    }


def design_rows(levels: np.ndarray, comb: dict, per_number: np.ndarray, offsets: np.ndarray, items: list) -> list[dict]:
    """One row per combination, the best first: its settings, score and band, the mean |percentile - 50| of
    the thesis's numbers, the score per figure / table, how often it is best and whether it is distinguishable
    from the best."""
    sources = list(dict.fromkeys(r[0] for r in items))
    rows = []
    for c in np.argsort(comb["score"], kind="stable"):
        rows.append(
            {
                "#": int(c),
                **_settings(levels[c]),
                "score (mean CRPS, points)": float(comb["score"][c]),
                "score 5 %": float(comb["lo"][c]),
                "score 95 %": float(comb["hi"][c]),
                "mean |percentile - 50|": float(offsets[c].mean()),
                **{
                    SOURCE_LABEL[src]: float(per_number[c, [i for i, r in enumerate(items) if r[0] == src]].mean())
                    for src in sources
                },
                "best in % of resamples": float(comb["share_best"][c]),
                "not distinguishable from the best": bool(comb["indistinct"][c]),
            }
        )
    return rows


def identified_rows(found: dict, shown: dict) -> list[dict]:
    """One row per setting: its values with their scores and bands, the best value, how often it is best, the
    values the thesis's numbers do not exclude, and whether they identify it."""
    rows = []
    for name, f in found.items():
        per_value = "; ".join(
            f"{shown[name][v]}: {f['score'][v]:.2f} [{f['lo'][v]:.2f}-{f['hi'][v]:.2f}]" for v in range(len(f["score"]))
        )
        rows.append(
            {
                "setting": SETTINGS[name][0],
                "score per value [5-95 %]": per_value,
                "best value": shown[name][f["best"]],
                "best in % of resamples": float(f["share_best"][f["best"]]),
                "not excluded": ", ".join(shown[name][v] for v in f["kept"]),
                "identified": bool(f["identified"]),
            }
        )
    return rows


def value_rows(found: dict, shown: dict) -> list[dict]:
    """One row per (setting, value): its score, band, share of resamples where it is best and the lower bound
    of its gap to the best value."""
    return [
        {
            "setting": SETTINGS[name][0],
            "value": shown[name][v],
            "score (mean CRPS, points)": float(f["score"][v]),
            "5 %": float(f["lo"][v]),
            "95 %": float(f["hi"][v]),
            "best in % of resamples": float(f["share_best"][v]),
            "gap bound (points)": float(f["gap_low"][v]),
            "best": v == f["best"],
            "excluded": v not in f["kept"],
        }
        for name, f in found.items()
        for v in range(len(f["score"]))
    ]


def unreached_rows(x: np.ndarray, items: list, levels: np.ndarray) -> list[dict]:
    """The thesis numbers outside the BAND of our members under every combination: the combination whose band
    comes nearest, that band and our median under the defaults (their causes: the `ensembles` study's gaps)."""
    lo, hi = np.percentile(x, BAND, axis=-1)  # (C, N)
    t = np.array([r[5] for r in items], float)
    off = np.maximum(lo - t, 0.0) + np.maximum(t - hi, 0.0)  # distance of the thesis number from each band
    rows = []
    for n in np.flatnonzero((off > 0).all(axis=0)):
        source, fam, method, k, q, value = items[n]
        c = int(np.argmin(off[:, n]))
        default = float(np.median(x[0, n]))
        rows.append(
            {
                "source": SOURCE_LABEL[source],
                "world": fam,
                "method": LABEL.get(method, method),
                "k": k,
                "quantity": {"catchment": "catchment %", "gt45": "e>45 %", "gt90": "e>90 %"}[q],
                "thesis": value,
                "defaults: median": default,
                "nearest band": f"{lo[c, n]:.1f}-{hi[c, n]:.1f}",
                "nearest: #": c,
                "nearest: settings": ", ".join(f"{k_}={v}" for k_, v in combination(levels[c]).items()),
            }
        )
    return rows


def settings_figure(found: dict, labels: dict, shown: dict):
    """One panel per setting: each value's score with its band over the resamples; best black, not excluded
    grey, excluded red; the title says whether the thesis's numbers identify the setting."""
    fig, axes = subplots(1, len(found), figsize=(2.6 * len(found), 3.2), squeeze=False, sharey=True)
    for ax, (name, f) in zip(axes[0], found.items()):
        values = SETTINGS[name][1]
        order = list(np.argsort(values)) if not isinstance(values[0], str) else list(range(len(values)))
        for x, v in enumerate(order):  # numeric values in their order (the default is listed first in SETTINGS)
            colour = "black" if v == f["best"] else "0.55" if v in f["kept"] else "tab:red"
            ax.errorbar(
                x,
                f["score"][v],
                yerr=[[f["score"][v] - f["lo"][v]], [f["hi"][v] - f["score"][v]]],
                fmt="o",
                color=colour,
                capsize=3,
            )
        ax.set_xticks(range(len(order)), [shown[name][v] for v in order])
        ax.set_xlim(-0.5, len(order) - 0.5)
        ax.set_xlabel(labels[name], fontsize=8)
        ax.set_title("identified" if f["identified"] else "not identified", fontsize=8)
    axes[0][0].set_ylabel("mean CRPS of the thesis's numbers (points)", fontsize=8)
    fig.tight_layout()
    return fig
