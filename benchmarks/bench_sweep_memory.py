"""Benchmark: a sweep's peak memory does not grow with its number of cells (only its results do).

    python benchmarks/bench_sweep_memory.py [--cells 1000 10000 100000] [--spacing 250]

A DELV vector-map sweep on env1 with a small grid (--spacing, cm), d x seed with the given number
of cells, each size in a fresh process: peak resident memory (ru_maxrss) after `run_sweep`, the
time, and the memory the result itself takes. A call of a group's program holds CELL_CHUNK cells;
setups are validated first and rebuilt per chunk, so only per-cell digests, group indices and the
sums (a few dozen bytes a cell) grow with the sweep.
"""

from __future__ import annotations

import argparse

from child import run_child

CHILD = r"""
import json, resource, sys, time
from delvjax.sweeps._spec import parse_sweep
from delvjax.sweeps import run_sweep
from delvjax.sweeps._run import CELL_CHUNK
cells, spacing = int(sys.argv[1]), float(sys.argv[2])
spec = parse_sweep(f"[axes]\nd = {{start = 10, stop = 100, num = 100}}\nseed = {{start = 0, stop = {cells // 100 - 1}}}\n"
                   f"spacing = [{spacing}]\n")
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
t = time.perf_counter(); ds = run_sweep(spec); s = time.perf_counter() - t
print(json.dumps({"cells": int(ds.attrs["cells"]), "points": int(ds.points.values.flat[0]), "s": s,
                  "import_mb": base, "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "result_mb": ds.nbytes / 2**20, "chunk": CELL_CHUNK}))
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cells", type=int, nargs="+", default=[1000, 10000, 100000], help="multiples of 100")
    ap.add_argument("--spacing", type=float, default=250.0)
    a = ap.parse_args()
    print(
        f"{'cells':>7} {'points':>6} {'time s':>7} {'ms/cell':>7} {'after import MB':>15} {'peak MB':>8} "
        f"{'result MB':>9}"
    )
    for cells in a.cells:
        r = run_child(CHILD, cells, a.spacing, DELVJAX_CACHE_DIR="")
        print(
            f"{r['cells']:>7} {r['points']:>6} {r['s']:7.1f} {1000 * r['s'] / r['cells']:7.2f} {r['import_mb']:15.0f} "
            f"{r['peak_mb']:8.0f} {r['result_mb']:9.2f}",
            flush=True,
        )


if __name__ == "__main__":
    main()
