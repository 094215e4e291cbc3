"""How the image path changes homing (beyond the thesis; docs/images.md §8): DELV, ALV, ACV and
predictive image matching on the rendered `robot` world as one setting changes at a time, against
the ideal rings of the ring model on the same layout.

Settings: panorama width (resolution), band height, hue threshold width, camera noise, and
lighting (the home record taken under the world's light, homing under a light turned by 90-270°). Image
matching reads the gray ring, so lighting and noise reach it; the landmark methods read blobs of
the red threshold.
Every setting but the width is a traced leaf: one compiled program per width. A full run adds
MinWarping on the gray panoramas (docs/model.md §4.7), which no ring setting reaches.
"""

from __future__ import annotations

import hashlib

import equinox as eqx
import numpy as np

from delvjax.core.methods.minwarping import hypothesis_counts
from delvjax.images import ImageSettings, image_world
from delvjax.images._render import camera
from delvjax.plots import subplots

from ._images_common import CAMERA_NOISE, LABEL, METHODS, database, ideal_map, image_map, numbers, preview

TITLE = "The image path: resolution, band, threshold, noise and lighting (beyond the thesis)"
COST = 95  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 5
FACTORS = {  # factor -> (values, label, values of --quick)
    "cols": ((72, 144, 360, 720), "panorama width (pixels)", (360,)),  # another width is another program
    "band_height_deg": ((2.0, 5.0, 10.0, 20.0, 40.0), "band height (deg)", (2.0, 10.0, 40.0)),
    "hue_width_deg": ((10.0, 20.0, 40.0, 80.0), "hue window (deg)", (10.0, 40.0)),
    "pixel_noise": ((0.0, 0.02, 0.05, 0.1, 0.2), "camera noise (of full scale)", (0.0, 0.05, 0.2)),
    "light_turn_deg": ((0.0, 90.0, 180.0, 270.0), "light turned after the home record (deg)", (0.0, 180.0)),
}


def _database(factor: str, value, seed: int, panoramas: bool = False):
    """The robot database with one setting changed, and the rings of the home record (with the gray
    panoramas too where MinWarping runs)."""
    kw = {"panoramas": panoramas}
    if factor == "cols":
        return database(
            "robot",
            ImageSettings(
                camera=camera(cols=int(value)), pixel_noise=CAMERA_NOISE.pixel_noise, gain_noise=CAMERA_NOISE.gain_noise
            ),
            seed,
            **kw,
        ), None
    if factor == "pixel_noise":
        return database(
            "robot", ImageSettings(pixel_noise=float(value), gain_noise=CAMERA_NOISE.gain_noise), seed, **kw
        ), None
    if factor == "light_turn_deg":
        turned = ImageSettings(
            pixel_noise=CAMERA_NOISE.pixel_noise,
            gain_noise=CAMERA_NOISE.gain_noise,
            light_azimuth_deg=45.0 + float(value),
        )
        db = database("robot", turned, seed, **kw)
        home = database("robot", seed=seed, **kw)  # the home record under the world's light (azimuth 45°)
        return db, home.rings
    ex = image_world("robot").extractor
    ex = eqx.tree_at(lambda e: getattr(e, factor), ex, float(value))
    return database("robot", extractor=ex, seed=seed, **kw), None


def mw_grid(cols: int) -> dict:
    """MinWarping's hypotheses on `cols`-column panoramas: the most, up to the authors' 96, that divide them."""
    n = max(k for k in hypothesis_counts(cols) if k <= 96)
    return {"n_alpha": n, "n_psi": n}


def panorama_key(db, home_rings) -> str:
    """A digest of all that MinWarping reads from a database: its panoramas and those of the home record,
    the camera's elevations, the positions and headings (equal digests, equal maps)."""
    digest = hashlib.sha256()
    home = db.rings if home_rings is None else home_rings
    rings = (db.rings.snapshots.panorama, home.snapshots.panorama, db.rings.snapshots.elevations)
    for a in (*rings, db.rings.positions, db.rings.headings):
        digest.update(np.ascontiguousarray(np.asarray(a)).tobytes())
    return digest.hexdigest()


def run(ctx) -> None:
    quick = preview(ctx)
    ideal = {m: numbers(ideal_map("robot", m))["mean_error_deg"] for m in METHODS}
    methods = METHODS if quick else (*METHODS, "minwarping")  # MinWarping on the panoramas: a full run
    ideal["minwarping"] = None  # it reads panoramas, not the rings of the ring model
    rows, panorama_maps = [], {}
    for factor, (values, label, quick_values) in FACTORS.items():
        for v in quick_values if quick else values:
            db, home_rings = _database(factor, v, ctx.config.seed, panoramas=not quick)
            for m in methods:
                if m == "minwarping":  # band and hue window do not reach the panoramas: one search for equal ones
                    key = panorama_key(db, home_rings)
                    if key not in panorama_maps:
                        panorama_maps[key] = image_map(db, m, home_rings=home_rings, **mw_grid(db.camera.cols))
                    s = numbers(panorama_maps[key])
                else:
                    s = numbers(image_map(db, m, home_rings=home_rings))
                rows.append(
                    {
                        "factor": factor,
                        "value": v,
                        "method": LABEL[m],
                        "mean error °": s["mean_error_deg"],
                        "e>45 %": s["gt45_pct"],
                        "e>90 %": s["gt90_pct"],
                        "invalid": s["invalid"],
                        "ideal rings: mean error °": ideal[m],
                    }
                )
                ctx.number(f"image_effects:{factor}={v}:{m}:mean_error_deg", s["mean_error_deg"])
        ctx.step(factor)
    ctx.table(
        "image_effects",
        "Mean angular error on rendered robot images as one setting of the image path changes",
        rows,
        source="beyond the thesis",
        note="Defaults: 360 x 60 panorama, 10° band, red ±20°, camera noise 0.02 with 3 % gain noise, light at "
        "45°. The ideal-ring column is the ring model on the same layout and grid. A full run adds MinWarping "
        "on the gray panoramas (the authors' settings, 90 x 90 hypotheses on 360 columns; no ideal rings: "
        "band and hue window do not reach it: where a setting leaves the panoramas as they were, its map is "
        "computed once and repeated).",
    )
    fig, axes = subplots(1, len(FACTORS), figsize=(3.6 * len(FACTORS), 3.6), sharey=True)
    for ax, (factor, (_, label, _)) in zip(axes, FACTORS.items()):
        for i, m in enumerate(methods):
            pts = [(r["value"], r["mean error °"]) for r in rows if r["factor"] == factor and r["method"] == LABEL[m]]
            color = f"C{i}"
            ax.plot(*zip(*pts), "o-", color=color, label=LABEL[m])
            if ideal[m] is not None:
                ax.axhline(ideal[m], color=color, ls=":", lw=1)
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("mean angular error (deg)")
    axes[0].legend(fontsize=7)
    fig.suptitle("Image path settings against the ideal rings (dotted), robot world")
    fig.set_layout_engine("tight")
    ctx.figure(
        "image_effects.png",
        fig,
        "Mean angular error of each method as one image setting changes; dotted: "
        "the same method on the ideal rings of the ring model.",
    )
