"""DELV vs ACV vs ALV with a compass (thesis §5.3, Figs 5.6-5.8).

Vector maps on env1-3 (Fig 5.6), error curves (Fig 5.7a), success rate vs release
distance under the default and the physical rules (Fig 5.7b) and trajectories from the
same release points (Fig 5.8) on env1.
"""

from __future__ import annotations

from delvjax.plots import error_curve_figure

from ._common import (
    LABEL,
    RULES,
    curve,
    curve_number,
    curves_rows,
    env,
    map_numbers,
    panel_figure,
    success_set,
    trajectory_set,
    vector_map,
)

TITLE = "DELV vs ACV vs ALV with a compass (Figs 5.6-5.8)"
COST = 6  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
METHODS = ("delv-compass", "acv", "alv")
ENVS = ("env1", "env2", "env3")
STEPS = len(ENVS) + len(METHODS) * len(RULES)  # the maps of each environment, then env1's success rates per rule set
N_STARTS = 8


def run(ctx) -> None:
    spacing = ctx.config.spacing
    rows = []
    for name in ENVS:  # three layouts x three methods, three compiled programs
        e = env(name)
        items, curves = [], {}
        for m in METHODS:
            vm = vector_map(ctx, e, m)
            s = map_numbers(e, vm)
            curves[LABEL[m]] = curve(e, vm)
            curve_number(ctx, f"error_curve:{name}:{m}", curves[LABEL[m]])
            ctx.number(f"map:{name}:{m}:mean_error_deg", s["mean_error_deg"])
            ctx.number(f"map:{name}:{m}:gt45_pct", s["gt45_pct"])
            rows.append(
                {
                    "env": name,
                    "method": LABEL[m],
                    "mean error °": s["mean_error_deg"],
                    "e>45 %": s["gt45_pct"],
                    "e>90 %": s["gt90_pct"],
                    "invalid points": s["invalid"],
                }
            )
            items.append((f"{LABEL[m]}: mean error {s['mean_error_deg']:.1f}°", e, vm))
        ctx.figure(
            f"fig5_6_vector_maps_{name}.png",
            panel_figure(items, spacing, classes=True, title=f"With a compass, {name}"),
            f"Fig 5.6: homing vectors of DELV, ACV and ALV with a compass on {name}, error classes marked.",
        )
        ctx.figure(
            f"fig5_7a_error_curves_{name}.png",
            error_curve_figure(curves, f"With a compass, {name} (Fig 5.7a)"),
            f"Fig 5.7a: mean angular error vs distance from home on {name} (95 % t intervals).",
        )
        ctx.csv(f"fig5_7a_error_curves_{name}.csv", rows=curves_rows(curves))
        ctx.step(name)
    ctx.table("vector_maps", "Vector-map errors with a compass", rows, source="Figs 5.6-5.7a")
    e = env("env1")
    success_set(
        ctx,
        e,
        METHODS,
        "fig5_7b_success_rate",
        "env1, with a compass",
        "Fig 5.7b: success rate vs release distance, 95 % Wilson intervals; default and physical rules.",
        source="Fig 5.7b",
        note="The thesis prints no numbers for this figure.",
    )
    trajectory_set(
        ctx,
        e,
        METHODS,
        "fig5_8_trajectories",
        "Same release points, with a compass, env1 (Fig 5.8)",
        f"Fig 5.8: homing paths of DELV, ACV and ALV from the same {N_STARTS} seeded release points.",
        N_STARTS,
    )
