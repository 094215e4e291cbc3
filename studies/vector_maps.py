"""Vector-map studies of thesis chapters 4-5 on the built-in environments.

Fig 4.2-4.4  DELV without compass on env1-3: vector maps, error classes, error curves.
Fig 4.6-4.7  step distance d in {20, 50, 100, 150} (one vmapped sweep over d).
Fig 4.8      3-5 landmarks in arbitrary (seeded random) layouts.
Fig 4.12-4.13a  quantization levels 1-5 and continuous (one vmapped sweep over Q).
Fig 5.2-5.4, 5.6  DELV with compass vs ACV vs ALV; Table 5.1/5.2 error point rates (k = 0).
Fig 5.11     the visual-compass variants.

Run: python -m studies.vector_maps --out results/vector_maps [--spacing 25] [--seed 0]
Every figure has its numbers beside it as CSV; the headline numbers go to vector_maps.json.
"""

from __future__ import annotations

import argparse

import jax.numpy as jnp
import matplotlib.pyplot as plt
import numpy as np

import delvjax
from delvjax import maps
from delvjax.config import Config
from delvjax.io import save_figure, write_csv
from delvjax.metrics import error_curve, summarize_map
from delvjax.plots import draw_env, draw_vector_map, error_curve_figure
from delvjax.scene import random_env

from .common import Study, take

ENVS = ("env1", "env2", "env3")
# Thesis Table 5.1 (error point rate e > 45 %, environment 1, no occlusion), SPEC §6.
THESIS_GT45_ENV1 = {"delv-compass": 8.75, "acv": 9.80, "alv": 0.00}


def panel_figure(items, spacing: float, classes: bool):
    """1 x n panels: items = [(title, env, VectorMap)]."""
    fig, axes = plt.subplots(1, len(items), figsize=(4.6 * len(items), 4.8))
    for ax, (title, env, vm) in zip(np.atleast_1d(axes), items):
        draw_vector_map(ax, env, vm.points, vm.direction, vm.valid, vm.included, spacing,
                        error_deg=vm.error_deg if classes else None)
        draw_env(ax, env)
        ax.set_title(title, fontsize=10)
    if classes:
        np.atleast_1d(axes)[-1].legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    return fig


def record(study: Study, key: str, env, vm, spacing: float) -> list[dict]:
    """Summary numbers, per-point CSV and error curve of one map; returns the curve rows."""
    study.summary[key] = summarize_map(vm.error_deg, vm.valid, vm.included)
    write_csv(study.path(f"maps/{key}.csv"), maps.vector_map_columns(vm))
    return error_curve(vm.error_deg, vm.points, env.home, vm.included)


def curves_csv(study: Study, name: str, curves: dict[str, list[dict]]) -> None:
    study.rows(name, [{"label": label, **row} for label, rows in curves.items() for row in rows])


