"""Thesis-style figures from result arrays (never recomputing): vector maps (Figs 4.2/4.3), error curves (Fig 4.4)."""

from __future__ import annotations

import numpy as np
from jax.typing import ArrayLike
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Rectangle
from matplotlib.path import Path as Outline

from ..core.maps import VectorMap
from ..core.metrics import error_class
from ..core.scene import Env


def subplots(
    *grid: int, figsize: tuple[float, float], layout: str | None = None, **kw
) -> tuple[Figure, Axes | np.ndarray]:
    """(figure, axes) of a new figure that belongs to no pyplot state (no backend switch, no global
    figure list; safe to draw on any thread): `Figure(figsize, layout).subplots(*grid, **kw)`."""
    fig = Figure(figsize=figsize, layout=layout)
    return fig, fig.subplots(*grid, **kw)


ARROW = Outline(  # a legend marker for a homing direction, drawn from vertices: no mathtext, whose
    # font state is shared between threads (reproduce draws figures side by side)
    [(-1.0, 0.0), (1.0, 0.0), (0.45, 0.4), (1.0, 0.0), (0.45, -0.4)],
    [Outline.MOVETO, Outline.LINETO, Outline.MOVETO, Outline.LINETO, Outline.LINETO],
)
HOMING_ARROW = ARROW  # its public name (delvjax.plots): `Line2D(marker=HOMING_ARROW)` in a legend
CLASS_STYLE = (  # Fig 4.3: dot < 45, star 45-90, triangle > 90
    ("<45°", dict(marker=".", color="0.35", s=10)),
    ("45–90°", dict(marker="*", color="tab:orange", s=40)),
    (">90°", dict(marker="^", facecolors="none", edgecolors="tab:red", s=36)),
)


def draw_env(ax: Axes, env: Env, perceived_radius: float | None = None) -> None:
    """Arena box, landmarks to scale (filled discs), home as a black square."""
    lm = np.asarray(env.landmarks)[np.asarray(env.valid)]
    draw_world(ax, env.arena, env.home, {"cylinders": lm.tolist()})


def draw_world(ax, arena, home, obstacles: dict, perceived=None) -> None:
    """Arena, cylinders [x, y, r] (discs) and boxes [xmin, ymin, xmax, ymax] (rectangles) to scale, home
    as a black square; `perceived` (K, 2) landmark positions as white circles (Fig 4.20)."""
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(arena))
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal")
    for x, y, r in obstacles.get("cylinders", []):
        ax.add_patch(Circle((x, y), r, facecolor="0.15", edgecolor="black", zorder=3))
    for x0, y0, x1, y1 in obstacles.get("boxes", []):
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, facecolor="0.15", edgecolor="black", zorder=3))
    if perceived is not None and len(perceived):
        r = 0.02 * (xmax - xmin)
        for x, y in np.asarray(perceived):
            ax.add_patch(Circle((x, y), r, facecolor="white", edgecolor="black", zorder=4))
    hx, hy = np.asarray(home)[:2]
    ax.plot([hx], [hy], marker="s", color="black", markersize=7, zorder=4, label="home")
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")


def draw_vector_map(
    ax: Axes,
    env: Env | None,
    points: ArrayLike,
    direction: ArrayLike,
    valid: ArrayLike,
    included: ArrayLike,
    spacing: float,
    error_deg: ArrayLike | None = None,
) -> None:
    """Unit arrows of the homing direction at each included point; invalid points as red x;
    error class markers when `error_deg` is given."""
    inc = np.asarray(included)
    pts = np.asarray(points)[inc]
    ok = np.asarray(valid)[inc]
    ang = np.asarray(direction)[inc]
    length = 0.7 * spacing
    u, v = np.cos(ang[ok]) * length, np.sin(ang[ok]) * length
    ax.quiver(
        pts[ok, 0],
        pts[ok, 1],
        u,
        v,
        angles="xy",
        scale_units="xy",
        scale=1.0,
        width=0.0022,
        headwidth=4,
        headlength=4,
        color="black",
        zorder=2,
    )
    if (~ok).any():
        ax.scatter(pts[~ok, 0], pts[~ok, 1], marker="x", color="tab:red", s=14, zorder=3, label="invalid")
    if error_deg is not None:
        cls = np.asarray(error_class(np.asarray(error_deg)))[inc]
        for c, (label, style) in enumerate(CLASS_STYLE):
            sel = (cls == c) & ok
            if sel.any() and c > 0:
                ax.scatter(pts[sel, 0], pts[sel, 1], zorder=4, label=label, **style)


