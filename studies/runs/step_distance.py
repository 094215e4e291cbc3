"""Step distance d of the unit movement (thesis §4.2, Figs 4.6-4.7).

DELV without compass on env1 for d in {20, 50, 100, 150} cm. d is a traced leaf of the
method's settings, so all four values run through the one compiled rollout program that
every other study of DELV uses (no compilation per value); each vector map is read from a
catchment run (`runs._common.vector_map`), which also gives the catchment per d.
"""

from __future__ import annotations

from delvjax.plots import error_curve_figure

from ._common import (
    FAILURES,
    HOME_RADIUS,
    as_vector_map,
    catchment,
    curve,
    curve_number,
    curves_rows,
    env,
    failures_text,
    map_numbers,
    outcome_counts,
    panel_figure,
    record_failures,
)

TITLE = "Step distance d of the unit movement (Figs 4.6-4.7)"
COST = 4  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 1
DS = (20.0, 50.0, 100.0, 150.0)
WIDE_RADIUS = 0.5 * DS[-1]  # the longest d again with a home radius of half the step (75 cm)


def run(ctx) -> None:
    e = env("env1")
    items, curves, rows = [], {}, []
    for d in DS:  # four values through one compiled program
        c = catchment(ctx, e, "delv", d=d)
        vm = as_vector_map(c)
        s = map_numbers(e, vm)
        pct = float(c.catchment_pct()[0])
        ctx.number(f"catchment:env1:delv:d={d:g}", pct)
        curves[f"d = {d:g} cm"] = curve(e, vm)
        curve_number(ctx, f"error_curve:env1:delv:d={d:g}", curves[f"d = {d:g} cm"])
        ctx.number(f"map:env1:delv:d={d:g}:mean_error_deg", s["mean_error_deg"])
        fails = {k: v for k, v in outcome_counts(c).items() if k in FAILURES}
        record_failures(ctx, f"catchment_failures:env1:delv:d={d:g}", fails)
        rows.append(
            {
                "d cm": d,
                "mean error °": s["mean_error_deg"],
                "e>45 %": s["gt45_pct"],
                "e>90 %": s["gt90_pct"],
                "invalid points": s["invalid"],
                "catchment %": pct,
                "failures timeout/landmark/arena": failures_text(fails),
            }
        )
        items.append((f"d = {d:g} cm: mean error {s['mean_error_deg']:.1f}°", e, vm))
    # the longest step with a home radius of half the step: is a step that jumps over the home disc the loss?
    wide = catchment(ctx, e, "delv", d=DS[-1], home_radius=WIDE_RADIUS)
    ctx.number(f"catchment:env1:delv:d={DS[-1]:g}:home_radius={WIDE_RADIUS:g}", float(wide.catchment_pct()[0]))
    ctx.number("step_distance:home_radius_cm", HOME_RADIUS)
    ctx.step("four values of d")
    ctx.table(
        "step_distance",
        "DELV without compass on env1 by step distance d",
        rows,
        source="Figs 4.6-4.7",
        note="The thesis prints no numbers for these figures; its claim is that d rarely matters (§4.2). Failures: "
        "grid points whose rollout times out, ends inside a landmark or leaves the arena (default rules). "
        "A step longer than twice the home radius (50 cm) can jump over the home disc: the run repeats "
        f"d = {DS[-1]:g} cm with a home radius of {WIDE_RADIUS:g} cm (number "
        f"catchment:env1:delv:d={DS[-1]:g}:home_radius={WIDE_RADIUS:g}).",
    )
    ctx.figure(
        "fig4_6_step_distance_maps.png",
        panel_figure(items, ctx.config.spacing, title="DELV without compass on env1, step distance d"),
        "Fig 4.6: homing vectors of DELV without compass for d = 20, 50, 100, 150 cm.",
    )
    ctx.figure(
        "fig4_7_step_distance_errors.png",
        error_curve_figure(curves, "DELV, step distance d (Fig 4.7)"),
        "Fig 4.7: mean angular error vs distance from home for each d (95 % t intervals).",
    )
    ctx.csv("fig4_7_step_distance_errors.csv", rows=curves_rows(curves))
