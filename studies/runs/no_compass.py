"""DELV without a compass on environments 1-3 (thesis §4.2, Figs 4.2-4.5).

Vector maps (Fig 4.2), error classes (Fig 4.3), mean angular error vs distance from home
with 95 % t intervals (Fig 4.4) and catchment areas (Fig 4.5), under the default rollout
rules and the physical ones. The vector maps are the catchments' own first directions.
"""

from __future__ import annotations

from delvjax.plots import error_curve_figure

from .. import thesis
from ._common import (
    RULES_NOTE,
    as_vector_map,
    catchment_columns,
    catchment_figure,
    catchments,
    curve,
    curve_number,
    curves_rows,
    env,
    map_numbers,
    panel_figure,
)

TITLE = "DELV without a compass, environments 1-3 (Figs 4.2-4.5)"
COST = 25  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 3
ENVS = ("env1", "env2", "env3")


def run(ctx) -> None:
    spacing = ctx.config.spacing
    items, curves, catch_items, rows = [], {}, [], []
    for name in ENVS:  # three layouts; every call reuses one compiled program
        e = env(name)
        res = catchments(ctx, e, "delv")
        ctx.step(f"catchment {name}")
        vm = as_vector_map(res["default"])
        s = map_numbers(e, vm)
        curves[name] = curve(e, vm)
        for key in ("mean_error_deg", "gt45_pct", "gt90_pct", "gt45_inside_hull_pct", "gt45_outside_hull_pct"):
            ctx.number(f"map:{name}:delv:{key}", s[key])
        for region in ("inside", "outside"):  # the points behind each share (the claims' one-point rule)
            ctx.number(f"n:map:{name}:delv:gt45_{region}_hull_pct", [s[f"n_{region}_hull"]])
        curve_number(ctx, f"error_curve:{name}:delv", curves[name])
        thesis_pct = thesis.CATCHMENT["fig4_5"][name]["delv"][0]
        row = {"env": name, "thesis %": thesis_pct}
        catchment_columns(ctx, f"catchment:{name}:delv", res, row)
        row.update(
            {
                "points": int(s["points"]),
                "mean error °": s["mean_error_deg"],
                "e>45 %": s["gt45_pct"],
                "e>45 inside hull %": s["gt45_inside_hull_pct"],
                "e>45 outside hull %": s["gt45_outside_hull_pct"],
            }
        )
        rows.append(row)
        items.append((f"{name}: mean error {s['mean_error_deg']:.1f}°, e>45 {s['gt45_pct']:.1f} %", e, vm))
        catch_items.append((f"{name}: {row['ours default %']:.2f} % (thesis {thesis_pct:.2f} %)", e, res["default"]))
    ctx.table(
        "catchment_fig4_5",
        "Catchment area and errors of DELV without compass",
        rows,
        source="Fig 4.5, §4.2",
        note=RULES_NOTE,
    )
    ctx.figure(
        "fig4_2_vector_maps.png",
        panel_figure(items, spacing, title="DELV without compass, random headings"),
        "Fig 4.2: homing vectors of DELV without compass on env1-3 (release heading random per point).",
    )
    ctx.figure(
        "fig4_3_error_classes.png",
        panel_figure(items, spacing, classes=True, title="DELV without compass: angular error classes"),
        "Fig 4.3: grid points with angular error 45-90° (stars) and > 90° (triangles).",
    )
    ctx.figure(
        "fig4_4_error_curves.png",
        error_curve_figure(curves, "DELV without compass (Fig 4.4)"),
        "Fig 4.4: mean angular error vs distance from home, 95 % Student-t intervals.",
    )
    ctx.csv("fig4_4_error_curves.csv", rows=curves_rows(curves))
    ctx.figure(
        "fig4_5_catchment.png",
        catchment_figure(catch_items, "DELV without compass: catchment area"),
        "Fig 4.5: release points from which DELV without compass reaches home (default rules).",
    )
