"""DELV with a compass on environments 1-3 (thesis §5.2, Figs 5.2-5.5).

With the compass only the cyclic shift k is searched (alpha is the compass reading):
vector maps (Figs 5.2-5.3), error curves beside DELV without compass (Fig 5.4) and
catchment areas (Fig 5.5), under the default and the physical rollout rules. Where the two
differ, the share of grid points at which DELV without compass picks a wrong heading (`heading_slips`)
says how much of the gap is heading estimation (claim "compass_slightly_smaller_error").
"""

from __future__ import annotations

import numpy as np

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
    vector_map,
)

TITLE = "DELV with a compass, environments 1-3 (Figs 5.2-5.5)"
COST = 5  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 3
ENVS = ("env1", "env2", "env3")


SLIP_DEG = 45.0  # degrees: DELV without compass this much worse than with it at a point: a wrong heading hypothesis


def heading_slips(with_compass, without) -> dict:
    """Where estimating the heading (§3.2.3) goes wrong: the share of grid points at which DELV without
    compass errs > SLIP_DEG more than with it (same points, seed and home record), and the mean error
    without compass at the other points."""
    inc = np.asarray(with_compass.included)
    a, b = np.asarray(with_compass.error_deg)[inc], np.asarray(without.error_deg)[inc]
    slip = b > a + SLIP_DEG
    return {
        "pct": 100.0 * float(slip.mean()),
        "mean_without_deg": float(b[~slip].mean()) if (~slip).any() else float("nan"),
    }


def run(ctx) -> None:
    spacing = ctx.config.spacing
    items, curves, catch_items, rows = [], {}, [], []
    for name in ENVS:  # three layouts, one compiled program
        e = env(name)
        res = catchments(ctx, e, "delv-compass")
        vm = as_vector_map(res["default"])
        s = map_numbers(e, vm)
        vm_free = vector_map(ctx, e, "delv")
        no_compass = map_numbers(e, vm_free)
        slips = heading_slips(vm, vm_free)
        ctx.number(f"map:{name}:delv:heading_slip_pct", slips["pct"])
        ctx.number(f"map:{name}:delv:mean_error_without_slips_deg", slips["mean_without_deg"])
        curves[f"{name} with compass"] = curve(e, vm)
        ctx.number(f"map:{name}:delv-compass:mean_error_deg", s["mean_error_deg"])
        curve_number(ctx, f"error_curve:{name}:delv-compass", curves[f"{name} with compass"])
        thesis_pct = thesis.CATCHMENT["fig5_5"][name]["delv-compass"][0]
        row = {
            "env": name,
            "thesis with compass %": thesis_pct,
            "thesis without compass % (Fig 4.5)": thesis.CATCHMENT["fig4_5"][name]["delv"][0],
        }
        catchment_columns(ctx, f"catchment:{name}:delv-compass", res, row)
        row.update(
            {
                "mean error ° (compass)": s["mean_error_deg"],
                "mean error ° (no compass)": no_compass["mean_error_deg"],
                "e>45 %": s["gt45_pct"],
                f"no compass > compass + {SLIP_DEG:g}° (% of points)": slips["pct"],
                "mean error ° (no compass, other points)": slips["mean_without_deg"],
            }
        )
        rows.append(row)
        items.append((f"{name}: mean error {s['mean_error_deg']:.1f}°, e>45 {s['gt45_pct']:.1f} %", e, vm))
        catch_items.append((f"{name}: {row['ours default %']:.2f} % (thesis {thesis_pct:.2f} %)", e, res["default"]))
        ctx.step(name)
    ctx.table(
        "catchment_fig5_5",
        "Catchment area and errors of DELV with a compass",
        rows,
        source="Fig 5.5, §5.2",
        note=RULES_NOTE + f" Without compass DELV also estimates its heading (§3.2.3): the share of grid points "
        f"where it errs more than {SLIP_DEG:g}° beyond DELV with a compass (a wrong heading hypothesis "
        "won) and its mean error at the other points.",
    )
    ctx.figure(
        "fig5_2_vector_maps.png",
        panel_figure(items, spacing, classes=True, title="DELV with a compass"),
        "Figs 5.2-5.3: homing vectors of DELV with a compass, error classes marked.",
    )
    ctx.figure(
        "fig5_4_error_curves.png",
        error_curve_figure(curves, "DELV with a compass (Fig 5.4)"),
        "Fig 5.4: mean angular error vs distance from home (95 % t intervals).",
    )
    ctx.csv("fig5_4_error_curves.csv", rows=curves_rows(curves))
    ctx.figure(
        "fig5_5_catchment.png",
        catchment_figure(catch_items, "DELV with a compass: catchment area"),
        "Fig 5.5: release points from which DELV with a compass reaches home (default rules).",
    )
