"""Homing (rollout) comparisons of thesis chapters 4-5 on the built-in environments (SPEC §5, §6).

Fig 4.5 / 5.5   catchment maps (squares on catchment points over the vector map) of DELV
                without and with a compass on env1-3, thesis catchment numbers beside ours.
Fig 4.9-4.10    DELV vs predictive image matching ("warping", mask channel) on env1: vector
                maps, error curves with 95 % t intervals, success rate vs release distance.
Fig 4.13b       success rate of DELV with Q = 1, 2, 5 quantization levels and continuous, and warping.
Fig 4.11 / 5.8  trajectories from the same release points: DELV vs warping; DELV-compass vs ACV vs ALV.
Fig 5.7b        success rate vs release distance of DELV-compass, ACV and ALV on env1.

Success: within 50 cm of home within 50 moves; a move into a landmark or out of the arena
fails (SPEC §5, stricter than the thesis, which is why our catchment is lower; see
studies/catchment_tables.py). Vector maps and error curves come from the catchment runs
themselves (the same headings and home record as `vector_map` with the same seed).
Every success-rate call (and every trajectory call) has the same shapes, so each method
compiles once for them; a catchment compiles once per method and environment (the number
of grid points differs between environments).

Run: python -m studies.homing --out results/homing [--spacing 25] [--trials 100] [--seed 0] [--quick]
Every figure has its numbers beside it as CSV; the headline numbers go to homing.json.
"""

from __future__ import annotations

import argparse

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

import delvjax
from delvjax.io import save_figure, write_csv
from delvjax.maps import VectorMap, vector_map_columns
from delvjax.metrics import error_curve, summarize_map
from delvjax.plots import error_curve_figure
from delvjax.plots_rollouts import SQUARE, catchment_panel, success_rate_figure, trajectories_figure
from delvjax.rollouts import OUTCOMES, SUCCESS, catchment_summary

from .common import Study
from .vector_maps import curves_csv, panel_figure

ENVS = ("env1", "env2", "env3")
LABEL = {"delv": "DELV", "delv-compass": "DELV (compass)", "warping": "image matching (warping)",
         "acv": "ACV", "alv": "ALV"}
SHORT = {**LABEL, "warping": "image matching"}
# SPEC §6: catchment area %, Figs 4.5 (no compass) and 5.5 (with compass).
THESIS_CATCHMENT = {"delv": {"env1": 98.52, "env2": 95.41, "env3": 77.66},
                    "delv-compass": {"env1": 92.01, "env2": 97.04, "env3": 84.91}}
# What the thesis's text says about the success-rate figures (it prints no numbers for them).
THESIS_CLAIMS = {
    "fig4_10b": "DELV succeeds > 90 % from every release distance; image matching is lower, worse far from home",
    "fig4_13b": "fewer quantization levels fail more often; three levels already guide the robot home in most cases",
    "fig5_7b": "DELV (compass), ACV and ALV similar; DELV slightly higher close to home, lower far away",
}
HOME_RADIUS = 50.0
N_STARTS = 8


def as_vector_map(c) -> VectorMap:
    """The vector map inside a `Catchment` (mask 0): same headings and home record as `vector_map`."""
    return VectorMap(points=c.points, included=c.included, heading=c.heading, direction=c.direction[0],
                     valid=c.valid[0], error_deg=c.error_deg[0])


def catchment_columns(c) -> dict[str, np.ndarray]:
    """Per grid point: the SPEC §7 vector-map columns plus the rollout's outcome and moves."""
    inc = np.asarray(c.included)
    outcome = np.asarray(c.outcome)[0][inc]
    return {**vector_map_columns(as_vector_map(c)), "outcome": np.array([OUTCOMES[o] for o in outcome]),
            "steps": np.asarray(c.steps)[0][inc]}