def figure_set(study: Study, items, curves, spacing: float, maps_png: str, curves_name: str, title: str) -> None:
    """Vector-map panels, the error-curve figure and its CSV of one figure set."""
    save_figure(panel_figure(items, spacing, classes=False), study.path(maps_png))
    save_figure(error_curve_figure(curves, title), study.path(f"{curves_name}.png"))
    curves_csv(study, f"{curves_name}.csv", curves)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results/vector_maps")
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args(argv)
    study = Study(a.out, "vector_maps")
    kw = dict(spacing=a.spacing, seed=a.seed)

    # Fig 4.2-4.4: DELV, no compass, env1-3.
    study.step("Fig 4.2-4.4: DELV without compass on env1-3")
    items, curves = [], {}
    for name in ENVS:  # three environments of different layouts; each call is one batched program
        env = delvjax.load_env(name)
        vm = delvjax.vector_map(env, method="delv", **kw)
        curves[name] = record(study, f"delv_{name}", env, vm, a.spacing)
        items.append((f"{name}: mean {study.summary[f'delv_{name}']['mean_error_deg']:.1f}°", env, vm))
    figure_set(study, items, curves, a.spacing, "fig4_2_delv_vector_maps.png", "fig4_4_delv_error_curves",
               "DELV without compass (Fig 4.4)")
    save_figure(panel_figure(items, a.spacing, classes=True), study.path("fig4_3_delv_error_classes.png"))

    # Fig 4.6-4.7: step distance d, one vmapped sweep.
    study.step("Fig 4.6-4.7: step distance d in 20, 50, 100, 150 (one sweep)")
    env = delvjax.load_env("env1")
    ds = [20.0, 50.0, 100.0, 150.0]
    key = delvjax.api.resolve_headings(None, a.seed)[1]
    swept = maps.sweep(env, "delv", Config(), "d", jnp.asarray(ds), spacing=a.spacing, key=key)
    items, curves = [], {}
    for i, d in enumerate(ds):
        vm = take(swept, i)
        curves[f"d = {d:g}"] = record(study, f"delv_env1_d{d:g}", env, vm, a.spacing)
        items.append((f"d = {d:g} cm", env, vm))
    figure_set(study, items, curves, a.spacing, "fig4_6_step_distance_maps.png", "fig4_7_step_distance_errors",
               "DELV, step distance d (Fig 4.7)")

    # Fig 4.8: 3-5 landmarks in arbitrary layouts.
    study.step("Fig 4.8: 3-5 landmarks, seeded random layouts")
    items, curves = [], {}
    for n in (3, 4, 5):
        env = random_env(100 + n, n, pad_to=5)  # one padded shape: one compilation
        vm = delvjax.vector_map(env, method="delv", **kw)
        curves[f"{n} landmarks"] = record(study, f"delv_random_{n}", env, vm, a.spacing)
        items.append((f"{n} landmarks (seed {100 + n})", env, vm))
    figure_set(study, items, curves, a.spacing, "fig4_8_landmark_numbers.png", "fig4_8f_landmark_number_errors",
               "DELV, landmark numbers (Fig 4.8f)")

    # Fig 4.12-4.13a: quantization levels, one vmapped sweep over Q, plus continuous.
    study.step("Fig 4.12-4.13: quantization levels 1-5 (one sweep) and continuous")
    env = delvjax.load_env("env1")
    levels = [1, 2, 3, 4, 5]
    swept = maps.sweep(env, "delv", Config(levels=1), "levels", jnp.asarray(levels), spacing=a.spacing, key=key)
    items, curves = [], {}
    for i, q in enumerate(levels):
        vm = take(swept, i)
        curves[f"Q = {q}"] = record(study, f"delv_env1_Q{q}", env, vm, a.spacing)
        if q >= 3:
            items.append((f"level {q}", env, vm))
    vm = delvjax.vector_map(env, method="delv", **kw)
    curves["continuous"] = record(study, "delv_env1_continuous", env, vm, a.spacing)
    figure_set(study, items, curves, a.spacing, "fig4_12_quantized_maps.png", "fig4_13a_quantization_errors",
               "DELV, quantized distances (Fig 4.13a)")

    # Chapter 5: with a compass (and the visual compass).
    for tag, methods, fig in (("compass", ("delv-compass", "acv", "alv"), "fig5_6"),
                              ("visual", ("delv-visual", "acv-visual", "alv-visual"), "fig5_11")):
        study.step(f"Chapter 5: {', '.join(methods)} on env1-3")
        rates = []
        for name in ENVS:
            env = delvjax.load_env(name)
            items, curves = [], {}
            for m in methods:
                vm = delvjax.vector_map(env, method=m, **kw)
                curves[m] = record(study, f"{m}_{name}", env, vm, a.spacing)
                s = study.summary[f"{m}_{name}"]
                items.append((f"{m} on {name}: >45° {s['gt45_pct']:.1f} %", env, vm))
                thesis = THESIS_GT45_ENV1.get(m) if name == "env1" else None
                rates.append({"env": name, "method": m, "gt45_pct": s["gt45_pct"], "gt90_pct": s["gt90_pct"],
                              "invalid": s["invalid"], "thesis_gt45_pct": thesis})
            save_figure(panel_figure(items, a.spacing, classes=True), study.path(f"{fig}_{tag}_maps_{name}.png"))
            save_figure(error_curve_figure(curves, f"{tag} methods on {name}"), study.path(f"{fig}_{tag}_errors_{name}.png"))
            curves_csv(study, f"{fig}_{tag}_errors_{name}.csv", curves)
        study.rows(f"table5_1_error_point_rates_{tag}.csv", rates)
        for r in rates:
            if r["thesis_gt45_pct"] is not None:
                study.step(f"  {r['env']} {r['method']:13s} e>45: ours {r['gt45_pct']:5.2f} %  thesis {r['thesis_gt45_pct']:5.2f} %")
    study.finish()


if __name__ == "__main__":
    main()
