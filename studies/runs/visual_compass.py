"""The visual compass in place of the compass (thesis §5.3.2, Figs 5.11-5.12), and compass noise.

For each background setting (`distant`, `walls`, `none`; docs/model.md §2.3): the visual compass's
heading error at every grid point (release heading random per point), and the catchment
and mean angular error of DELV, ACV and ALV with the visual compass beside the true
compass, on env1, under the default and the physical rollout rules. Then a compass-noise
sweep (sigma 0-45 deg) of the catchment of DELV, ACV and ALV with the true compass: the
one compiled rollout program, the sigma being a traced leaf of the `Sensor` (`noise.compass`).
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from delvjax.plots._maps import subplots
import numpy as np

from delvjax.core.maps import grid_included, grid_points, random_headings
from delvjax.core.methods.heading import visual_compass_errors
from delvjax.options._settings import make_sensor
from .. import thesis

from ._common import as_vector_map, catchment, catchments, env, map_numbers, outcome_counts, rule_suffix, LABEL

TITLE = "The visual compass and compass noise (Figs 5.11-5.12)"
BACKGROUNDS = ("distant", "walls", "none")
TRUE = ("delv-compass", "acv", "alv")
VISUAL = ("delv-visual", "acv-visual", "alv-visual")
SIGMAS = (0.0, 5.0, 10.0, 20.0, 30.0, 45.0)
STEPS = len(BACKGROUNDS) * 2 + 2


def heading_error_stats(err_deg: np.ndarray) -> dict:
    a = np.abs(err_deg)
    return {
        "mean |error| °": float(a.mean()),
        "median |error| °": float(np.median(a)),
        "error > 5° %": 100.0 * float((a > 5).mean()),
        "error > 45° %": 100.0 * float((a > 45).mean()),
        "error > 90° %": 100.0 * float((a > 90).mean()),
    }


def run(ctx) -> None:
    e = env("env1")
    spacing = ctx.settings.spacing
    points = jnp.asarray(grid_points(e.arena, spacing))
    included = np.asarray(grid_included(e, points, 10.0))
    headings = random_headings(jax.random.PRNGKey(ctx.settings.seed), points.shape[0])  # the vector map's headings
    true = {}
    for m in TRUE:
        for rules, c in catchments(ctx, e, m).items():
            true[m, rules] = float(c.catchment_pct()[0])
            if rules == "default":
                true[m, "mean_error"] = map_numbers(e, as_vector_map(c))["mean_error_deg"]
        ctx.number(f"catchment:env1:{m}", true[m, "default"])
        ctx.number(f"map:env1:{m}:mean_error_deg", true[m, "mean_error"])
    ctx.step("true compass")
    errors, compass_rows, catch_rows = {}, [], []
    for bg in BACKGROUNDS:  # three settings of a traced leaf: one compiled program
        err = np.degrees(np.asarray(visual_compass_errors(e, points, headings, make_sensor(background=bg))))
        errors[bg] = err[included]
        stats = heading_error_stats(errors[bg])
        compass_rows.append({"background": bg, **stats})
        ctx.number(f"visual:{bg}:heading_error_mean_deg", stats["mean |error| °"])
        ctx.number(f"visual:{bg}:heading_error_gt5_pct", stats["error > 5° %"])
        ctx.step(f"heading errors {bg}")
        for tm, vm_name in zip(TRUE, VISUAL):
            row = {"background": bg, "method": LABEL[tm]}
            for rules, c in catchments(ctx, e, vm_name, background=bg).items():
                pct = float(c.catchment_pct()[0])
                counts = outcome_counts(c)
                row[f"visual {rules} %"] = pct
                row[f"visual {rules} failures timeout/landmark/arena"] = (
                    f"{counts['timeout']}/{counts['landmark']}/{counts['arena']}"
                )
                if rules == "default":
                    s = map_numbers(e, as_vector_map(c))
                    ctx.number(f"visual:{bg}:{tm}:mean_error_deg", s["mean_error_deg"])
                    row["visual mean error °"] = s["mean_error_deg"]
                ctx.number(f"visual:{bg}:{tm}:catchment" + rule_suffix(rules), pct)
            row.update(
                {
                    "true compass default %": true[tm, "default"],
                    "true compass physical %": true[tm, "physical"],
                    "true compass mean error °": true[tm, "mean_error"],
                    "thesis visual %": thesis.CATCHMENT.get("fig5_11", {}).get("env1", {}).get(vm_name, [None])[0],
                }
            )
            catch_rows.append(row)
        ctx.step(f"catchments {bg}")
    ctx.table(
        "visual_compass_heading_errors",
        "Heading error of the visual compass on the env1 grid",
        compass_rows,
        source="§5.3.2",
        note="The thesis: the visual compass 'does not guarantee 100% of accuracy'; "
        "it does not say which background it used.",
    )
    ctx.table(
        "visual_compass_catchment",
        "Catchment and mean error with the visual compass, env1",
        catch_rows,
        source="Figs 5.11-5.12",
        note="Thesis (Fig 5.11): DELV 74.85, ACV 47.04, ALV 40.68 %. "
        "default / physical: the rollout rules (docs/model.md §5).",
    )
    fig, axes = subplots(1, 3, figsize=(13, 3.8), sharey=True)
    for ax, bg in zip(axes, BACKGROUNDS):
        ax.hist(errors[bg], bins=np.arange(-180, 181, 5), color="C0")
        ax.set_title(f"background {bg}: mean |error| {np.abs(errors[bg]).mean():.1f}°", fontsize=9)
        ax.set_xlabel("visual compass heading error (°)")
        ax.set_yscale("log")
    axes[0].set_ylabel("grid points")
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    ctx.figure(
        "fig5_11_visual_compass_errors.png",
        fig,
        "Heading error of the visual compass at the env1 grid points (release heading random per point), "
        "per background setting; log scale.",
    )
    ctx.csv(
        "visual_compass_heading_errors_per_point.csv",
        columns={
            "background": np.repeat(BACKGROUNDS, [errors[b].size for b in BACKGROUNDS]).tolist(),
            "heading_error_deg": np.concatenate([errors[b] for b in BACKGROUNDS]),
        },
    )
    fig, ax = subplots(figsize=(7.5, 4.6))
    width = 0.13
    for i, (bg, hatch) in enumerate(zip((*BACKGROUNDS, "true compass"), ("", "//", "..", "xx"))):
        vals = [
            true[m, "default"]
            if bg == "true compass"
            else next(r["visual default %"] for r in catch_rows if r["background"] == bg and r["method"] == LABEL[m])
            for m in TRUE
        ]
        ax.bar(
            np.arange(3) + (i - 1.5) * width * 1.6,
            vals,
            width * 1.5,
            hatch=hatch,
            edgecolor="black",
            label=bg if bg == "true compass" else f"visual compass, background {bg}",
        )
    ax.plot(np.arange(3), [74.85, 47.04, 40.68], "k*", ms=12, label="thesis, visual compass (Fig 5.11)")
    ax.set_xticks(np.arange(3), [LABEL[m] for m in TRUE])
    ax.set_xlabel("method (env1)")
    ax.set_ylabel("catchment area (%)")
    ax.set_ylim(0, 105)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, frameon=False)
    ax.grid(alpha=0.3, axis="y")
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    ctx.figure(
        "fig5_11_visual_compass_catchment.png",
        fig,
        "Fig 5.11: catchment with the visual compass per background setting beside the true compass (env1, "
        "default rules); stars: the thesis.",
    )
    # compass-noise sweep
    rows = []
    for m in TRUE:  # one compiled program for all; sigma is traced
        pcts = [float(catchment(ctx, e, m, compass_noise_deg=s).catchment_pct()[0]) for s in SIGMAS]
        ctx.number(f"compass_noise:env1:{m}:catchment", pcts)
        rows += [{"method": LABEL[m], "compass sigma °": s, "catchment %": p} for s, p in zip(SIGMAS, pcts)]
    ctx.number("compass_noise:sigmas", list(SIGMAS))
    ctx.step("compass noise")
    ctx.table(
        "compass_noise",
        "Catchment vs compass noise, env1 (default rules)",
        rows,
        source="beyond the thesis",
        note="The thesis's §5.4 claim: DELV depends least on the accuracy of the compass.",
    )
    fig, ax = subplots(figsize=(6.4, 4))
    for i, m in enumerate(TRUE):
        ax.plot(SIGMAS, [r["catchment %"] for r in rows if r["method"] == LABEL[m]], marker="o", label=LABEL[m])
    ax.set_xlabel("compass noise sigma (°)")
    ax.set_ylabel("catchment area (%)")
    ax.set_ylim(0, 105)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    ctx.figure("compass_noise_catchment.png", fig, "Catchment on env1 vs the compass's Gaussian noise sigma.")
