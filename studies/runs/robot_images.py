"""Robot experiments with artificial landmarks, on rendered images (thesis §4.4.1, Figs 4.16-4.21).

The `robot` world (docs/images.md §8: four red cylinders in a 1.8 m arena, a camera 25 cm up,
snapshots every 20 cm, a 20 cm unit move) is rendered with camera noise and run through the
image pipeline (HSV threshold, 10° band, blobs). DELV and predictive image matching give the
vector maps and error curves of Figs 4.18-4.19; DELV with quantized distances those of Figs
4.20-4.21, with the perceived landmark positions. Every number is set against the ideal rings of
the ring model on the same layout.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from delvjax.core.images import Camera, Catadioptric, donut, rgb_to_hsv, segment, unwrap
from delvjax.core.methods import DELV
from delvjax.images import database_catchment, image_world
from delvjax.images._disk import file_columns
from delvjax.images._evaluate import catchment_numbers, perceived
from delvjax.plots import database_map_figure, error_curve_figure, pipeline_figure, subplots

from ._common import curves_rows
from ._images_common import LABEL, ROBOT_SCALE, curve, database, ideal_map, image_map, numbers, preview

TITLE = "Robot experiments with artificial landmarks, on rendered images (Figs 4.16-4.21)"
COST = 45  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 3
LEVELS = (1, 2, 4, 5)
BIN = 20.0  # cm, error-curve bins in the 1.8 m arena


def pipeline_panels(db) -> object:
    """Figs 4.16b-4.17: the donut at home, its panorama, the landmark pixels and the ring."""
    iw, mirror, cam = image_world("robot"), Catadioptric(), Camera()

    @jax.jit  # one program, not one per operation
    def images(world, ex):
        img = donut(world, mirror, jnp.asarray(iw.home, jnp.float32), jnp.float32(0.0))
        pano = unwrap(img, mirror, cam)
        return img, pano, segment(rgb_to_hsv(pano), ex.hue_deg, ex.hue_width_deg, ex.sat_min, ex.val_min)

    img, pano, mask = images(iw.world, iw.extractor)
    ring = np.asarray(db.rings.snapshots.mask)[db.home_index]
    return pipeline_figure(
        np.asarray(img),
        file_columns(np.asarray(pano)),
        file_columns(np.asarray(mask), axis=-1),
        file_columns(ring, axis=-1),
        "The image pipeline at home (robot world)",
    )


def run(ctx) -> None:
    db = database("robot", seed=ctx.config.seed, panoramas=True)  # panoramas: MinWarping
    home = db.home
    ctx.figure(
        "fig4_17_pipeline.png",
        pipeline_panels(db),
        "Figs 4.16b-4.17: catadioptric image at home, unwrapped panorama, red pixels found by the HSV "
        "threshold, and the 1D ring of the 10° band (columns in the file order: unmirrored).",
    )
    rows, curves, maps = [], {}, {}
    runs = (("delv", "gray"), ("warping", "gray"))
    runs += (("warping", "mask"), ("minwarping", "panorama")) if not preview(ctx) else ()
    for m, channel in runs:  # (the mask ring and MinWarping are other programs: the full run only)
        if m == "minwarping":  # no ring model of a panorama: no ideal numbers
            vm, ideal = image_map(db, m), None
        else:
            vm, ideal = image_map(db, m, channel=channel), ideal_map("robot", m, channel=channel)
        s = numbers(vm)
        si = numbers(ideal) if ideal is not None else {"mean_error_deg": float("nan"), "gt45_pct": float("nan")}
        starts, paths = database_catchment(db, vm, seed=ctx.config.seed)
        c = catchment_numbers(paths)
        tag = m + ("" if channel in ("gray", "panorama") else f":{channel}")
        label = LABEL[m] + (f" ({channel} ring)" if m == "warping" else "")
        if m == "minwarping":
            curves[f"{LABEL[m]} (images)"] = curve(vm, home, BIN)
        elif channel == "gray":
            curves[f"{LABEL[m]} (images)"] = curve(vm, home, BIN)
            curves[f"{LABEL[m]} (ideal rings)"] = curve(ideal, home, BIN)
            maps[m] = (vm, s)
        ctx.number(f"robot_images:{tag}:mean_error_deg", s["mean_error_deg"])
        ctx.number(f"n:robot_images:{tag}:mean_error_deg", [s["points"]])  # the sample behind it: map points
        if ideal is not None:
            ctx.number(f"robot_images:{tag}:ideal_mean_error_deg", si["mean_error_deg"])
            ctx.number(f"n:robot_images:{tag}:ideal_mean_error_deg", [si["points"]])
        ctx.number(f"robot_images:{tag}:catchment_pct", c["catchment_pct"])
        ctx.number(f"n:robot_images:{tag}:catchment_pct", [c["releases"]])
        rows.append(
            {
                "method": label,
                "images: mean error °": s["mean_error_deg"],
                "images: e>45 %": s["gt45_pct"],
                "images: e>90 %": s["gt90_pct"],
                "ideal rings: mean error °": si["mean_error_deg"],
                "ideal rings: e>45 %": si["gt45_pct"],
                "catchment %": c["catchment_pct"],
                "invalid": s["invalid"],
            }
        )
    ctx.step("maps")
    fig, axes = subplots(1, 2, figsize=(12.0, 6.0))
    for ax, (m, (vm, s)), tag in zip(axes, maps.items(), "ab"):
        database_map_figure(db, vm, f"({tag}) {LABEL[m]}: mean error {s['mean_error_deg']:.1f}°", ax=ax)
    fig.set_layout_engine("tight")
    ctx.figure(
        "fig4_18_robot_maps.png",
        fig,
        "Fig 4.18: vector maps from the rendered images, (a) DELV, (b) "
        "predictive image matching on the gray ring (no compass; grid points within 10 cm of a "
        "landmark have no snapshot).",
    )
    ctx.figure(
        "fig4_19_robot_errors.png",
        error_curve_figure(curves, "Robot world: images against ideal rings (Fig 4.19)"),
        "Fig 4.19: mean angular error vs distance from home (95 % t intervals), images and ideal rings.",
    )
    ctx.csv("fig4_19_robot_errors.csv", rows=curves_rows(curves))
    ctx.table(
        "robot_images",
        "DELV and image matching on rendered robot images",
        rows,
        source="Figs 4.18-4.19",
        note="The thesis prints no numbers: its robot errors were larger than in simulation, 'most likely due "
        "to the landmark detection error'. Catchment: nearest-snapshot rollouts, landmarks ignored. Image "
        "matching on the mask ring errs as much on ideal rings: it is the method, not the images. MinWarping "
        "(Möller 2009; full run) reads the whole gray panorama, which the ring model has no counterpart of.",
    )
    qrows, qcurves, panels = [], {}, []
    for q in LEVELS:  # a traced leaf of DELV: one program for every level
        vm, ideal = (
            image_map(db, "delv", levels=q, scale=ROBOT_SCALE),
            ideal_map("robot", "delv", levels=q, scale=ROBOT_SCALE),
        )
        s, si = numbers(vm), numbers(ideal)
        qcurves[f"{q} level{'s' * (q > 1)}"] = curve(vm, home, BIN)
        ctx.number(f"robot_images:delv:Q{q}:mean_error_deg", s["mean_error_deg"])
        ctx.number(f"n:robot_images:delv:Q{q}:mean_error_deg", [s["points"]])
        qrows.append(
            {
                "levels": q,
                "images: mean error °": s["mean_error_deg"],
                "images: e>45 %": s["gt45_pct"],
                "ideal rings: mean error °": si["mean_error_deg"],
            }
        )
        if q != 2:
            panels.append((q, vm, s, perceived(db, DELV(levels=q, scale=ROBOT_SCALE))))
    ctx.step("quantization")
    fig, axes = subplots(1, len(panels), figsize=(5.2 * len(panels), 5.4))
    for ax, (q, vm, s, where), tag in zip(axes, panels, "abc"):
        database_map_figure(db, vm, f"({tag}) level {q}: mean error {s['mean_error_deg']:.1f}°", ax=ax, perceived=where)
    fig.set_layout_engine("tight")
    ctx.figure(
        "fig4_20_robot_quantized.png",
        fig,
        f"Fig 4.20: DELV with quantized distances (scale {ROBOT_SCALE:g} cm) on the images; white circles: "
        "the perceived landmark positions of the reference map (outside the panel when beyond the arena).",
    )
    ctx.figure(
        "fig4_21_robot_quantized_errors.png",
        error_curve_figure(
            {k: v for k, v in qcurves.items() if not k.startswith("4")},
            "DELV, quantized distances, robot images (Fig 4.21)",
        ),
        "Fig 4.21: error curves with 1, 2 and 5 levels (95 % t intervals).",
    )
    ctx.csv("fig4_21_robot_quantized_errors.csv", rows=curves_rows(qcurves))
    ctx.table(
        "robot_images_quantized",
        "DELV with quantized distances on rendered robot images",
        qrows,
        source="Figs 4.20-4.21",
        note="The thesis: the robot errors 'maintained similar level of errors with respect to the quantization "
        "level' as in simulation.",
    )
    ctx.step("done")
