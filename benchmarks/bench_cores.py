"""Benchmark: one CPU device against the `delvjax` command's default (one per core), issue 54.

    python benchmarks/bench_cores.py [--rounds 2] [--reps 5] [--devices N] [--smoke]

Runs, each in a fresh process with no persistent compilation cache, and in turn (1 device, N devices,
1 device, ...: a loaded machine slows each alike), four workloads on env1:
  * map: a DELV vector map at spacing 10 cm (10 000 points);
  * catchment: an ALV catchment at spacing 25 cm (1600 rollouts);
  * success: a DELV success rate, 100 trials at each of 9 distances;
  * sweep: a catchment sweep of 20 cells (d x bearing noise x seed, DELV, spacing 25).
N is what `delvjax catchment` asks for (`cli._entry.host_devices`: one device per core; --devices
overrides), forced with `XLA_FLAGS=--xla_force_host_platform_device_count=N`. Printed per workload
and device count: the first call's compile seconds (JAX's compile events: trace, lowering, XLA), its
wall and CPU seconds (compile included), and the median wall and CPU seconds of --reps warm calls
(other seeds); then the 1-device / N-device ratio of warm and of first-call wall seconds against the
target (>= 1.6x on 2 cores). --smoke: an ALV map of 100 points, one round: that it runs (tests/test_benchmarks_smoke.py).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys

from child import run_child, save_json

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from delvjax.cli._entry import DEVICE_FLAG, host_devices  # noqa: E402  (no JAX: the parent stays light)

TARGET = 1.6  # 1 device / every core, on 2 cores (issue 54)

CHILD = r"""
import json, os, statistics, sys, time
import jax
jax.config.update("jax_enable_compilation_cache", False)
import delvjax
work, reps, smoke = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1"
EVENTS = ("/jax/core/compile/jaxpr_trace_duration", "/jax/core/compile/jaxpr_to_mlir_module_duration",
          "/jax/core/compile/backend_compile_duration")
log = [0.0]
jax.monitoring.register_event_duration_secs_listener(lambda e, d, **k: log.__setitem__(0, log[0] + d * (e in EVENTS)))
spacing = 100 if smoke else 10
def call(seed):
    if work == "map":
        return delvjax.vector_map("env1", "alv" if smoke else "delv", grid=delvjax.Grid(spacing=spacing), seed=seed).error_deg
    if work == "catchment":
        return delvjax.catchment("env1", "alv", grid=delvjax.Grid(spacing=100 if smoke else 25), seed=seed).outcome
    if work == "success":
        few = {"method": "alv", "trials": 3, "distances": [100.0]} if smoke else {"method": "delv", "trials": 100}
        return delvjax.success_rate("env1", seed=seed, **few).outcome
    from delvjax.sweeps import run_sweep
    from delvjax.sweeps._spec import parse_sweep
    d = "[10, 20]" if smoke else "{start = 10, stop = 50, num = 5}"
    seeds = f"[{seed}]" if smoke else f"{{start = {seed}, stop = {seed + 1}}}"
    grid = "spacing = [100]\n" if smoke else ""
    spec = f'[sweep]\nkind = "catchment"\n[axes]\n{grid}d = {d}\nbearing_noise_deg = [0, 2]\nseed = {seeds}\n'
    return run_sweep(parse_sweep(spec)).catchment_pct.values
def timed(seed):
    c, w, k = time.process_time(), time.perf_counter(), log[0]
    jax.block_until_ready(call(seed))
    return time.perf_counter() - w, time.process_time() - c, log[0] - k
first = timed(0)
warm = [timed(1000 + i) for i in range(reps)]
print(json.dumps({"devices": jax.device_count(), "first_wall": first[0], "first_cpu": first[1], "compile": first[2],
                  "warm_wall": statistics.median(w for w, _, _ in warm), "warm_cpu": statistics.median(c for _, c, _ in warm)}))
"""
WORKS = ("map", "catchment", "success", "sweep")


def measure(work: str, devices: int, reps: int, smoke: bool) -> dict:
    flags = f"{os.environ.get('XLA_FLAGS', '')} {DEVICE_FLAG}={devices}".strip()
    return run_child(CHILD, work, reps, int(smoke), XLA_FLAGS=flags, DELVJAX_CACHE_DIR="", JAX_PLATFORMS="cpu")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rounds", type=int, default=2, help="fresh processes per workload and device count")
    p.add_argument("--reps", type=int, default=5, help="warm calls per process (their median is kept)")
    p.add_argument("--devices", type=int, default=0, help="the N compared to 1 (default: the CLI's default)")
    p.add_argument("--works", nargs="+", choices=WORKS, default=list(WORKS))
    p.add_argument("--smoke", action="store_true", help="a tiny map, one round: that the script runs")
    p.add_argument("--json", metavar="PATH", help="also write the ratio(s) and raw numbers here (speed_targets.py)")
    a = p.parse_args()
    if DEVICE_FLAG in os.environ.get("XLA_FLAGS", ""):
        raise SystemExit(f"XLA_FLAGS sets {DEVICE_FLAG}: this script sets it itself")
    n = a.devices or max(host_devices("catchment", {}), 1)
    rounds, reps, works = (1, 1, ["map"]) if a.smoke else (a.rounds, a.reps, a.works)
    if n == 1:
        print("this process may run on one core only: 1 device is the default; comparing 1 with 2")
        n = 2
    print(f"{os.cpu_count()} cores; 1 device vs {n} forced host devices; rounds {rounds}, warm reps {reps}")
    print(
        f"{'work':10s} {'dev':>3s} {'compile s':>9s} {'first wall':>10s} {'first CPU':>9s} {'warm wall':>9s} {'warm CPU':>8s}"
    )
    raw = {}
    for work in works:
        runs: dict[int, list[dict]] = {1: [], n: []}
        for _ in range(rounds):
            for devices in (1, n):
                m = measure(work, devices, reps, a.smoke)
                runs[devices].append(m)
                print(
                    f"{work:10s} {devices:3d} {m['compile']:9.2f} {m['first_wall']:10.2f} {m['first_cpu']:9.2f}"
                    f" {m['warm_wall']:9.3f} {m['warm_cpu']:8.3f}",
                    flush=True,
                )
        best = {d: {k: min(r[k] for r in rs) for k in rs[0]} for d, rs in runs.items()}
        warm = best[1]["warm_wall"] / max(best[n]["warm_wall"], 1e-9)
        first = best[1]["first_wall"] / max(best[n]["first_wall"], 1e-9)
        share = statistics.mean(r["compile"] / max(r["first_wall"], 1e-9) for r in runs[1])
        verdict = "meets" if warm >= TARGET else "misses"
        print(
            f"{work}: 1 device / {n} devices, warm {warm:.2f}x ({verdict} >= {TARGET:g}x), first call {first:.2f}x"
            f" (compile {100 * share:.0f} % of a first call's wall on 1 device)"
        )
        raw[work] = {"one": best[1], "every": best[n], "warm_ratio": warm, "first_ratio": first, "compile_share": share}
    save_json(a.json, {"devices": n, "rounds": rounds, "reps": reps, "works": raw})


if __name__ == "__main__":
    main()
