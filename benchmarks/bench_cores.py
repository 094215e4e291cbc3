"""Benchmark: the same work on one core and on every core (issue 54: "on 2 cores >= 1.6x faster than on 1 core").

    python benchmarks/bench_cores.py [--rounds 2] [--reps 5] [--devices N] [--smoke]

Four workloads on env1, each run in a fresh process with no persistent compilation cache:
  * map: a DELV vector map at spacing 10 cm (10 000 points);
  * catchment: an ALV catchment at spacing 25 cm (1600 rollouts);
  * success: a DELV success rate, 100 trials at each of 9 distances;
  * sweep: a catchment sweep of 20 cells (d x bearing noise x seed, DELV, spacing 25).
Three settings, in turn (a loaded machine slows each alike):
  * "1 core": the process pinned to one core (`os.sched_setaffinity`), one device: what the command
    gets on a one-core machine;
  * "every core, 1 dev": every core, one CPU device (XLA's own threads: compilation and large operations);
  * "every core, N dev": every core, N forced host devices (`XLA_FLAGS=--xla_force_host_platform_device_count=N`,
    N = one per core, or --devices).
The command's default on every core is one of the last two: N devices for `delvjax catchment` and
`delvjax sweep`, one for `vector-map` and `success-rate` (`cli._entry.EVERY_CORE`). Printed per workload and
setting: the first call's compile seconds (JAX's compile events: trace, lowering, XLA), its wall and CPU
seconds (compile included: what a user of a fresh process waits for), and the median wall and CPU seconds
of --reps warm calls (other seeds); then the ratios 1 core / the default on every core, of the first call
and of the warm calls, against the target (>= 1.6x on 2 cores). --smoke: an ALV map of 100 points, one
round: that it runs (tests/test_benchmarks_smoke.py). --large: the map at 4 cm (62 500 points) and the
catchment at 8 cm (about 15 000 rollouts), where a warm call lasts long enough for the cores to share it (not
the issue's sizes; speed_targets.py runs without it).
"""

from __future__ import annotations

import argparse
import os
import sys

from child import run_child, save_json

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from delvjax.cli._entry import DEVICE_FLAG, EVERY_CORE, host_devices  # noqa: E402  (no JAX: the parent stays light)

TARGET = 1.6  # 1 core / every core, on 2 cores (issue 54)

CHILD = r"""
import json, os, statistics, sys, time
if sys.argv[4] == "1":  # pinned to one core before JAX starts its threads
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
import jax
jax.config.update("jax_enable_compilation_cache", False)
import delvjax
work, reps, smoke, large = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1", sys.argv[5] == "1"
EVENTS = ("/jax/core/compile/jaxpr_trace_duration", "/jax/core/compile/jaxpr_to_mlir_module_duration",
          "/jax/core/compile/backend_compile_duration")
log = [0.0]
jax.monitoring.register_event_duration_secs_listener(lambda e, d, **k: log.__setitem__(0, log[0] + d * (e in EVENTS)))
spacing = 100 if smoke else 4 if large else 10
def call(seed):
    if work == "map":
        return delvjax.vector_map("env1", "alv" if smoke else "delv", grid=delvjax.Grid(spacing=spacing), seed=seed).error_deg
    if work == "catchment":
        return delvjax.catchment("env1", "alv", grid=delvjax.Grid(spacing=100 if smoke else 8 if large else 25), seed=seed).outcome
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
print(json.dumps({"devices": jax.device_count(), "cores": len(os.sched_getaffinity(0)), "first_wall": first[0], "first_cpu": first[1], "compile": first[2],
                  "warm_wall": statistics.median(w for w, _, _ in warm), "warm_cpu": statistics.median(c for _, c, _ in warm)}))
"""
WORKS = ("map", "catchment", "success", "sweep")
COMMAND = {"map": "vector-map", "catchment": "catchment", "success": "success-rate", "sweep": "sweep"}