def catchment_figure(items: list[tuple[str, object, object]], spacing: float, title: str):
    """1 x 3 panels (Figs 4.5 / 5.5): items = [(panel title, env, Catchment)]."""
    fig, axes = plt.subplots(1, len(items), figsize=(4.8 * len(items), 5.3))
    for ax, (label, env, c) in zip(np.atleast_1d(axes), items):
        catchment_panel(ax, env, c, 0, spacing, title=label)
    handles = [Patch(label="start inside the catchment area", **SQUARE),
               Line2D([], [], marker="s", color="black", ls="", ms=7, label="home"),
               Line2D([], [], marker="o", color="0.15", ls="", ms=9, label="landmark (to scale)")]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=9, frameon=False)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return fig


def trajectory_rows(label: str, traj) -> list[dict]:
    """One row per visited position: label, trial, release heading, step, x, y, outcome of the trial."""
    path = np.asarray(traj.path)
    outcome = np.asarray(traj.outcome)
    heading = np.degrees(np.asarray(traj.heading))
    rows = []
    for t in range(path.shape[0]):  # a handful of paths: output formatting
        name = OUTCOMES[outcome[t]] if outcome[t] >= 0 else "running"
        for s in np.flatnonzero(np.all(np.isfinite(path[t]), axis=-1)):
            rows.append({"label": label, "trial": t, "release_heading_deg": float(heading[t]), "step": int(s),
                         "x": float(path[t, s, 0]), "y": float(path[t, s, 1]), "outcome": name})
    return rows


def success_summary(rows: list[dict]) -> dict:
    """Headline numbers of one success-rate table: % per distance and overall."""
    placed = sum(r["placed"] for r in rows)
    return {"success_pct_by_distance": {f"{r['distance_cm']:g}": r["success_pct"] for r in rows},
            "overall_success_pct": 100.0 * sum(r["successes"] for r in rows) / max(placed, 1),
            "min_success_pct": float(np.nanmin([r["success_pct"] for r in rows]))}


