"""Benchmark: sweep throughput (cells per second) on 1, 2 and 4 forced host devices and 2 processes.

    python benchmarks/bench_sweep.py [--kinds vector-map catchment] [--devices 1 2 4] [--processes 2]
                                     [--cells 1000] [--catchment-cells 100]

Two sweeps on env1, DELV:
  * vector-map: 40 x 40 grid, d x bearing noise x seed, --cells cells (10 x 10 x cells/100);
  * catchment: a rollout from each of the 1559 grid points (25 cm), d x bearing noise x seed,
    --catchment-cells cells (5 x 2 x cells/10).
Each setting runs in fresh processes: forced host devices with
`XLA_FLAGS=--xla_force_host_platform_device_count=N`, and P processes of one device each joined by
`jax.distributed` on 127.0.0.1 (gloo). Printed: the first run (compilation included), a second
run with other seeds (warm), cells per second warm, and the scaling efficiency against one device
(speedup / devices or processes). Forced host devices and local processes share the machine's
cores, so on 2 cores nothing beyond 2 can scale; on a GPU machine the same script measures the GPU.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import subprocess
import sys

from child import run_child

CHILD = r"""
import json, sys, time
import jax
kind, seeds, process, processes, port = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
if processes > 1:
    jax.config.update("jax_cpu_collectives_implementation", "gloo")
    jax.distributed.initialize(f"127.0.0.1:{port}", processes, process)
from delvjax.sweeps._spec import parse_sweep
from delvjax.sweeps import run_sweep
def spec(first):
    if kind == "vector-map":
        axes = "d = {start = 10, stop = 100, num = 10}\nbearing_noise_deg = {start = 0, stop = 4.5, step = 0.5}"
    else:
        axes = "d = {start = 10, stop = 50, num = 5}\nbearing_noise_deg = [0, 2]"
    return parse_sweep(f'[sweep]\nkind = "{kind}"\n[axes]\n{axes}\nseed = {{start = {first}, stop = {first + seeds - 1}}}\n')
t = time.perf_counter(); ds = run_sweep(spec(0)); first = time.perf_counter() - t
t = time.perf_counter(); run_sweep(spec(1000)); warm = time.perf_counter() - t
print(json.dumps({"devices": jax.device_count(), "processes": jax.process_count(),
                  "platform": jax.devices()[0].platform, "cells": int(ds.attrs["cells"]), "first_s": first,
                  "warm_s": warm, "programs": int(ds.attrs["programs_compiled"])}))
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run_devices(kind: str, devices: int, seeds: int) -> dict:
    return run_child(
        CHILD, kind, seeds, 0, 1, 0, XLA_FLAGS=f"--xla_force_host_platform_device_count={devices}", DELVJAX_CACHE_DIR=""
    )


def run_processes(kind: str, processes: int, seeds: int) -> dict:
    port = free_port()
    env = {**os.environ, "DELVJAX_CACHE_DIR": "", "JAX_PLATFORMS": "cpu"}
    procs = [
        subprocess.Popen(
            [sys.executable, "-c", CHILD, kind, str(seeds), str(p), str(processes), str(port)],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for p in range(processes)
    ]
    outs = [p.communicate() for p in procs]
    if any(p.returncode for p in procs):
        raise SystemExit("\n".join(o[1][-2000:] for o in outs))
    return json.loads(outs[0][0].strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kinds", nargs="+", default=["vector-map", "catchment"], choices=["vector-map", "catchment"])
    ap.add_argument("--devices", type=int, nargs="+", default=[1, 2, 4])
    ap.add_argument("--processes", type=int, nargs="*", default=[2])
    ap.add_argument("--cells", type=int, default=1000, help="vector-map cells, a multiple of 100")
    ap.add_argument("--catchment-cells", type=int, default=100, help="catchment cells, a multiple of 10")
    a = ap.parse_args()
    for kind in a.kinds:
        seeds = max(1, a.cells // 100) if kind == "vector-map" else max(1, a.catchment_cells // 10)
        grid = "40 x 40 grid" if kind == "vector-map" else "1559 rollouts a cell"
        print(f"\nDELV {kind} sweep, env1, {grid}; cpu count {os.cpu_count()}")
        print(
            f"{'setting':>12} {'first s':>8} {'warm s':>7} {'cells':>6} {'cells/s':>8} {'efficiency':>10} "
            f"{'programs':>8}"
        )
        base = None
        runs = [(f"{d} device(s)", d, run_devices(kind, d, seeds)) for d in a.devices]
        runs += [(f"{p} processes", p, run_processes(kind, p, seeds)) for p in a.processes]
        for label, scale, r in runs:
            rate = r["cells"] / r["warm_s"]
            base = rate if base is None and scale == 1 else base
            eff = f"{rate / (base * scale):.2f}" if base else "-"
            print(
                f"{label:>12} {r['first_s']:8.1f} {r['warm_s']:7.1f} {r['cells']:>6} {rate:8.1f} {eff:>10} "
                f"{r['programs']:>8}  ({r['platform']})",
                flush=True,
            )


if __name__ == "__main__":
    main()
