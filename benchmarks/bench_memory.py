"""Benchmark: peak memory (RSS) and time of a vector map against its number of grid points.

    python benchmarks/bench_memory.py [--points 1e4 1e5 1e6] [--method delv] [--batch 16384]

Each size runs in a fresh process (peak RSS is per process, `resource.getrusage`): env1's
landmarks and home in a square arena grown so that the docs/model.md §5 grid at 25 cm spacing has
about N cells. The grid runs in host-side chunks of --batch points (`core.maps.vector_map`), so
peak memory should stay flat: the per-point results (about 30 bytes a point) are the only part
that grows. Each process maps twice (new seed): compile = first minus second call, warm = second.
The last column is the same run with one chunk for the whole grid ("-" above 1e5 points).
"""

from __future__ import annotations

import argparse
import math

from child import run_child

CHILD = r"""
import json, resource, sys, time
import numpy as np, jax, delvjax
from delvjax.core.scene import Env
n, method, batch = int(float(sys.argv[1])), sys.argv[2], int(sys.argv[3])
base = delvjax.load_env("env1")
side = 25.0 * math.ceil(math.sqrt(n))
env = Env(landmarks=base.landmarks, home=np.asarray(base.home), arena=np.array([0.0, 0.0, side, side], np.float32),
          valid=base.valid, name="grown")
times = []
for seed in (0, 1):  # the first call compiles, the second is warm
    t = time.perf_counter()
    vm = delvjax.vector_map(env, method=method, batch_size=batch, max_points=10**8, seed=seed)
    jax.block_until_ready(vm)
    times.append(time.perf_counter() - t)
print(json.dumps({"points": int(vm.points.shape[0]), "seconds": times[1], "compile": times[0] - times[1],
                  "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
""".replace("import json,", "import math, json,")


def run(n: float, method: str, batch: int) -> dict:
    return run_child(CHILD, n, method, batch)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=float, nargs="+", default=[1e4, 1e5, 1e6])
    ap.add_argument("--method", default="delv")
    ap.add_argument("--batch", type=int, default=16384)
    a = ap.parse_args()
    print(f"vector map of {a.method}, chunks of {a.batch} points; peak RSS per fresh process")
    print(f"{'points':>9} {'compile s':>9} {'warm s':>8} {'points/s':>9} {'peak RSS MB':>12} {'one chunk MB':>13}")
    for n in a.points:
        r = run(n, a.method, a.batch)
        one = run(n, a.method, 10**9)["peak_rss_mb"] if n <= 1e5 else math.nan
        print(
            f"{r['points']:9d} {r['compile']:9.2f} {r['seconds']:8.2f} {r['points'] / r['seconds']:9.0f} {r['peak_rss_mb']:12.0f} "
            f"{'-' if math.isnan(one) else f'{one:.0f}':>13}"
        )


if __name__ == "__main__":
    main()
