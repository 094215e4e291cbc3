"""Benchmark: vector-map sweep throughput (cells per second) on 1, 2 and 4 forced host devices.

    python benchmarks/bench_sweep.py [--devices 1 2 4] [--cells 1000]

A DELV sweep on env1 (40 x 40 grid): d x bearing noise x seed with --cells cells (10 x 10 x
cells/100), each device count in a fresh process (`XLA_FLAGS=--xla_force_host_platform_device_count=N`).
Printed: the first run (compilation included), a second run with other seeds (warm), cells per
second warm, and the scaling efficiency against one device (speedup / devices). Forced host
devices share the machine's cores, so on 2 cores more than 2 devices cannot scale; on a GPU
machine the same script measures the GPU (one device). Catchment sweeps are not implemented yet.
"""

from __future__ import annotations

import argparse
import os

from child import run_child

CHILD = r"""
import json, sys, time
import jax
from delvjax.sweep_spec import parse_sweep
from delvjax.sweeps import run_sweep
seeds = int(sys.argv[1])
def spec(first):
    return parse_sweep(f'''
[axes]
d = {{start = 10, stop = 100, num = 10}}
bearing_noise_deg = {{start = 0, stop = 4.5, step = 0.5}}
seed = {{start = {first}, stop = {first + seeds - 1}}}
''')
t = time.perf_counter(); ds = run_sweep(spec(0)); first = time.perf_counter() - t
t = time.perf_counter(); run_sweep(spec(1000)); warm = time.perf_counter() - t
print(json.dumps({"devices": jax.local_device_count(), "platform": jax.devices()[0].platform,
                  "cells": int(ds.attrs["cells"]), "first_s": first, "warm_s": warm,
                  "programs": int(ds.attrs["programs_compiled"])}))
"""


def run(devices: int, seeds: int) -> dict:
    return run_child(CHILD, seeds, XLA_FLAGS=f"--xla_force_host_platform_device_count={devices}", DELVJAX_CACHE_DIR="")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--devices", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--cells", type=int, default=1000, help="a multiple of 100")
    a = ap.parse_args()
    seeds = max(1, a.cells // 100)
    print(f"DELV vector-map sweep, env1 40 x 40, {seeds * 100} cells; cpu count {os.cpu_count()}")
    print(f"{'devices':>7} {'first s':>8} {'warm s':>7} {'cells/s':>8} {'efficiency':>10} {'programs':>8}")
    base = None
    for d in a.devices:
        r = run(d, seeds)
        rate = r["cells"] / r["warm_s"]
        if d == 1:
            base = rate
        eff = f"{rate / (base * d):.2f}" if base else "-"
        print(f"{r['devices']:>7} {r['first_s']:8.1f} {r['warm_s']:7.1f} {rate:8.1f} {eff:>10} {r['programs']:>8}"
              f"  ({r['platform']})")


if __name__ == "__main__":
    main()
