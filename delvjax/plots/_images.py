"""Figures of image experiments (docs/images.md; thesis Figs 4.16-4.21, 4.24): a world's obstacles,
vector maps and catchments on a database, homing paths, and the pipeline from camera image to ring."""

from __future__ import annotations

import matplotlib
import numpy as np
from jax.typing import ArrayLike
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..core.images.rollouts import Paths
from ..core.maps import VectorMap
from ..images._load import LoadedDatabase
from ._maps import draw_vector_map, draw_world, subplots


def database_map_figure(
    db: LoadedDatabase,
    vm: VectorMap,
    title: str = "",
    classes: bool = False,
    ax: Axes | None = None,
    perceived: ArrayLike | None = None,
) -> Figure:
    """Vector map on a database (Fig 4.18): arrows, invalid points as red x, obstacles."""
    fig, ax = subplots(figsize=(6.4, 6.4)) if ax is None else (ax.figure, ax)
    draw_vector_map(
        ax,
        None,
        vm.points,
        vm.direction,
        vm.valid,
        vm.included,
        db.spacing,
        error_deg=vm.error_deg if classes else None,
    )
    draw_world(ax, db.arena, db.home, db.obstacles, perceived)
    if getattr(db, "kind", "grid") == "route":  # docs/images.md §6.1: the route the images were taken along
        route = np.asarray(db.rings.positions)
        ax.plot(route[:, 0], route[:, 1], "-", color="0.6", lw=1.0, zorder=0, label="route")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title, fontsize=10)
    return fig


def database_catchment_figure(
    db: LoadedDatabase, vm: VectorMap, starts: ArrayLike, paths: Paths, title: str = ""
) -> Figure:
    """Catchment on a database: the vector map with a square on every release point that homed."""
    fig = database_map_figure(db, vm, title)
    ax = fig.axes[0]
    ok = np.asarray(paths.outcome) == 0
    s = np.asarray(starts)
    ax.scatter(s[ok, 0], s[ok, 1], marker="s", s=60, facecolors="none", edgecolors="tab:blue", zorder=1, label="homes")
    ax.legend(loc="upper right", fontsize=8)
    return fig


def paths_figure(db: LoadedDatabase, vm: VectorMap, paths: Paths, title: str = "") -> Figure:
    """Fig 4.24: (a) homing paths from a few release points, (b) the vector map."""
    fig, (a, b) = subplots(1, 2, figsize=(12.0, 6.0))
    draw_world(a, db.arena, db.home, db.obstacles)
    path = np.asarray(paths.path)
    colors = matplotlib.colormaps["tab10"](np.arange(path.shape[0]) % 10)
    for t in range(path.shape[0]):  # a handful of paths: drawing, not computing
        a.plot(path[t, :, 0], path[t, :, 1], ".-", color=colors[t], lw=1.2, ms=4, zorder=5)
        a.plot(path[t, 0, 0], path[t, 0, 1], "*", color="black", ms=10, zorder=6)
    a.set_title("(a) homing paths", fontsize=10)
    database_map_figure(db, vm, "(b) homing vectors", ax=b)
    fig.suptitle(title)
    fig.set_layout_engine("tight")
    return fig


def pipeline_figure(
    donut_image: ArrayLike, panorama_image: ArrayLike, mask_image: ArrayLike, ring_mask: ArrayLike, title: str = ""
) -> Figure:
    """Figs 4.16b-4.17: the donut image, its unwrapped panorama, the segmented landmarks and the ring."""
    fig = matplotlib.figure.Figure(figsize=(10.0, 6.2))
    grid = fig.add_gridspec(3, 2, width_ratios=[1.0, 2.4])
    ax = fig.add_subplot(grid[:, 0])
    ax.imshow(donut_image)
    ax.set_title("(a) catadioptric image", fontsize=9)
    for i, (img, label) in enumerate(
        (
            (panorama_image, "(b) unwrapped panorama"),
            (mask_image, "(c) landmark pixels (HSV threshold)"),
            (np.repeat(np.asarray(ring_mask)[None], 8, 0), "(d) 1D ring"),
        )
    ):
        a = fig.add_subplot(grid[i, 1])
        a.imshow(img, cmap="gray", aspect="auto", interpolation="nearest")
        a.set_title(label, fontsize=9)
        a.set_yticks([])
    for a in fig.axes:  # pictures: no pixel ticks
        a.set_xticks([])
        a.set_yticks([])
    fig.suptitle(title)
    fig.set_layout_engine("tight")
    return fig