def vector_map_handles(classes: bool = False, first: bool = False) -> list:
    """Legend entries of a vector map: every marker it can show (the arrows are unit directions)."""
    what = "first homing direction" if first else "homing direction"
    handles = [
        Line2D([], [], marker=ARROW, color="black", ls="", ms=10, label=f"{what} (unit arrows)"),
        Line2D([], [], marker="s", color="black", ls="", ms=7, label="home"),
        Line2D([], [], marker="o", color="0.15", ls="", ms=9, label="landmark (to scale)"),
        Line2D([], [], marker="x", color="tab:red", ls="", ms=7, label="no direction (invalid)"),
    ]
    if classes:
        handles += [
            Line2D(
                [],
                [],
                ls="",
                label=f"error {lab}",
                marker=style["marker"],
                color=style.get("color", style.get("edgecolors")),
                mfc="none" if "facecolors" in style else None,
            )
            for lab, style in CLASS_STYLE[1:]
        ]
    return handles


def vector_map_figure(
    env: Env, vm: VectorMap, spacing: float | None = None, title: str = "", classes: bool = False
) -> Figure:
    """Figure of one vector map (Fig 4.2; with `classes`, the error markers of Fig 4.3). The arrows'
    length follows the grid's spacing: the map's own (`VectorMap.spacing`) unless `spacing` is given."""
    spacing = map_spacing(vm, spacing)
    fig, ax = subplots(figsize=(6.4, 7.0), layout="constrained")
    draw_vector_map(
        ax, env, vm.points, vm.direction, vm.valid, vm.included, spacing, error_deg=vm.error_deg if classes else None
    )
    draw_env(ax, env)
    ax.set_title(title)
    fig.legend(handles=vector_map_handles(classes), loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    return fig


def map_spacing(vm: VectorMap, spacing: float | None = None) -> float:
    """The grid spacing a figure of `vm` draws with: `spacing` when given, else the one the map carries;
    a `ValueError` when neither is known (a map built by hand, or on scattered points)."""
    if spacing is not None:
        return float(spacing)
    if vm.spacing is None:
        raise ValueError("this VectorMap carries no grid spacing (not from vector_map): pass spacing=")
    return float(vm.spacing)


def error_curve_figure(curves: dict[str, list[dict]], title: str = "") -> Figure:
    """Mean angular error vs distance from home with 95% t intervals, one line per label (Fig 4.4)."""
    fig, ax = subplots(figsize=(6.4, 4.2))
    for label, rows in curves.items():
        x = np.array([(r["bin_lo"] + r["bin_hi"]) / 2 for r in rows])
        m = np.array([r["mean_deg"] for r in rows])
        lo = np.array([r["ci_lo_deg"] for r in rows])
        hi = np.array([r["ci_hi_deg"] for r in rows])
        yerr = np.nan_to_num(np.stack([m - lo, hi - m]), nan=0.0)
        ax.errorbar(x, m, yerr=yerr, marker="o", ms=4, capsize=3, label=label)
    ax.set_xlabel("distance from home (cm)")
    ax.set_ylabel("angular error (deg)")
    ax.set_ylim(bottom=0)
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def environments_figure(envs: list[Env]) -> Figure:
    """The built-in environments side by side (README), in centimetres, with a legend of what is drawn."""
    cols = min(len(envs), 4)
    rows = -(-len(envs) // cols)
    fig, axes = subplots(rows, cols, figsize=(3.3 * cols, 3.4 * rows + 0.4), squeeze=False, layout="constrained")
    for ax in axes.ravel()[len(envs) :]:
        ax.set_visible(False)
    for i, (ax, env) in enumerate(zip(axes.ravel(), envs)):
        draw_env(ax, env)
        ax.set_title(env.name)
        ax.set_xlabel("x (cm)")
        ax.set_ylabel("y (cm)")
        ax.tick_params(labelsize=7)
    marks = [
        Line2D([], [], marker="o", ls="", color="0.15", markersize=9, label="landmark (cylinder, to scale)"),
        Line2D([], [], marker="s", ls="", color="black", markersize=6, label="home"),
        Line2D([], [], color="black", lw=1.0, label="arena wall"),
    ]
    fig.legend(handles=marks, loc="outside lower center", ncol=3, fontsize=8, frameon=False)
    return fig