def measure(work: str, one_core: bool, devices: int, reps: int, smoke: bool, large: bool = False) -> dict:
    flags = f"{os.environ.get('XLA_FLAGS', '')} {DEVICE_FLAG}={devices}".strip()
    return run_child(
        CHILD,
        work,
        reps,
        int(smoke),
        int(one_core),
        int(large),
        XLA_FLAGS=flags,
        DELVJAX_CACHE_DIR="",
        JAX_PLATFORMS="cpu",
    )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rounds", type=int, default=2, help="fresh processes per workload and setting")
    p.add_argument("--reps", type=int, default=5, help="warm calls per process (their median is kept)")
    p.add_argument("--devices", type=int, default=0, help="the N of every core, N dev (default: one per core)")
    p.add_argument("--works", nargs="+", choices=WORKS, default=list(WORKS))
    p.add_argument("--smoke", action="store_true", help="a tiny map, one round: that the script runs")
    p.add_argument(
        "--large", action="store_true", help="more work a call: the map at 4 cm (62 500 points), the catchment at 8 cm"
    )
    p.add_argument("--json", metavar="PATH", help="also write the ratio(s) and raw numbers here (speed_targets.py)")
    a = p.parse_args()
    if DEVICE_FLAG in os.environ.get("XLA_FLAGS", ""):
        raise SystemExit(f"XLA_FLAGS sets {DEVICE_FLAG}: this script sets it itself")
    cores = len(os.sched_getaffinity(0))
    n = a.devices or max(host_devices("catchment", {}), 2)
    rounds, reps, works = (1, 1, ["map"]) if a.smoke else (a.rounds, a.reps, a.works)
    if cores == 1:
        print("this process may run on one core only: 'every core' is that core (the ratios say nothing)")
    settings = {"1 core": (True, 1), "every core, 1 dev": (False, 1), f"every core, {n} dev": (False, n)}
    print(f"{cores} cores; rounds {rounds}, warm reps {reps}")
    print(
        f"{'work':10s} {'setting':>18s} {'compile s':>9s} {'first wall':>10s} {'first CPU':>9s}"
        f" {'warm wall':>9s} {'warm CPU':>8s}"
    )
    raw = {}
    for work in works:
        runs: dict[str, list[dict]] = {label: [] for label in settings}
        for _ in range(rounds):
            for label, (one_core, devices) in settings.items():
                m = measure(work, one_core, devices, reps, a.smoke, a.large)
                runs[label].append(m)
                print(
                    f"{work:10s} {label:>18s} {m['compile']:9.2f} {m['first_wall']:10.2f} {m['first_cpu']:9.2f}"
                    f" {m['warm_wall']:9.3f} {m['warm_cpu']:8.3f}",
                    flush=True,
                )
        best = {label: {k: min(r[k] for r in rs) for k in rs[0]} for label, rs in runs.items()}
        default = f"every core, {n} dev" if COMMAND[work] in EVERY_CORE else "every core, 1 dev"
        one, every = best["1 core"], best[default]
        first = one["first_wall"] / max(every["first_wall"], 1e-9)
        warm = one["warm_wall"] / max(every["warm_wall"], 1e-9)
        devices_warm = one["warm_wall"] / max(best[f"every core, {n} dev"]["warm_wall"], 1e-9)
        print(
            f"{work}: 1 core / every core (`delvjax {COMMAND[work]}`'s default, {default}): first call {first:.2f}x"
            f" ({'meets' if first >= TARGET else 'misses'} >= {TARGET:g}x), warm {warm:.2f}x"
            f" ({'meets' if warm >= TARGET else 'misses'}); warm on {n} devices {devices_warm:.2f}x"
        )
        raw[work] = {
            "settings": best, "default": default, "first_ratio": first, "warm_ratio": warm,
            "devices_warm_ratio": devices_warm, "compile_share": one["compile"] / max(one["first_wall"], 1e-9),
        }  # fmt: skip
    save_json(a.json, {"cores": cores, "devices": n, "rounds": rounds, "reps": reps, "large": a.large, "works": raw})


if __name__ == "__main__":
    main()