class Homing:
    """Runs of one study: shared options, result caches (so no program runs twice) and the writers."""

    def __init__(self, study: Study, spacing: float, trials: int, seed: int):
        self.study, self.spacing, self.trials, self.seed = study, spacing, trials, seed
        self.envs = {name: delvjax.load_env(name).arrays() for name in ENVS}  # neutral names: one compile per shape
        self.catchments: dict = {}
        self.tables: dict = {}

    def catchment(self, env: str, method: str):
        if (env, method) not in self.catchments:
            c = delvjax.catchment(self.envs[env], method=method, spacing=self.spacing, seed=self.seed,
                                  home_radius=HOME_RADIUS)
            self.catchments[env, method] = c
            s = catchment_summary(c)
            row = s["per_mask"][0]
            summary = {"catchment_pct": row["catchment_pct"],
                       "thesis_catchment_pct": THESIS_CATCHMENT.get(method, {}).get(env), "points": s["points"],
                       "mean_steps_success": row["mean_steps_success"],
                       **{f"{o}_count": row[f"{o}_count"] for o in OUTCOMES}}
            self.study.summary.setdefault("catchment", {}).setdefault(env, {})[method] = summary
            write_csv(self.study.path(f"maps/catchment_{method}_{env}.csv"), catchment_columns(c))
            t = summary["thesis_catchment_pct"]
            self.study.step(f"  {env} {method:13s} catchment {summary['catchment_pct']:6.2f} %"
                            + (f"   thesis {t:6.2f} %" if t is not None else "")
                            + "   failures: " + ", ".join(f"{o} {row[f'{o}_count']}" for o in OUTCOMES[1:]))
        return self.catchments[env, method]

    def success(self, label: str, method: str, **options) -> list[dict]:
        """Success rate vs release distance on env1 (`trials` per bin, 50..450 cm); same shape for every call."""
        if label not in self.tables:
            res = delvjax.success_rate(self.envs["env1"], method=method, trials=self.trials, seed=self.seed,
                                       home_radius=HOME_RADIUS, **options)
            self.tables[label] = res.table()
            s = success_summary(self.tables[label])
            self.study.summary.setdefault("success_rate_env1", {})[label] = s
            pct = s["success_pct_by_distance"].values()
            self.study.step(f"  success {label:26s} " + " ".join(f"{v:5.1f}" for v in pct)
                            + f"   overall {s['overall_success_pct']:5.1f} %")
        return self.tables[label]

    def success_figure(self, labels: dict[str, str], name: str, title: str) -> None:
        """labels: {table label: legend label}."""
        tables = {shown: self.tables[label] for label, shown in labels.items()}
        save_figure(success_rate_figure(tables, title), self.study.path(f"{name}.png"))
        self.study.rows(f"{name}.csv", [{"label": label, **r} for label, rows in tables.items() for r in rows])

    def trajectories(self, methods: list[str], name: str, title: str) -> None:
        """Paths of `methods` from the same N_STARTS seeded release points on env1 (same seed = same points)."""
        env = self.envs["env1"]
        results, rows = {}, []
        for m in methods:  # a few methods, one program each
            results[LABEL[m]] = delvjax.trajectories(env, method=m, n_starts=N_STARTS, seed=self.seed,
                                                     home_radius=HOME_RADIUS)
            rows += trajectory_rows(m, results[LABEL[m]])
        fig = trajectories_figure(env, results, HOME_RADIUS, title)
        save_figure(fig, self.study.path(f"{name}.png"))
        self.study.rows(f"{name}.csv", rows)
        counts = {LABEL[m]: int((np.asarray(t.outcome) == SUCCESS).sum()) for m, t in zip(methods, results.values())}
        self.study.summary.setdefault("trajectories_env1", {})[name] = {"starts": N_STARTS, "reach_home": counts}
        self.study.step(f"  {name}: reach home " + ", ".join(f"{k} {v}/{N_STARTS}" for k, v in counts.items()))


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results/homing")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--trials", type=int, default=100, help="rollouts per release distance (success rates)")
    p.add_argument("--quick", action="store_true", help="smoke run: spacing 50, 20 trials")
    a = p.parse_args(argv)
    if a.quick:
        a.spacing, a.trials = 50.0, 20
    study = Study(a.out, "homing")
    study.summary["options"] = {"seed": a.seed, "spacing": a.spacing, "trials": a.trials, "quick": a.quick,
                                "home_radius": HOME_RADIUS, "max_steps": 50, "trajectory_starts": N_STARTS}
    study.summary["thesis_claims"] = THESIS_CLAIMS
    h = Homing(study, a.spacing, a.trials, a.seed)

    # Fig 4.5 / 5.5: catchment maps, env1-3, DELV without and with compass.
    for method, fig, title in (("delv", "fig4_5", "DELV without compass: catchment area (Fig 4.5)"),
                               ("delv-compass", "fig5_5", "DELV with compass: catchment area (Fig 5.5)")):
        study.step(f"{fig}: catchment of {method} on env1-3")
        items = []
        for env in ENVS:  # three layouts; each call is one batched program
            c = h.catchment(env, method)
            s = study.summary["catchment"][env][method]
            items.append((f"{env}: {s['catchment_pct']:.2f} % (thesis {s['thesis_catchment_pct']:.2f} %)",
                          h.envs[env], c))
        save_figure(catchment_figure(items, a.spacing, title), study.path(f"{fig}_catchment_{method}.png"))
    study.rows("catchment_vs_thesis.csv", [{"env": env, "method": m, **study.summary["catchment"][env][m]}
                                           for m in THESIS_CATCHMENT for env in ENVS])

    # Fig 4.9-4.10: DELV vs predictive image matching on env1.
    study.step("fig4_9-4_10: DELV vs image matching (warping) on env1")
    env = h.envs["env1"]
    items, curves = [], {}
    for m in ("delv", "warping"):
        vm = as_vector_map(h.catchment("env1", m))  # per-point CSV: maps/catchment_{m}_env1.csv
        s = study.summary.setdefault("vector_map_env1", {})[m] = summarize_map(vm.error_deg, vm.valid, vm.included)
        curves[LABEL[m]] = error_curve(vm.error_deg, vm.points, env.home, vm.included)
        items.append((f"({'ab'[len(items)]}) {SHORT[m]}: mean error {s['mean_error_deg']:.1f}°, "
                      f"catchment {study.summary['catchment']['env1'][m]['catchment_pct']:.1f} %", env, vm))
        study.step(f"  {m:8s} vector map: mean error {s['mean_error_deg']:5.1f}°, e > 45: {s['gt45_pct']:5.1f} %, "
                   f"invalid {s['invalid']}")
    fig = panel_figure(items, a.spacing, classes=False)
    for ax in fig.axes:
        if ax.get_legend_handles_labels()[0]:  # invalid points (red x) only
            ax.legend(loc="upper right", fontsize=8, framealpha=0.9)
    fig.suptitle("Vector maps, env1, no compass, random headings (Fig 4.9)")
    fig.tight_layout()
    save_figure(fig, study.path("fig4_9_delv_vs_warping_maps.png"))
    save_figure(error_curve_figure(curves, "DELV vs image matching, env1, no compass (Fig 4.10a)"),
                study.path("fig4_10a_delv_vs_warping_errors.png"))
    curves_csv(study, "fig4_10a_delv_vs_warping_errors.csv", curves)
    for m in ("delv", "warping"):
        h.success(LABEL[m], m)
    h.success_figure({LABEL["delv"]: LABEL["delv"], LABEL["warping"]: LABEL["warping"]}, "fig4_10b_delv_vs_warping_success",
                     f"Success rate, env1, no compass ({a.trials} trials per distance; Fig 4.10b)")

    # Fig 4.13b: quantization levels (one compiled program for every Q) vs continuous and warping.
    study.step("fig4_13b: success rate of quantized DELV on env1")
    for q in (1, 2, 5):
        h.success(f"DELV Q = {q}", "delv", levels=q)
    h.success_figure({**{f"DELV Q = {q}": f"DELV, {q} level{'s' * (q > 1)}" for q in (1, 2, 5)},
                      LABEL["delv"]: "DELV, continuous", LABEL["warping"]: LABEL["warping"]},
                     "fig4_13b_quantization_success",
                     f"Success rate, quantized DELV and image matching, env1 ({a.trials} trials per distance; Fig 4.13b)")

    # Fig 5.7b: with a compass.
    study.step("fig5_7b: success rate of DELV (compass), ACV, ALV on env1")
    for m in ("delv-compass", "acv", "alv"):
        h.success(LABEL[m], m)
    h.success_figure({LABEL[m]: LABEL[m] for m in ("delv-compass", "acv", "alv")}, "fig5_7b_compass_success",
                     f"Success rate with a compass, env1 ({a.trials} trials per distance; Fig 5.7b)")

    # Fig 4.11 / 5.8: trajectories from the same release points.
    study.step("fig4_11 / fig5_8: trajectories on env1")
    h.trajectories(["delv", "warping"], "fig4_11_trajectories_delv_vs_warping",
                   "Same release points (black stars), no compass, env1 (Fig 4.11)")
    h.trajectories(["delv-compass", "acv", "alv"], "fig5_8_trajectories_compass",
                   "Same release points (black stars), with a compass, env1 (Fig 5.8)")

    catch = study.summary["catchment"]
    study.summary["headline"] = {
        "catchment_pct_ours_vs_thesis": {m: {env: [catch[env][m]["catchment_pct"], THESIS_CATCHMENT[m][env]]
                                             for env in ENVS} for m in THESIS_CATCHMENT},
        "env1_mean_error_deg": {m: s["mean_error_deg"] for m, s in study.summary["vector_map_env1"].items()},
        "env1_catchment_pct": {m: catch["env1"][m]["catchment_pct"] for m in ("delv", "delv-compass", "warping")},
        "env1_overall_success_pct": {k: s["overall_success_pct"] for k, s in study.summary["success_rate_env1"].items()},
    }
    study.step("catchment ours (thesis) %:")
    for m in THESIS_CATCHMENT:
        study.step(f"  {m:13s} " + "  ".join(f"{env} {catch[env][m]['catchment_pct']:6.2f} "
                                             f"({THESIS_CATCHMENT[m][env]:.2f})" for env in ENVS))
    study.finish()


if __name__ == "__main__":
    main()
