"""Sensitivity of homing loss by automatic differentiation (beyond the thesis; docs/differentiable.md).

Which landmark's position matters most (arrows on the landmarks scaled by the gradient of the
soft homing loss smoothed at 5 cm and 1 degree, docs/differentiable.md "Sensitivity at a stated
scale"), and how homing loss responds to d, bearing, odometry and compass noise, for DELV, ALV,
ACV (smoothed gradients with their standard errors) and warping (central differences of the
ordinary loss).
Also (in a full run, not under --quick) the bearing-noise gain maps: ||d direction / d current bearings|| at every
grid point.
Run alone: python -m delvjax.studies.runs.sensitivity --out results/sensitivity [--env env1]
"""

from __future__ import annotations

import argparse

import numpy as np

from delvjax.cli._main import main as cli
from delvjax.core import maps
from delvjax.core.sensitivity import bearing_noise_gain
from delvjax.core.sensor import Sensor
from delvjax.evaluate._vector_map import resolve_headings
from delvjax.gradients import SAMPLES, SMOOTHING_CM, SMOOTHING_DEG, sensitivity, sensitivity_profiles
from delvjax.options import METHODS as REGISTRY
from delvjax.options import method_set
from delvjax.plots import draw_env, landmark_figure, parameter_figure, profile_figure, subplots

from ._common import env

TITLE = "Sensitivity of homing loss: landmarks, d and noise (gradients; beyond the thesis)"
COST = 60  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 5
GAIN_METHODS = ("delv", "delv-compass", "alv", "acv")
# One compiled Jacobian program for these (a `MethodSet`: 18.0 -> 7.1 s for the four maps, cold, 2 cores;
# docs/reproduce.md "One compiled rollout program"). ACV keeps its own: in the shared program its gains
# differ in the last bit (4.8e-7 deg/deg), and no number moves for speed.
GAIN_SET = ("delv", "delv-compass", "alv")


def gain_method(name: str):
    """The method whose gain map is drawn: in the shared program of GAIN_PROGRAM, or on its own."""
    return method_set(name, GAIN_SET)[0] if name in GAIN_SET else REGISTRY[name]


def gain_figure(e, spacing: float, seed: int):
    """Bearing-noise gain maps (deg of direction per deg of bearing noise) and their rows."""
    _, key = resolve_headings(None, seed)
    pts = maps.grid_points(e.arena, spacing)
    inc = np.asarray(maps.grid_included(e, pts, maps.CLEARANCE))
    headings = maps.random_headings(key, pts.shape[0])
    fig, axes = subplots(1, len(GAIN_METHODS), figsize=(4.4 * len(GAIN_METHODS), 4.6), squeeze=False)
    rows, n = [], int(round(np.sqrt(pts.shape[0])))
    xmin, ymin, xmax, ymax = np.asarray(e.arena)
    for ax, m in zip(axes[0], GAIN_METHODS):
        gain, ok = (np.asarray(a) for a in bearing_noise_gain(e, pts, headings, key, Sensor(), gain_method(m)))
        ok = ok & inc
        rows.append(
            {"method": m, "median_gain": float(np.median(gain[ok])), "p90_gain": float(np.percentile(gain[ok], 90))}
        )
        im = ax.imshow(
            np.log10(np.where(ok, gain, np.nan).reshape(n, n)),
            origin="lower",
            extent=(xmin, xmax, ymin, ymax),
            cmap="viridis",
            vmin=-1,
            vmax=1.5,
        )
        draw_env(ax, e)
        ax.set_title(f"{m}: median {rows[-1]['median_gain']:.2f}°/°", fontsize=10)
    fig.colorbar(im, ax=axes[0].tolist(), shrink=0.8, label="log10 gain (deg of direction per deg of bearing noise)")
    return fig, rows


def run(ctx) -> None:
    e = env("env1")
    result = sensitivity(e, spacing=ctx.config.spacing, seed=ctx.config.seed, progress=ctx.step)
    for m, r in result["methods"].items():
        ctx.number(f"sensitivity:env1:{m}:loss", r["loss"])
        for name, v in r["per_setting_unit"].items():
            ctx.number(f"sensitivity:env1:{m}:{name}", v)
    ctx.table(
        "sensitivity_parameters",
        "Change of homing loss (mean 1 - cos error) per 10 cm of d and per degree of each noise sigma, env1",
        result["parameter_rows"],
        source="beyond the thesis",
        note=f"DELV, ALV, ACV: gradient of the soft loss smoothed at {SMOOTHING_CM:g} cm and {SMOOTHING_DEG:g} deg "
        f"({SAMPLES} common random draws), with its standard error per setting unit (resolved: more than 2 standard "
        "errors from 0, so its sign is known); it predicts the soft loss's trend at that "
        "scale for ALV (3-10 %), not yet for ACV and DELV, whose errors are then as large as the values; against "
        "the hard (pixel) loss smoothed alike even ALV's is 38-75 % off, mostly right in sign only "
        "(docs/differentiable.md). Warping: central differences of the "
        "ordinary loss; it reads only the current ring image, so d, blob-bearing and odometry noise do "
        "not enter it (exactly 0). Methods without a compass have no compass sensitivity.",
        columns=["method", "parameter", "nominal", "step", "d_loss_per_step", "standard_error", "resolved", "loss"],
    )
    ctx.table(
        "sensitivity_landmarks",
        f"Gradient of the soft homing loss smoothed at {SMOOTHING_CM:g} cm with respect to each landmark of env1, "
        "with standard errors (resolved_*: |derivative| > 2 standard errors, its sign known from the draws)",
        result["landmark_rows"],
        source="beyond the thesis",
    )
    ctx.figure(
        "sensitivity_landmarks.png",
        landmark_figure(result),
        f"Arrows on the landmarks: moving a landmark that way lowers the homing loss smoothed at {SMOOTHING_CM:g} cm; "
        "numbers: |dL/dx| per metre; a gray arrow's x and y are both within 2 standard errors of 0 (direction not known).",
    )
    ctx.figure(
        "sensitivity_parameters.png",
        parameter_figure(result),
        "Change of homing loss per 10 cm of d and per degree of each noise sigma.",
    )
    if ctx.config.quick or ctx.config.spacing >= 100:  # four more compiled programs: only in a full run
        return
    profiles = sensitivity_profiles(
        e, ("alv", "acv"), spacing=ctx.config.spacing, seed=ctx.config.seed, progress=ctx.step
    )
    ctx.csv("profile.csv", rows=[dict(method=m, **r) for m, rows in profiles.items() for r in rows])
    ctx.figure(
        "profile.png",
        profile_figure(profiles),
        "The loss along landmark 0's x at the point, 1 cm and 5 cm, with each scale's sensitivity as a dashed "
        "tangent: ALV's tangents follow their curves; ACV's 5 cm tangent does not (its softmins switch shifts "
        "within a centimetre; docs/differentiable.md).",
    )
    fig, rows = gain_figure(e, ctx.config.spacing, ctx.config.seed)
    ctx.csv("bearing_gain.csv", rows=rows)
    ctx.figure(
        "bearing_gain.png", fig, "First-order std of the homing direction per degree of bearing noise (jax.grad)."
    )


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results/sensitivity")
    p.add_argument("--env", default="env1")
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args(argv)
    return cli(["sensitivity", a.env, "--out", a.out, "--spacing", str(a.spacing), "--seed", str(a.seed)])


if __name__ == "__main__":
    raise SystemExit(main())
