"""Figures of the familiarity experiments (docs/familiarity.md §3), from a `FamiliarityResult`:
(a) the route, the heading field coloured by its error and the route-following paths; (b) the RIDF
at points 0, 20 and 60 cm from the route; (c) catchment areas (CA, RCA) along the route."""

from __future__ import annotations

import matplotlib
import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

from ..familiarity._run import FamiliarityResult
from ._maps import draw_world, subplots

RIDF_DISTANCES = (0.0, 20.0, 60.0)  # cm from the route: the points whose RIDF panel (b) draws


def familiarity_figure(result: FamiliarityResult, title: str = "") -> Figure:
    """The three panels of the module docstring."""
    fig, (a, b, c) = subplots(1, 3, figsize=(16.0, 5.2))
    f = result.field_columns()
    p = np.asarray(result.route.route.positions)
    draw_world(a, result.arena, p[-1], result.obstacles)
    if result.footprint is not None:  # a mesh world: its triangles seen from above
        a.add_collection(PolyCollection(result.footprint, facecolor="0.55", edgecolor="none", alpha=0.5, zorder=1))
    a.plot(p[:, 0], p[:, 1], "-", color="tab:green", lw=2.5, zorder=2, label="route")
    h = np.radians(f["heading_deg"])
    q = a.quiver(f["x_cm"], f["y_cm"], np.cos(h), np.sin(h), np.minimum(f["error_deg"], 180.0), cmap="viridis_r",
                 clim=(0, 180), angles="xy", scale=25, width=0.004, zorder=4)  # fmt: skip
    database = result.on_database  # an image database's field: column-0 headings against the nearest route image's
    fig.colorbar(
        q,
        ax=a,
        label="error vs the nearest route image (deg)" if database else "heading error vs the route (deg)",
        shrink=0.8,
    )
    path = np.zeros((0, 1, 2)) if result.trials is None else np.asarray(result.trials.path)
    for t in range(min(len(path), 5)):  # a few paths: drawing, not computing
        a.plot(path[t, :, 0], path[t, :, 1], "-", color="tab:red", lw=0.8, alpha=0.7, zorder=5)
    what = "column-0 heading of the most familiar view" if database else "heading field"
    a.set_title(f"(a) {result.model}: {what}" + (" and paths" if len(path) else ""), fontsize=10)
    a.legend(loc="lower right", fontsize=8)
    curve = np.asarray(result.field.curve)
    start = np.degrees(np.asarray(result.field.curve_start))
    step = 360.0 / curve.shape[1]
    dist = f["distance_to_route_cm"]
    reference = f["route_direction_deg"] if "route_direction_deg" in f else f["route_image_heading_deg"]
    colors = matplotlib.colormaps["plasma"](np.linspace(0, 0.8, len(RIDF_DISTANCES)))
    for d, col in zip(RIDF_DISTANCES, colors):
        i = int(np.argmin(np.abs(dist - d)))
        rel = (start[i] + step * np.arange(curve.shape[1]) - reference[i] + 180) % 360 - 180
        o = np.argsort(rel)
        b.plot(rel[o], curve[i][o], color=col, label=f"{dist[i]:.0f} cm from the route")
    b.axvline(0, color="0.5", lw=0.8)
    b.set_xlabel("heading relative to the route (deg)")
    b.set_ylabel("unfamiliarity")
    b.set_title("(b) rotational familiarity (RIDF)", fontsize=10)
    b.legend(fontsize=8)
    ca = result.catchment_columns()
    sp = float(result.settings["route_spacing"])
    c.plot(ca["image"], ca["ca_size_on_route"] * sp, label="CA (IDF monotonic)")
    c.plot(ca["image"], ca["rca_size_on_route"] * sp, label="RCA (heading error < 45°)")
    c.set_xlabel("route image (goal)")
    c.set_ylabel("catchment along the route (cm)")
    c.set_title("(c) catchment areas along the route", fontsize=10)
    c.legend(fontsize=8)
    s = result.summary()
    if not title and s["trials"]:
        ci = s["success_ci95_pct"]
        title = f"{result.world}: {result.model}, success {s['success_pct']:.0f} % of {s['trials']} trials"
        title += f" (95 % CI {ci[0]:.0f}-{ci[1]:.0f} %)"
    fig.suptitle(title or f"{result.world}: {result.model}, tested on {s['settings']['tested_on']}")
    fig.set_layout_engine("tight")
    return fig
