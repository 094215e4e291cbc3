"""DELV with a compass on environments 1-3 (thesis §5.2, Figs 5.2-5.5).

With the compass only the cyclic shift k is searched (alpha is the compass reading):
vector maps (Figs 5.2-5.3), error curves beside DELV without compass (Fig 5.4) and
catchment areas (Fig 5.5), under the default and the physical rollout rules.
"""

from __future__ import annotations

from delvjax.plots import error_curve_figure
from studies import thesis

from .common import (RULES, RULES_NOTE, as_vector_map, catchment, catchment_columns, catchment_figure, curve, curve_means, curves_rows, env, map_numbers,
                     panel_figure, vector_map)

TITLE = "DELV with a compass, environments 1-3 (Figs 5.2-5.5)"
STEPS = 3
ENVS = ("env1", "env2", "env3")


def run(ctx) -> None:
    spacing = ctx.settings.spacing
    items, curves, catch_items, rows = [], {}, [], []
    for name in ENVS:  # three layouts, one compiled program
        e = env(name)
        res = {rules: catchment(ctx, e, "delv-compass", rules) for rules in RULES}
        vm = as_vector_map(res["default"])
        s = map_numbers(e, vm)
        no_compass = map_numbers(e, vector_map(ctx, e, "delv"))
        curves[f"{name} with compass"] = curve(e, vm)
        ctx.number(f"map:{name}:delv-compass:mean_error_deg", s["mean_error_deg"])
        ctx.number(f"error_curve:{name}:delv-compass", curve_means(curves[f"{name} with compass"]))
        thesis_pct = thesis.CATCHMENT["fig5_5"][name]["delv-compass"][0]
        row = {"env": name, "thesis with compass %": thesis_pct,
               "thesis without compass % (Fig 4.5)": thesis.CATCHMENT["fig4_5"][name]["delv"][0]}
        catchment_columns(ctx, f"catchment:{name}:delv-compass", res, row)
        row.update({"mean error ° (compass)": s["mean_error_deg"], "mean error ° (no compass)":
                    no_compass["mean_error_deg"], "e>45 %": s["gt45_pct"]})
        rows.append(row)
        items.append((f"{name}: mean error {s['mean_error_deg']:.1f}°, e>45 {s['gt45_pct']:.1f} %", e, vm))
        catch_items.append((f"{name}: {row['ours default %']:.2f} % (thesis {thesis_pct:.2f} %)", e, res["default"]))
        ctx.step(name)
    ctx.table("catchment_fig5_5", "Catchment area and errors of DELV with a compass", rows, source="Fig 5.5, §5.2",
              note=RULES_NOTE)
    ctx.figure("fig5_2_vector_maps.png", panel_figure(items, spacing, classes=True, title="DELV with a compass"),
               "Figs 5.2-5.3: homing vectors of DELV with a compass, error classes marked.")
    ctx.figure("fig5_4_error_curves.png", error_curve_figure(curves, "DELV with a compass (Fig 5.4)"),
               "Fig 5.4: mean angular error vs distance from home (95 % t intervals).")
    ctx.csv("fig5_4_error_curves.csv", rows=curves_rows(curves))
    ctx.figure("fig5_5_catchment.png", catchment_figure(catch_items, spacing, "DELV with a compass: catchment area"),
               "Fig 5.5: release points from which DELV with a compass reaches home (default rules).")
