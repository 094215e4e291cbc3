"""Number of landmarks in arbitrary layouts (thesis §4.2, Fig 4.8).

DELV without compass in seeded random layouts of 3, 4 and 5 landmarks (padded to one
shape: one compiled program), vector maps and error curves; image matching on the same layouts
(§4.1: it is "extremely sensitive to ... the number of landmarks").
"""

from __future__ import annotations

from delvjax.envs import random_env
from delvjax.plots import error_curve_figure

from ._common import PAD, curve, curve_means, curve_number, curves_rows, map_numbers, panel_figure, vector_map

TITLE = "Number of landmarks, arbitrary layouts (Fig 4.8)"
COST = 16  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 3
COUNTS = (3, 4, 5)


def run(ctx) -> None:
    items, curves, rows = [], {}, []
    for n in COUNTS:  # three layouts, one compiled program
        e = random_env(100 + n, n, pad_to=PAD)
        vm = vector_map(ctx, e, "delv")
        s = map_numbers(e, vm)
        label = f"{n} landmarks"
        curves[label] = curve(e, vm)
        curve_number(ctx, f"error_curve:random{n}:delv", curves[label])
        w = vector_map(ctx, e, "warping")
        sw = map_numbers(e, w)
        curve_number(ctx, f"error_curve:random{n}:warping", curve(e, w))
        rows.append(
            {
                "landmarks": n,
                "layout seed": 100 + n,
                "mean error °": s["mean_error_deg"],
                "e>45 %": s["gt45_pct"],
                "e>90 %": s["gt90_pct"],
                "largest bin mean error °": max(curve_means(curves[label])),
                "image matching mean error °": sw["mean_error_deg"],
                "image matching e>45 %": sw["gt45_pct"],
            }
        )
        items.append((f"{n} landmarks (layout seed {100 + n}): mean error {s['mean_error_deg']:.1f}°", e, vm))
        ctx.step(label)
    ctx.table(
        "landmark_number",
        "DELV without compass (and image matching) in arbitrary layouts",
        rows,
        source="Fig 4.8, §4.1",
        note="Layouts are seeded random (delvjax.envs.random_env); the thesis's are not given.",
    )
    ctx.figure(
        "fig4_8_landmark_numbers.png",
        panel_figure(items, ctx.config.spacing, title="DELV without compass, arbitrary layouts"),
        "Fig 4.8a-e: homing vectors of DELV without compass with 3, 4 and 5 landmarks.",
    )
    ctx.figure(
        "fig4_8f_landmark_number_errors.png",
        error_curve_figure(curves, "DELV, landmark numbers (Fig 4.8f)"),
        "Fig 4.8f: mean angular error vs distance from home (95 % t intervals).",
    )
    ctx.csv("fig4_8f_landmark_number_errors.csv", rows=curves_rows(curves))
