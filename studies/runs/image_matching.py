"""DELV vs predictive image matching, no compass, environment 1 (thesis §4.2, Figs 4.9-4.11).

Vector maps (Fig 4.9), error curves (Fig 4.10a), success rate vs release distance
(Fig 4.10b), trajectories from the same release points (Fig 4.11), and the catchments
with their failures inside and outside the landmarks' convex hull; rollouts under the
default and the physical rules. A full run adds MinWarping (docs/model.md §4.7) on env1's
panoramas (docs/images.md §10) to the vector maps, error curves and trajectories.
"""

from __future__ import annotations

import numpy as np

import delvjax
from delvjax import Grid
from delvjax.plots import error_curve_figure

from ._common import (
    LABEL,
    RULES,
    as_vector_map,
    catchments,
    curve,
    curve_number,
    curves_rows,
    env,
    hull_failures,
    inside_hull,
    map_numbers,
    outcome_counts,
    panel_figure,
    rule_suffix,
    success_set,
    trajectory_set,
)
from ._images_common import preview

TITLE = "DELV vs predictive image matching, no compass (Figs 4.9-4.11)"
COST = 90  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
METHODS = ("delv", "warping")
# per method and rule set a catchment and a success-rate table, then MinWarping's map (a preview: a
# step that says it is the full run's) and the trajectories
STEPS = 2 * len(METHODS) * len(RULES) + 2
N_STARTS = 8
# MinWarping on env1's rendered panoramas (docs/images.md §10) in the authors' configuration: 288-column
# panoramas, 96 x 96 hypotheses (minwarping.AUTHORS_GRID). Full run only: its vector map of the full grid
# takes about 30 s on 2 cores (at 360 columns and 90 x 90, 75 s, and 4.57° against 4.51° mean error at
# spacing 50), a catchment of the full grid minutes, so no rollouts but trajectories.
SCENE_MINWARPING = {"n_pix": 288, "n_alpha": 96, "n_psi": 96}


def run(ctx) -> None:
    e = env("env1")
    spacing = ctx.config.spacing
    items, curves, rows = [], {}, []
    for m in METHODS:  # two methods: two programs
        for rules, c in catchments(ctx, e, m).items():
            pct = float(c.catchment_pct()[0])
            suffix = rule_suffix(rules)
            ctx.number(f"catchment:env1:{m}{suffix}", pct)
            f = hull_failures(c, inside_hull(e, np.asarray(c.points)))  # over the counted points
            fail_in, fail_out = f["inside"], f["outside"]
            for region in ("inside", "outside"):
                ctx.number(f"fail_{region}_hull:env1:{m}{suffix}", f[region])
                ctx.number(f"n:fail_{region}_hull:env1:{m}{suffix}", [f[f"n_{region}"]])  # the sample behind it
            if rules == "default":
                vm = as_vector_map(c)
                s = map_numbers(e, vm)
                curves[LABEL[m]] = curve(e, vm)
                curve_number(ctx, f"error_curve:env1:{m}", curves[LABEL[m]])
                ctx.number(f"map:env1:{m}:mean_error_deg", s["mean_error_deg"])
                items.append((f"{LABEL[m]}: mean error {s['mean_error_deg']:.1f}°, catchment {pct:.1f} %", e, vm))
            counts = outcome_counts(c)
            rows.append(
                {
                    "method": LABEL[m],
                    "rules": rules,
                    "catchment %": pct,
                    "failures timeout/landmark/arena": f"{counts['timeout']}/{counts['landmark']}/{counts['arena']}",
                    "fail inside hull %": fail_in,
                    "fail outside hull %": fail_out,
                    "mean error °": s["mean_error_deg"],
                }
            )
            ctx.step(f"catchment {m} {rules}")
    own = {}
    if preview(ctx):
        ctx.step("MinWarping: full run only")
    else:
        own["minwarping"] = SCENE_MINWARPING
        vm = delvjax.vector_map(
            e, method="minwarping", seed=ctx.config.seed, grid=Grid(spacing=spacing), **SCENE_MINWARPING
        )
        s = map_numbers(e, vm)
        curves[LABEL["minwarping"]] = curves_mw = curve(e, vm)
        curve_number(ctx, "error_curve:env1:minwarping", curves_mw)
        ctx.number("map:env1:minwarping:mean_error_deg", s["mean_error_deg"])
        items.append((f"{LABEL['minwarping']}: mean error {s['mean_error_deg']:.1f}°", e, vm))
        rows.append(
            {
                "method": LABEL["minwarping"],
                "rules": "(vector map only)",
                "catchment %": "not run (minutes)",
                "failures timeout/landmark/arena": "",
                "fail inside hull %": "",
                "fail outside hull %": "",
                "mean error °": s["mean_error_deg"],
            }
        )
        ctx.step("vector map minwarping")
    ctx.table(
        "catchment_delv_vs_warping",
        "Catchment and failures by region, env1",
        rows,
        source="Figs 4.9-4.11",
        note="The thesis prints no numbers for these figures. Hull: the convex hull of the landmark centres. "
        "MinWarping (full run only; docs/images.md §10): its vector map on 288-column panoramas with the "
        "authors' 96 x 96 hypotheses; a catchment of this grid takes minutes on 2 cores "
        "(`delvjax catchment env1 --method minwarping --n-pix 288`).",
    )
    ctx.figure(
        "fig4_9_vector_maps.png",
        panel_figure(items, spacing, title="env1, no compass, random headings"),
        "Fig 4.9: homing vectors of DELV (a) and predictive image matching (b); MinWarping (c) in a full run.",
    )
    ctx.figure(
        "fig4_10a_error_curves.png",
        error_curve_figure(curves, "DELV vs image matching, env1 (Fig 4.10a)"),
        "Fig 4.10a: mean angular error vs distance from home (95 % t intervals).",
    )
    ctx.csv("fig4_10a_error_curves.csv", rows=curves_rows(curves))
    success_set(
        ctx,
        e,
        METHODS,
        "fig4_10b_success_rate",
        "env1, no compass",
        "Fig 4.10b: success rate vs release distance, 95 % Wilson intervals; default and physical rules.",
        source="Fig 4.10b",
        note="The thesis: DELV > 90 % at every distance (§4.2).",
    )
    trajectory_set(
        ctx,
        e,
        METHODS + tuple(own),
        "fig4_11_trajectories",
        "Same release points, no compass, env1 (Fig 4.11)",
        f"Fig 4.11: homing paths of DELV and image matching (and MinWarping in a full run) from the same "
        f"{N_STARTS} seeded release points.",
        N_STARTS,
        own=own,
    )
    ctx.step("trajectories")
