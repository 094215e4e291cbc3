"""Time the image path (issue: a 40x40 database of 360x60 panoramas rendered and evaluated in < 10 s
on the 2-core CPU): render every panorama, reduce it to a ring (HSV, threshold, band, blobs) and
evaluate a method on the database, in a fresh process so the first run includes compilation.

Rows: in memory (render -> rings -> vector map, no files), and through files (render-db writes the
BoB database, load_database reads it back, vector map). The per-image time of the plain NumPy
reference (tests/twins/images.py) on a few images gives the ratio.
Run: python benchmarks/bench_images.py [--env env1] [--spacing 25] [--methods delv alv acv warping] [--smoke]
--smoke: a 200 cm grid, in memory, one reference image: that it runs, not how fast (the test suite
runs it, tests/test_benchmarks_smoke.py).
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import sys, time, json
t0 = time.perf_counter()
import numpy as np, jax
from delvjax import images as I
env, spacing, method, mode, folder = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
t_import = time.perf_counter() - t0
def run():
    if mode == "memory":
        db = I.render_in_memory(env, spacing)
    else:
        shutil.rmtree(folder, ignore_errors=True)
        I.render_database(env, folder, spacing)
        db = I.load_database(folder)
    vm = I.database_vector_map(db, method)
    vm.error_deg.block_until_ready()
    return db, vm
import shutil
t1 = time.perf_counter(); db, vm = run(); first = time.perf_counter() - t1
t2 = time.perf_counter(); db, vm = run(); warm = time.perf_counter() - t2
inc = np.asarray(vm.included)
import resource
print(json.dumps({"peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,"images": len(np.asarray(db.rings.positions)), "cols": db.camera.cols, "rows": db.camera.rows,
                  "import_s": t_import, "first_s": first, "warm_s": warm,
                  "mean_error_deg": float(np.asarray(vm.error_deg)[inc].mean())}))
"""


def child(env: str, spacing: float, method: str, mode: str) -> dict:
    import json

    folder = tempfile.mkdtemp(prefix="bench-images-")
    try:
        out = subprocess.run(
            [sys.executable, "-c", CHILD, env, str(spacing), method, mode, folder + "/db"],
            capture_output=True,
            text=True,
            check=True,
            cwd=ROOT,
        )
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def reference_seconds_per_image(env: str, n: int) -> float:
    """Per-image wall time of the NumPy reference (tests/twins/images.py): render a 360 x 60
    panorama, then band rings and blobs, at `n` poses."""
    sys.path.insert(0, str(ROOT))  # the repository root: tests.twins
    import numpy as np

    from delvjax.images._worlds import image_world
    from tests.twins import images as ref

    iw = image_world(env)
    a = np.asarray(iw.world.arena)
    pts = np.stack([np.linspace(a[0] + 50, a[2] - 50, n), np.linspace(a[1] + 60, a[3] - 40, n)], -1)
    t0 = time.perf_counter()
    for p in pts:  # the reference is per pixel by design
        share, _ = ref.band_rings(ref.panorama(ref.world_dict(iw.world), p, 0.0, 60, 360))
        ref.ring_blobs(share)
    return (time.perf_counter() - t0) / n


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--env", default="env1")
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--methods", nargs="+", default=["delv"])
    p.add_argument("--ref-images", type=int, default=2)
    p.add_argument("--modes", nargs="+", default=["memory", "files"], choices=["memory", "files"])
    p.add_argument("--smoke", action="store_true", help="a coarse grid, in memory only: that it runs")
    a = p.parse_args()
    if a.smoke:
        a.spacing, a.modes, a.ref_images = 200.0, ["memory"], 1
    print(f"env {a.env}, spacing {a.spacing:g} cm (fresh process per row; first run includes compilation)")
    print(
        f"{'method':10s} {'mode':7s} {'images':>6s} {'size':>7s} {'first s':>8s} {'warm s':>7s} {'ms/img':>7s} "
        f"{'error':>6s} {'RSS MB':>7s}"
    )
    warm_per_image = None
    for m in a.methods:
        for mode in a.modes:
            r = child(a.env, a.spacing, m, mode)
            ms = 1e3 * r["warm_s"] / r["images"]
            warm_per_image = warm_per_image or r["warm_s"] / r["images"]
            print(
                f"{m:10s} {mode:7s} {r['images']:6d} {r['cols']:3d}x{r['rows']:<3d} {r['first_s']:8.2f} "
                f"{r['warm_s']:7.2f} {ms:7.2f} {r['mean_error_deg']:6.1f} {r['peak_rss_mb']:7.0f}",
                flush=True,
            )
    ref = reference_seconds_per_image(a.env, a.ref_images)
    print(
        f"NumPy reference: {ref * 1e3:.0f} ms per image (render, band rings, blobs); the whole path above "
        f"(render, rings, vector map) per image, warm: {warm_per_image * 1e3:.2f} ms; ratio {ref / warm_per_image:.0f}x"
    )


if __name__ == "__main__":
    main()
