"""Thesis-style rollout figures from result arrays (never recomputing): catchment maps (Figs 4.5, 5.5, 5.10),
trajectories (Figs 4.11, 5.8) and success rate vs release distance (Figs 4.10b, 5.7b)."""

from __future__ import annotations

import math

import matplotlib
import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import PatchCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Patch, Rectangle

from ..core.rollouts import OUTCOMES, SUCCESS, Catchment
from ..core.scene import Env
from ._maps import draw_env, draw_vector_map, subplots, vector_map_handles

SQUARE = dict(facecolor=(0.55, 0.75, 0.95, 0.35), edgecolor=(0.1, 0.35, 0.75), linewidth=0.6)
CATCHMENT_SQUARE = SQUARE  # its public name (delvjax.plots): the patch style of a cell that reaches home
NOT_COUNTED = dict(facecolor="none", edgecolor="0.55", hatch="////", linewidth=0.0)
FAIL_STYLE = {"timeout": ("o", "black"), "landmark": ("x", "black"), "arena": ("s", "black")}


def draw_catchment(ax, points, success, included, spacing: float) -> None:
    """Squares on the grid points whose rollout reaches home (Fig 4.5: "the squared region ... inside the catchment area")."""
    sel = np.asarray(included) & np.asarray(success)
    side = 0.86 * spacing
    squares = [Rectangle((x - side / 2, y - side / 2), side, side) for x, y in np.asarray(points)[sel]]
    ax.add_collection(PatchCollection(squares, zorder=1, **SQUARE))


def draw_not_counted(ax, points, included, counted, spacing: float) -> None:
    """Hatched squares on the grid points that are released but not counted in the catchment (closer
    than d to a wall under the default first move, docs/model.md section 5): not failures."""
    sel = np.asarray(included) & ~np.asarray(counted)
    side = 0.86 * spacing
    squares = [Rectangle((x - side / 2, y - side / 2), side, side) for x, y in np.asarray(points)[sel]]
    if squares:
        ax.add_collection(PatchCollection(squares, zorder=1, match_original=False, **NOT_COUNTED))


def has_uncounted(result: Catchment) -> bool:
    """Whether a `Catchment` has released grid points that are not counted."""
    return bool((np.asarray(result.included) & ~np.asarray(result.counted)).any())


not_counted = has_uncounted  # the name before it was public (delvjax.plots.has_uncounted)


def catchment_handles(uncounted: bool, hidden: bool = False) -> list:
    """Legend entries of a catchment map: success squares, cells not counted (if any), blank failures,
    the vector map's markers and hidden landmarks."""
    handles = [Patch(label="release point that reaches home", **SQUARE)]
    if uncounted:
        handles.append(Patch(label="not counted (within d of a wall)", **NOT_COUNTED))
    handles.append(Patch(facecolor="white", edgecolor="0.7", label="blank: release point that fails"))
    handles += vector_map_handles(first=True)
    if hidden:
        handles.append(Patch(facecolor="white", edgecolor="black", linestyle="--", label="hidden landmark"))
    return handles


def catchment_panel(
    ax: Axes, env: Env, result: Catchment, m: int, spacing: float | None = None, title: str = ""
) -> None:
    """One mask of a `Catchment`: its vector map with the catchment squares underneath (and the cells
    not counted hatched); `spacing`: the catchment's own grid (`Catchment.grid`) unless given."""
    spacing = result.grid.spacing if spacing is None else spacing
    draw_catchment(ax, result.points, np.asarray(result.success)[m], result.counted, spacing)
    draw_not_counted(ax, result.points, result.included, result.counted, spacing)
    draw_vector_map(
        ax, env, result.points, np.asarray(result.direction)[m], np.asarray(result.valid)[m], result.included, spacing
    )
    draw_env(ax, env)
    hidden = result.hidden[m] if m < len(result.hidden) else ()
    lms = np.asarray(env.landmarks)
    for i in hidden:  # occluded landmarks: hollow, dashed
        ax.add_patch(Circle(lms[i, :2], lms[i, 2], facecolor="white", edgecolor="black", linestyle="--", zorder=4))
    ax.set_title(title, fontsize=10)


