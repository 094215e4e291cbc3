"""Benchmark: a sweep against a loop of single calls (issue 54), and sweep throughput (cells per second)
on 1, 2 and 4 forced host devices and 2 processes.

    python benchmarks/bench_sweep.py [--kinds vector-map catchment] [--devices 1 2 4] [--processes 2]
                                     [--cells 1000] [--catchment-cells 100] [--versus N] [--repeats 2] [--smoke]

First, sweep versus loop: the cells of a vector-map sweep on env1 (seed x bearing noise, --versus cells, for
DELV and ALV) against a Python loop of `delvjax.vector_map` calls with the same settings, and a catchment sweep
of --versus/5 cells against a loop of `delvjax.catchment` calls; each side in fresh processes with an empty
compilation cache, interleaved (sweep, loop, loop, sweep, ...), --repeats times. Printed per side: CPU and
wall seconds of the first run (compilation included) and of a second run with other seeds (warm), and the
ratio loop / sweep (the issue's target: >= 1.5 with compilation, CPU seconds), and the bound on that ratio:
loop first / (loop first - loop warm), what a sweep that compiled as fast as one call and cost nothing
warm would reach (where it is under 1.5, the target is out of reach at this size on this machine).
--smoke: 4 cells on a 100 cm grid, ALV only, one repeat, no scaling table.

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

from child import run_child, save_json

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


VERSUS = r"""
import json, sys, time
import jax
import delvjax
from delvjax.sweeps._spec import parse_sweep
from delvjax.sweeps import run_sweep
side, kind, method, seeds, noises, spacing = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), float(sys.argv[6])
levels = [round(0.5 * i, 1) for i in range(noises)]
def sweep(first):
    axes = f'method = ["{method}"]\nseed = {{start = {first}, stop = {first + seeds - 1}}}\nbearing_noise_deg = {levels}'
    run_sweep(parse_sweep(f'[sweep]\nkind = "{kind}"\n[axes]\nenv = ["env1"]\n{axes}\nspacing = [{spacing}]\n'))
def loop(first):
    call = delvjax.vector_map if kind == "vector-map" else delvjax.catchment
    for seed in range(first, first + seeds):
        for noise in levels:
            out = call("env1", method, seed=seed, bearing_noise_deg=noise, grid=delvjax.Grid(spacing=spacing))
            jax.block_until_ready(out.error_deg if kind == "vector-map" else out)
run = sweep if side == "sweep" else loop
times = []
for first in (0, 1000):
    c, t = time.process_time(), time.perf_counter()
    run(first)
    times.append((time.process_time() - c, time.perf_counter() - t))
print(json.dumps({"first_cpu": times[0][0], "first_wall": times[0][1], "warm_cpu": times[1][0], "warm_wall": times[1][1]}))
"""


def versus(kind: str, method: str, cells: int, spacing: float, repeats: int) -> dict:
    """Sweep against loop, fresh processes with an empty cache, interleaved; prints the rows and the ratio,
    returns them (the best of each side, the ratios loop / sweep)."""
    noises = min(10, cells)
    seeds = max(1, cells // noises)
    runs: dict[str, list[dict]] = {"sweep": [], "loop": []}
    for r in range(repeats):
        for side in ("sweep", "loop") if r % 2 == 0 else ("loop", "sweep"):
            runs[side].append(run_child(VERSUS, side, kind, method, seeds, noises, spacing, DELVJAX_CACHE_DIR=""))
    best = {side: {k: min(x[k] for x in rs) for k in rs[0]} for side, rs in runs.items()}
    print(f"\n{method.upper()} {kind}: {seeds * noises} cells (seed x bearing noise), env1, {spacing:g} cm grid")
    print(f"{'side':>6} {'first cpu s':>11} {'first wall s':>12} {'warm cpu s':>10} {'warm wall s':>11}")
    for side, b in best.items():
        print(f"{side:>6} {b['first_cpu']:11.2f} {b['first_wall']:12.2f} {b['warm_cpu']:10.2f} {b['warm_wall']:11.2f}")
    s, lp = best["sweep"], best["loop"]
    print(
        f"loop / sweep, compile included: {lp['first_cpu'] / s['first_cpu']:.2f}x CPU, "
        f"{lp['first_wall'] / s['first_wall']:.2f}x wall (target >= 1.5); warm: {lp['warm_cpu'] / s['warm_cpu']:.2f}x CPU, "
        f"{lp['warm_wall'] / s['warm_wall']:.2f}x wall",
        flush=True,
    )
    bound = lp["first_wall"] / max(lp["first_wall"] - lp["warm_wall"], 1e-9)
    print(
        f"bound: a sweep that compiled no longer than one call and did no work at all would be {bound:.2f}x"
        " faster than the loop (loop first / (loop first - loop warm), wall): the ratio this comparison can reach"
    )
    return {
        "cells": seeds * noises, "spacing": spacing, "repeats": repeats, "sweep": s, "loop": lp,
        "first_cpu_ratio": lp["first_cpu"] / s["first_cpu"], "first_wall_ratio": lp["first_wall"] / s["first_wall"],
        "warm_cpu_ratio": lp["warm_cpu"] / s["warm_cpu"], "warm_wall_ratio": lp["warm_wall"] / s["warm_wall"],
        "bound_wall": bound,
    }  # fmt: skip


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
    ap.add_argument("--versus", type=int, default=100, help="vector-map cells of the sweep-versus-loop comparison")
    ap.add_argument("--repeats", type=int, default=2, help="fresh processes per side of the comparison")
    ap.add_argument("--versus-only", action="store_true", help="the comparison alone, no scaling table")
    ap.add_argument("--smoke", action="store_true", help="the ALV comparison on 4 cells, 100 cm grid, alone")
    ap.add_argument(
        "--json", metavar="PATH", help="also write the sweep-versus-loop ratios and raw numbers here (speed_targets.py)"
    )
    a = ap.parse_args()
    cells, spacing, repeats = (4, 100.0, 1) if a.smoke else (a.versus, 25.0, a.repeats)
    raw = {}
    if "vector-map" in a.kinds:
        for method in ("alv",) if a.smoke else ("delv", "alv"):
            raw[f"vector-map {method}"] = versus("vector-map", method, cells, spacing, repeats)
    if "catchment" in a.kinds and not a.smoke:
        raw["catchment delv"] = versus("catchment", "delv", max(2, cells // 5), spacing, repeats)
    save_json(a.json, {"versus": raw})
    if a.smoke or a.versus_only:
        return
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
