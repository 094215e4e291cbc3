"""Rolled copies of an image database (issue 25; docs/images.md §6): the same poses, another column 0.

A rolled copy rolls every image i of a database by k_i whole pixels and rewrites its heading to
h_i + k_i * 2 pi / W, so each image still shows the same world from the same pose. The vector map of
every registry method (warping and MFDID on both channels) is computed on the original and on the
copy, and the directions compared point by point (home excluded).

Cases (env1 rendered at spacing 100 cm, 98 points, W = 360):

  a  one roll k = 37 for every image (no move turns: k_C - k_P = 0)
  b  a random roll per image (the stored headings differ from image to image; each view is rolled by
     its own pixels into the move's frame, so no move turns)
  b5 a random roll per image, a multiple of W / n_psi = 5 pixels (turns on warping's psi grid)
  c  re-rendered (no camera noise) at random whole-degree headings, against heading 0
  d  re-rendered (no camera noise) at random headings off the pixel lattice, against heading 0:
     the roll of `_plan` rounds to a whole pixel, so each view's column 0 is up to half a pixel
     from the move direction, and the images are sampled at other angles
  e  d's rendering against its own copy rolled by a random whole pixel per image: the rounding of
     `_plan` moves with the roll, so this is case b again (off-lattice headings)

Columns: points compared (valid in both), points that differ by more than 1e-4 deg, max and
median difference (deg), the bound stated for the method (docs/images.md §6).

    python benchmarks/rolled_copies.py
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import jax
import jax.numpy as jnp
import numpy as np

import delvjax
from delvjax.core.images.database import RingDatabase, rolled
from delvjax.images import render_in_memory
from delvjax.images._evaluate import LoadedDatabase, database_vector_map
from delvjax.images._render import ImageSettings, render_rings

ENV, SPACING, SEED = "env1", 100.0, 0
THRESHOLD_DEG = 1e-4

# bound per registry name (docs/images.md §6) for whole-pixel rolls (cases a, b, b5, e); "float" = float32
# rounding of the heading and bearing arithmetic only (the rolls are exact): measured up to 0.03 deg
# (MFDID, where its home vector is short), else below 0.001 deg. Cases c and d are re-renderings: their
# images differ (c: 3 of 35640 mask pixels at blob edges; d: sampled at other angles, frame rounded)
BOUNDS = {
    "alv": "float",
    "acv": "float",
    "cc": "float",
    "mfdid": "float",
    "alv-visual": "float",
    "acv-visual": "float",
    "delv-visual": "float",
    "delv-compass": "float",
    "delv-gap-compass": "float",
    "delv-refined": "float",
    "delv": "float; 2-landmark tie",
    "delv-gap": "float; 2-landmark tie",
    "delv-agent": "float; 2-landmark tie; a blob on the wrap",
    "delv-compass-agent": "float",
    "warping": "float",
}


def methods() -> list[tuple[str, dict]]:
    """Every registry method on its default channel, and the image methods on `gray` too."""
    out = [(name, {}) for name in delvjax.METHODS]
    return out + [("warping", {"channel": "gray"}), ("mfdid", {"channel": "gray"})]


def rolled_copy(db: LoadedDatabase, k) -> LoadedDatabase:
    """Every image i rolled by k[i] whole pixels, its heading rewritten to h_i + k_i * 2 pi / W."""
    rings = db.rings
    n_pix = rings.snapshots.mask.shape[-1]
    k = jnp.asarray(k, jnp.int32)
    snaps = jax.vmap(rolled)(rings.snapshots, k)
    headings = rings.headings + k.astype(jnp.float32) * jnp.float32(2 * np.pi / n_pix)
    return dataclasses.replace(db, rings=RingDatabase(snaps, rings.positions, headings))


def rerendered(db: LoadedDatabase, headings, seed: int = SEED) -> LoadedDatabase:
    """`db`'s positions rendered again (no camera noise) with column 0 along `headings` (rad)."""
    from delvjax.images._worlds import image_world

    settings = ImageSettings(camera=db.camera, pixel_noise=jnp.float32(0.0))
    pos = np.asarray(db.rings.positions, np.float64)
    head = np.asarray(headings, np.float32)
    rings = render_rings(image_world(db.name), settings, pos, head, jax.random.PRNGKey(seed), db.extractor)
    return dataclasses.replace(db, rings=rings)


def difference_deg(a, b) -> tuple[np.ndarray, int]:
    """|a - b| (deg) at the points valid in both maps, and how many points' validity differs."""
    inc = np.asarray(a.included)
    va, vb = np.asarray(a.valid)[inc], np.asarray(b.valid)[inc]
    da, db_ = np.asarray(a.direction)[inc], np.asarray(b.direction)[inc]
    both = va & vb
    d = np.abs((np.degrees(da - db_) + 180.0) % 360.0 - 180.0)[both]
    return d, int(np.sum(va != vb))


def main() -> None:
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    t0 = time.perf_counter()
    noisy = render_in_memory(ENV, spacing=SPACING, seed=SEED)
    clean = dataclasses.replace(noisy, rings=rerendered(noisy, np.zeros(len(noisy.rings.positions))).rings)
    n, n_pix = len(noisy.rings.positions), noisy.camera.cols
    rng = np.random.default_rng(SEED)
    cases = {
        "a": (noisy, rolled_copy(noisy, np.full(n, 37))),
        "b": (noisy, rolled_copy(noisy, rng.integers(0, n_pix, n))),
        "b5": (noisy, rolled_copy(noisy, 5 * rng.integers(0, n_pix // 5, n))),
        "c": (clean, rerendered(noisy, np.radians(rng.integers(0, 360, n)))),
        "d": (clean, rerendered(noisy, rng.uniform(0.0, 2 * np.pi, n))),
    }
    cases["e"] = (cases["d"][1], rolled_copy(cases["d"][1], rng.integers(0, n_pix, n)))
    print(f"{ENV}, spacing {SPACING:g} cm: {n} points, W = {n_pix}; rendered in {time.perf_counter() - t0:.1f} s")
    print(f"{'case':4} {'method':22} {'pts':>4} {'>1e-4':>6} {'max deg':>10} {'median':>10}  bound")
    maps = {}
    for case, (orig, copy) in cases.items():
        for name, opts in methods():
            label = name + (f" [{opts['channel']}]" if opts else "")
            key = (id(orig), label)
            if key not in maps:
                maps[key] = database_vector_map(orig, name, **opts)
            d, flips = difference_deg(maps[key], database_vector_map(copy, name, **opts))
            extra = f" (validity differs at {flips})" if flips else ""
            print(
                f"{case:4} {label:22} {d.size:4d} {int(np.sum(d > THRESHOLD_DEG)):6d} "
                f"{d.max(initial=0.0):10.4g} {np.median(d) if d.size else 0.0:10.3g}  {BOUNDS[name]}{extra}"
            )
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
