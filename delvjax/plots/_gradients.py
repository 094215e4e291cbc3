"""Figures of the differentiable path (docs/differentiable.md), from the results of
`delvjax.gradients` (never recomputing): which landmark matters, the sensitivity to d and the noise,
trap points near failed rollouts, an optimised layout beside its start."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..gradients._layout import LayoutResult
from ..gradients._sensitivity import NOMINAL, RESOLVED_SE, UNITS, resolved
from ..gradients._traps import TrapReport
from ._maps import draw_env, subplots
from ._rollouts import catchment_panel


def landmark_figure(result: dict) -> Figure:
    """Arrows on the landmarks: the direction that lowers the homing loss (minus the position gradient),
    scaled per method so that its longest arrow is 150 cm; the number is |grad| x 100 (per metre). An arrow
    whose x and y derivatives are both within RESOLVED_SE standard errors of 0 (smoothed sensitivities) is
    gray: its direction is not known."""
    env = result["env"]
    soft = [m for m, r in result["methods"].items() if r["landmark_grad"] is not None]
    n = max(len(soft), 1)
    fig, axes = subplots(1, n, figsize=(4.6 * n, 5.0), squeeze=False, layout="constrained")
    lm = np.asarray(env.landmarks)[np.asarray(env.valid)]
    for ax, m in zip(axes[0], soft):
        g = np.asarray(result["methods"][m]["landmark_grad"])
        se = result["methods"][m].get("landmark_se")
        known = np.ones(len(g), bool) if se is None else np.any(resolved(g[:, :2], np.asarray(se)[:, :2]), axis=1)
        colors = np.where(known, "tab:red", "0.6")
        norm = np.hypot(g[:, 0], g[:, 1])
        scale = 150.0 / max(norm.max(), 1e-12)
        draw_env(ax, env)
        ax.quiver(
            lm[:, 0],
            lm[:, 1],
            -g[:, 0] * scale,
            -g[:, 1] * scale,
            angles="xy",
            scale_units="xy",
            scale=1.0,
            color=colors,
            width=0.008,
            zorder=5,
        )
        for (x, y, r), n, c in zip(lm, norm, colors):
            ax.annotate(
                f"{100 * n:.2g}",
                (x, y),
                xytext=(0, r * 0.0 + 14),
                textcoords="offset points",
                ha="center",
                fontsize=8,
                color=c,
                zorder=6,
            )
        ax.set_title(f"{m}: loss {result['methods'][m]['loss']:.3g} (lower is better)", fontsize=10)
    fig.suptitle(
        "Which landmark matters: arrows move a landmark the way that lowers the homing loss\n"
        "(arrow lengths scaled per panel, the longest 150 cm; numbers |dL/dx| per metre; "
        f"gray: x and y within {RESOLVED_SE:g} standard errors of 0)",
        fontsize=10,
    )
    return fig


def parameter_figure(result: dict) -> Figure:
    """Bars: change of homing loss per unit of d (10 cm) and of each noise sigma (1 degree)."""
    methods = list(result["methods"])
    names = list(NOMINAL)
    fig, axes = subplots(1, 1, figsize=(7.5, 4.2), squeeze=False, layout="constrained")
    ax = axes[0, 0]
    width = 0.8 / len(methods)
    for k, m in enumerate(methods):
        vals = [result["methods"][m]["per_setting_unit"][n] * UNITS[n] for n in names]
        ax.bar(np.arange(len(names)) + (k - (len(methods) - 1) / 2) * width, vals, width, label=m)
    ax.axhline(0, color="black", linewidth=0.8)
    ax.set_xticks(range(len(names)), ["d (per 10 cm)", "bearing σ (per °)", "odometry σ (per °)", "compass σ (per °)"])
    ax.set_ylabel("change of homing loss\n(mean 1 - cos error; < 0 is better)")
    ax.set_xlabel("parameter (change per unit)")
    ax.legend(fontsize=8)
    ax.set_title("Sensitivity of homing loss at d = 50 cm, σ bearing 1°, odometry 1°, compass 2°", fontsize=9)
    return fig


def trap_figure(report: TrapReport, spacing: float) -> Figure:
    """The catchment map (squares: rollouts that reach home) and vector map with the zeros drawn
    (the sink at home left out): sinks red discs, saddles orange crosses, sources blue triangles, discontinuities grey diamonds;
    the end points of the timed-out rollouts as small red dots."""
    fig, axes = subplots(1, 1, figsize=(6.2, 6.2), squeeze=False, layout="constrained")
    ax = axes[0, 0]
    s = report.summary
    catchment_panel(
        ax,
        report.env,
        report.catchment,
        0,
        spacing,
        f"{report.method}: catchment {s['catchment_pct']:.1f} %, {s['timed_out']} timed out, "
        f"{s['timed_out_within_near_of_a_sink']} within {s['near_cm']:g} cm of a sink",
    )
    if len(report.failed_ends):
        ax.plot(
            report.failed_ends[:, 0],
            report.failed_ends[:, 1],
            ".",
            color="tab:red",
            markersize=3,
            zorder=5,
            label="timed-out ends",
        )
    style = {
        "sink": ("o", "tab:red"),
        "saddle": ("X", "tab:orange"),
        "source": ("^", "tab:blue"),
        "degenerate": ("s", "tab:purple"),
        "discontinuity": ("D", "0.5"),
        "2-cycle": ("P", "tab:green"),
    }
    for kind, (marker, color) in style.items():
        pts = np.array([[r["x"], r["y"]] for r in report.points if r["kind"] == kind and not r["home"]]).reshape(-1, 2)
        if len(pts):
            ax.plot(
                pts[:, 0], pts[:, 1], marker, color=color, markersize=10, markeredgecolor="black", zorder=6, label=kind
            )
    ax.legend(fontsize=7, loc="upper right")
    return fig


def layout_figure(result: LayoutResult, spacing: float) -> Figure:
    """Start and optimised layouts side by side: each one's vector map and catchment (the comparison's
    own runs; the worst mask under occlusion), and the soft objective per step."""
    fig, axes = subplots(1, 3, figsize=(16.5, 5.6), squeeze=False, layout="constrained")
    for ax, env, row, c in zip(axes[0][:2], (result.start, result.optimised), result.rows, result.catchments):
        worst = int(np.argmin(c.catchment_pct()))
        catchment_panel(
            ax,
            env,
            c,
            worst,
            spacing,
            f"{row['layout']}: catchment {row['catchment_pct']:.1f} % "
            f"(worst mask {row['catchment_min_pct']:.1f} %)\n"
            f"e>45° {row['gt45_pct']:.1f} %, e>90° {row['gt90_pct']:.1f} %",
        )
    ax = axes[0][2]
    ax.plot(range(len(result.objective)), result.objective, marker="o", markersize=3)
    ax.set_xlabel("BFGS step")
    ax.set_ylabel("soft objective (loss + penalty; lower is better)")
    ax.ticklabel_format(axis="y", useOffset=True, style="sci", scilimits=(-2, 3))
    ax.set_title(f"{result.method}, occlude {result.occlude}: {result.seconds:.1f} s", fontsize=10)
    return fig


def profile_figure(profiles: dict[str, list[dict]]) -> Figure:
    """Per method: the loss along one landmark coordinate at each scale (`gradients._profile`), with the
    sensitivity at t = 0 drawn as a dashed tangent of the same colour."""
    n = max(len(profiles), 1)
    fig, axes = subplots(1, n, figsize=(5.0 * n, 4.0), squeeze=False, layout="constrained")
    for ax, (method, rows) in zip(axes[0], profiles.items()):
        scales = list(dict.fromkeys(r["scale_cm"] for r in rows))
        for i, scale in enumerate(scales):
            part = [r for r in rows if r["scale_cm"] == scale]
            t = np.array([r["t_cm"] for r in part])
            q = np.array([r["loss"] for r in part])
            label = "at the point" if scale == "" else f"smoothed at {scale:g} cm"
            color = f"C{i}"
            ax.plot(t, q, color=color, lw=1.2, label=label)
            ax.plot(t, part[0]["loss_at_0"] + part[0]["slope_at_0"] * t, color=color, ls="--", lw=0.9)
        r0 = rows[0]
        ax.set_xlabel(f"landmark {r0['landmark']} {r0['coordinate']} moved by, cm")
        ax.set_ylabel("homing loss (mean 1 - cos error)")
        ax.set_title(f"{method}: loss and its sensitivity (dashed)", fontsize=10)
        ax.legend(fontsize=8)
    return fig
