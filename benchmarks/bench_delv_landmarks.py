"""Benchmark: DELV without a compass against the number of landmarks L (docs/model.md §3.3).

    python benchmarks/bench_delv_landmarks.py [--landmarks 4 8 16 32 64] [--spacing 50] [--smoke]

Each L runs in a fresh process (its own peak RSS): L landmarks (radius 5 cm) at random in a ring
150-400 cm around home in a 10 x 10 m arena, a vector map of `delv` at --spacing, mapped twice
(compile = first minus the warm call; warm = best of three more). Prints µs a point of wall time
and of CPU time (all threads: the fairer number on a shared machine), compile s, peak RSS, the local exponent between sizes, and the ratio the issue asks for: time a point at L = 32
over L = 8 (the pairing search of every rotation is O(L^2); it was O(L^3), 29x). To compare with
another checkout, run this file with PYTHONPATH pointing there (it only calls the public API).
--smoke: L = 4 only, a coarse grid, no ratio (the test suite runs it; tests/test_benchmarks_smoke.py).
"""

from __future__ import annotations

import argparse
import math

from child import run_child, save_json

CHILD = r"""
import json, math, resource, sys, time
import numpy as np, jax, delvjax
from delvjax.core.scene import Env
n_lm, spacing = int(sys.argv[1]), float(sys.argv[2])
rng = np.random.default_rng(n_lm)
r, t = rng.uniform(150.0, 400.0, n_lm), rng.uniform(0.0, 2 * math.pi, n_lm)
lms = np.stack([500.0 + r * np.cos(t), 500.0 + r * np.sin(t), np.full(n_lm, 5.0)], 1).astype(np.float32)
env = Env(landmarks=lms, valid=np.ones(n_lm, bool), home=np.array([500.0, 500.0], np.float32),
          arena=np.array([0.0, 0.0, 1000.0, 1000.0], np.float32), name=f"ring{n_lm}")
t0 = time.perf_counter()
vm = delvjax.vector_map(env, "delv", grid=delvjax.Grid(spacing=spacing), seed=0)
jax.block_until_ready(vm.error_deg)
first = time.perf_counter() - t0
warm, cpu = [], []
for seed in (1, 2, 3):
    t0, c0 = time.perf_counter(), time.process_time()
    jax.block_until_ready(delvjax.vector_map(env, "delv", grid=delvjax.Grid(spacing=spacing), seed=seed).error_deg)
    warm.append(time.perf_counter() - t0)
    cpu.append(time.process_time() - c0)
print(json.dumps({"points": int(vm.points.shape[0]), "seconds": min(warm), "cpu": min(cpu), "compile": first - min(warm),
                  "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def run(n_landmarks: int, spacing: float) -> dict:
    """One fresh process: {points, seconds (warm wall, best), cpu (warm CPU, best), compile, peak_rss_mb}."""
    return run_child(CHILD, n_landmarks, spacing)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--landmarks", type=int, nargs="+", default=[4, 8, 16, 32, 64])
    ap.add_argument("--spacing", type=float, default=50.0)
    ap.add_argument("--smoke", action="store_true", help="L = 4 on a 200 cm grid: that it runs, not how fast")
    ap.add_argument("--json", metavar="PATH", help="also write the ratio(s) and raw numbers here (speed_targets.py)")
    a = ap.parse_args()
    sizes, spacing = ([4], 200.0) if a.smoke else (a.landmarks, a.spacing)
    print(f"vector map of delv (no compass), {spacing:g} cm spacing; a fresh process per L")
    print(
        f"{'L':>4} {'points':>7} {'us/point':>9} {'CPU us/pt':>9} {'exponent':>9} {'compile s':>9} {'peak RSS MB':>12}"
    )
    per_point, per_point_cpu, last, raw = {}, {}, None, {}
    for n in sizes:
        r = raw[str(n)] = run(n, spacing)
        per_point[n], cpu = r["seconds"] / r["points"] * 1e6, r["cpu"] / r["points"] * 1e6
        per_point_cpu[n] = cpu
        slope = "" if last is None else f"{math.log(per_point[n] / per_point[last]) / math.log(n / last):.2f}"
        row = f"{n:4d} {r['points']:7d} {per_point[n]:9.1f} {cpu:9.1f} {slope:>9} {r['compile']:9.2f}"
        print(f"{row} {r['peak_rss_mb']:12.0f}")
        last = n
    ratio = ratio_cpu = None
    if 8 in per_point and 32 in per_point:
        ratio, ratio_cpu = per_point[32] / per_point[8], per_point_cpu[32] / per_point_cpu[8]
        print(f"time a point at L = 32 / L = 8: {ratio:.1f}x wall, {ratio_cpu:.1f}x CPU (issue 54 asks <= 20x)")
    save_json(a.json, {
        "spacing": spacing, "runs": raw, "us_per_point": {str(n): v for n, v in per_point.items()},
        "cpu_us_per_point": {str(n): v for n, v in per_point_cpu.items()}, "ratio_wall": ratio, "ratio_cpu": ratio_cpu,
    })  # fmt: skip


if __name__ == "__main__":
    main()
