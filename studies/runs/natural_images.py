"""Robot experiments with natural landmarks, on rendered images (thesis §4.4.2, Figs 4.22-4.24).

The `natural` world (docs/images.md §8: a table, a lecture desk, a flower pot and a drawer in a
room, home at (500, 500)) is rendered with camera noise; landmarks are whatever is saturated in
colour. DELV without a compass gives the vector map and the homing paths from four release
points of Fig 4.24, and a catchment of nearest-snapshot rollouts.
"""

from __future__ import annotations

import numpy as np

from delvjax.core.images.rollouts import OUTCOMES
from delvjax.images import database_catchment, database_rollouts
from delvjax.images._evaluate import catchment_numbers
from delvjax.plots import paths_figure

from ._images_common import LABEL, database, image_map, numbers, preview

TITLE = "Robot experiments with natural landmarks, on rendered images (Fig 4.24)"
COST = 45  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
METHODS = ("delv", "alv", "warping", "minwarping")
STEPS = len(METHODS)  # a map each (a preview: DELV's, then a step that says the others are the full run's)
STARTS = ((380.0, 860.0), (620.0, 860.0), (900.0, 460.0), (460.0, 140.0))  # two upper, one right, one lower


def run(ctx) -> None:
    db = database("natural", seed=ctx.config.seed, panoramas=not preview(ctx))  # panoramas: MinWarping
    rows = []
    for m in METHODS[:1] if preview(ctx) else METHODS:
        vm = image_map(db, m)
        s = numbers(vm)
        _, paths = database_catchment(db, vm, seed=ctx.config.seed, collisions=True)
        c = catchment_numbers(paths)
        ctx.number(f"natural_images:{m}:mean_error_deg", s["mean_error_deg"])
        ctx.number(f"natural_images:{m}:catchment_pct", c["catchment_pct"])
        rows.append(
            {
                "method": LABEL[m],
                "images: mean error °": s["mean_error_deg"],
                "images: e>45 %": s["gt45_pct"],
                "catchment %": c["catchment_pct"],
                "landmark hits %": c["landmark_pct"],
                "invalid": s["invalid"],
            }
        )
        if m == "delv":
            trips = database_rollouts(db, vm, np.asarray(STARTS), seed=ctx.config.seed, max_steps=60)
            ctx.figure(
                "fig4_24_natural.png",
                paths_figure(db, vm, trips, "DELV with natural landmarks (Fig 4.24)"),
                "Fig 4.24: (a) homing paths from four release points (nearest-snapshot rollouts), (b) the vector "
                "map; boxes: table, lecture desk, drawer; disc: flower pot.",
            )
            ctx.csv(
                "fig4_24_paths.csv",
                rows=[
                    {"start": i, "step": t, "x": float(x), "y": float(y), "outcome": OUTCOMES[int(trips.outcome[i])]}
                    for i in range(len(STARTS))
                    for t, (x, y) in enumerate(np.asarray(trips.path[i]))
                ],
            )
        ctx.step(m)
    for _ in range(STEPS - (1 if preview(ctx) else len(METHODS))):  # a preview: the bar still ends at its total
        ctx.step("the other methods: full run only")
    ctx.table(
        "natural_images",
        "Homing with natural landmarks on rendered images",
        rows,
        source="Fig 4.24",
        note="Landmarks: every saturated colour (the walls, floor and ceiling are grey; the thesis used "
        "mean-shift segmentation). Catchment: nearest-snapshot rollouts every 40 cm, a trial that walks "
        "into furniture fails.",
    )
