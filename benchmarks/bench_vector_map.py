"""Time vector maps (issue: DELV no-compass on env1, spacing 25 = 40x40 grid) against the NumPy twin.

Prints compile time and warm time (median; best) separately, the per-point time of the plain NumPy
reference (tests/twins/methods.py) on a subset of the same points, and the per-point ratio.
Run: python benchmarks/bench_vector_map.py [--methods delv alv ...] [--env env1] [--ref-points 20]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import jax

from delvjax import Grid

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the repository root: tests.twins
sys.path.insert(0, str(Path(__file__).resolve().parent))
from timing import reference_seconds_per_point, time_map_program

import delvjax
from delvjax.core.sensor import Sensor
from tests.twins import methods as ref


def bench(env_name: str, method: str, spacing: float, repeats: int, ref_points: int) -> dict:
    run = time_map_program(env_name, method, Sensor(), spacing, repeats)
    # the whole public call (grid, headings, errors: one jitted program) for reference
    delvjax.vector_map(env_name, method=method, grid=Grid(spacing=spacing)).error_deg.block_until_ready()
    t0 = time.perf_counter()
    delvjax.vector_map(env_name, method=method, grid=Grid(spacing=spacing)).error_deg.block_until_ready()
    api_s = time.perf_counter() - t0
    ref_per_point = reference_seconds_per_point(ref.reference_direction, run, method, ref_points)
    warm_s = statistics.median(run["warm"])
    n = run["points"].shape[0]
    return {
        "method": method,
        "points": n,
        "compile_s": run["compile_s"],
        "warm_ms": 1e3 * warm_s,
        "best_ms": 1e3 * min(run["warm"]),
        "api_warm_ms": 1e3 * api_s,
        "us_per_point": 1e6 * warm_s / n,
        "ref_ms_per_point": 1e3 * ref_per_point,
        "ratio": ref_per_point / (warm_s / n),
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--env", default="env1")
    p.add_argument("--methods", nargs="+", default=["delv"])
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--repeats", type=int, default=20)
    p.add_argument("--ref-points", type=int, default=20)
    a = p.parse_args()
    print(
        f"jax {jax.__version__} on {jax.devices()[0].platform} ({jax.device_count()} device), env {a.env}, spacing {a.spacing:g}"
    )
    print(
        f"{'method':13s} {'points':>6s} {'compile s':>9s} {'warm ms':>8s} {'best ms':>7s} {'api ms':>7s} {'us/pt':>7s} {'ref ms/pt':>9s} {'ratio':>8s}"
    )
    for m in a.methods:
        r = bench(a.env, m, a.spacing, a.repeats, a.ref_points)
        print(
            f"{r['method']:13s} {r['points']:6d} {r['compile_s']:9.2f} {r['warm_ms']:8.1f} {r['best_ms']:7.1f} {r['api_warm_ms']:7.1f} "
            f"{r['us_per_point']:7.1f} {r['ref_ms_per_point']:9.2f} {r['ratio']:7.0f}x",
            flush=True,
        )


if __name__ == "__main__":
    main()