def catchment_figure(env: Env, result: Catchment, spacing: float | None = None, title: str = "") -> Figure:
    """Catchment map (Fig 4.5 style); with occlusion one panel per choice of hidden landmarks (Fig 5.10). The
    squares' side: the catchment's own grid (`Catchment.grid`) unless `spacing` is given."""
    pct = result.catchment_pct()
    n = len(pct)
    cols = 1 if n == 1 else 2 if n <= 4 else 3 if n <= 9 else 4
    rows = math.ceil(n / cols)
    size = 6.4 if n == 1 else 4.6 if n <= 4 else 3.6
    fig, axes = subplots(
        rows,
        cols,
        figsize=(size * cols, size * rows + 0.9 + (0.4 if title else 0)),
        squeeze=False,
        layout="constrained",
    )
    for m in range(n):
        ax = axes[m // cols][m % cols]
        hidden = result.hidden[m]
        label = f"catchment {pct[m]:.2f}%" + (f" (hidden {', '.join(map(str, hidden))})" if hidden else "")
        catchment_panel(ax, env, result, m, spacing, title=label if n > 1 else f"{title}: {label}" if title else label)
        if n > 1:  # small panels: small labels, still labelled
            ax.xaxis.label.set_fontsize(8)
            ax.yaxis.label.set_fontsize(8)
            ax.tick_params(labelsize=7)
    for m in range(n, rows * cols):
        axes[m // cols][m % cols].axis("off")
    if n > 1 and title:
        fig.suptitle(f"{title}: mean {pct.mean():.2f}%, min {pct.min():.2f}%, max {pct.max():.2f}%")
    handles = catchment_handles(not_counted(result), hidden=any(len(h) for h in result.hidden))
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    return fig


def draw_trajectories(ax, env: Env, traj, home_radius: float, margin: float = 60.0) -> None:
    """Paths (lines with a dot per move), release points as black stars, failed ends marked by outcome.
    The panel extends `margin` cm beyond the outlined arena so that a path that left it stays visible."""
    draw_env(ax, env)
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(env.arena))
    ax.set_xlim(xmin - margin, xmax + margin)
    ax.set_ylim(ymin - margin, ymax + margin)
    ax.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, fill=False, edgecolor="0.4", lw=1.0, zorder=1))
    ax.add_patch(Circle(np.asarray(env.home), home_radius, fill=False, linestyle=":", edgecolor="0.3", zorder=2))
    path = np.asarray(traj.path)
    outcome = np.asarray(traj.outcome)
    colors = matplotlib.colormaps["tab10"](np.arange(path.shape[0]) % 10)
    for t in range(path.shape[0]):  # a handful of paths: drawing, not computing
        p = path[t][np.all(np.isfinite(path[t]), axis=-1)]
        ax.plot(p[:, 0], p[:, 1], "-", color=colors[t], lw=1.2, zorder=5)
        ax.plot(p[1:, 0], p[1:, 1], ".", color=colors[t], ms=3.5, zorder=5)
        name = OUTCOMES[outcome[t]] if outcome[t] >= 0 else ""
        if name in FAIL_STYLE:
            marker, color = FAIL_STYLE[name]
            ax.plot(p[-1, 0], p[-1, 1], marker, mfc="none", mec=color, ms=8, mew=1.8, zorder=6)
    start = np.asarray(traj.start)
    ax.plot(start[:, 0], start[:, 1], "*", color="black", ms=12, zorder=7)


def trajectories_figure(env: Env, results: dict, home_radius: float, title: str = "") -> Figure:
    """One panel per method, same release points (Figs 4.11, 5.8)."""
    n = len(results)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    fig, axes = subplots(rows, cols, figsize=(5.2 * cols, 5.4 * rows + 0.3), squeeze=False)
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    for ax, (label, traj) in zip(axes.ravel(), results.items()):
        draw_trajectories(ax, env, traj, home_radius)
        ok = np.asarray(traj.outcome) == SUCCESS
        ax.set_title(f"{label}: {int(ok.sum())}/{ok.size} reach home", fontsize=10)
    handles = [Line2D([], [], marker="*", color="black", ls="", ms=10, label="release point")]
    handles += [
        Line2D([], [], marker=m, mfc="none", mec=c, ls="", ms=7, mew=1.8, label=f"failure: {name}")
        for name, (m, c) in FAIL_STYLE.items()
    ]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8, frameon=False)
    if title:
        fig.suptitle(title)
    fig.set_layout_engine("tight", rect=(0, 0.05 / rows, 1, 1))  # applied when drawn (in the figure thread)
    return fig


def success_rate_figure(tables: dict, title: str = "") -> Figure:
    """Success rate (%) vs release distance, one line per method (Figs 4.10b, 5.7b), with 95% Wilson
    intervals (lines offset a few cm apart) and a table of per-bin counts (successes / trials placed)."""
    n = len(tables)
    fig, ax = subplots(figsize=(8.6, 4.4 + 0.22 * n))  # 1.6 in for the legend beside the panel
    markers = "osd^v<>"
    colors = []
    for i, (label, rows) in enumerate(tables.items()):
        x = np.array([r["distance_cm"] for r in rows])
        y = np.array([r["success_pct"] for r in rows])
        yerr = np.nan_to_num(
            np.array([[r["success_pct"] - r["ci_lo_pct"], r["ci_hi_pct"] - r["success_pct"]] for r in rows]).T, nan=0.0
        )
        line = ax.errorbar(
            x + 4.0 * (i - (n - 1) / 2),
            y,
            yerr=yerr,
            marker=markers[i % len(markers)],
            ms=5,
            capsize=2.5,
            elinewidth=0.8,
            label=label,
        ).lines[0]
        colors.append(line.get_color())
    x = np.array([r["distance_cm"] for r in next(iter(tables.values()))])
    step = np.diff(x)
    if x.size > 1 and np.allclose(step, step[0]):
        ax.set_xlim(x[0] - step[0] / 2, x[-1] + step[0] / 2)  # table columns centred on the points
        ax.set_xticks(x)
        ax.set_xticklabels([])
        cells = [[f"{r['successes']}/{r['placed']}" for r in rows] for rows in tables.values()]
        table = ax.table(
            cellText=[[f"{v:g}" for v in x]] + cells,
            rowLabels=["distance (cm)", *tables],
            cellLoc="center",
            loc="bottom",
            bbox=(0, -0.05 - 0.075 * (n + 1), 1, 0.075 * (n + 1)),
        )
        table.auto_set_font_size(False)
        table.set_fontsize(7.5)
        for (row, col), cell in table.get_celld().items():
            cell.set_edgecolor("0.8")
            if row >= 1:
                cell.get_text().set_color(colors[row - 1])
        ax.set_xlabel("")
        ax.text(
            1.0,
            -0.08 - 0.075 * (n + 1),
            "successes / trials per release distance",
            transform=ax.transAxes,
            ha="right",
            va="top",
            fontsize=7,
            color="0.35",
        )
    else:
        ax.set_xlabel("release distance from home (cm)")
    ax.set_ylabel("success rate (%)")
    ax.set_ylim(-2, 105)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    # beside the panel, not on it: a legend of a method per rule set (nine entries in Fig 5.7b) covers curves
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.set_layout_engine("tight")  # applied when drawn (in the figure thread)
    return fig
