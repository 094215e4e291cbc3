"""Shape buckets (issue 54): a second vector map of another grid size compiles < 10 % of the first's.

Runs, in one fresh process with no persistent compilation cache, a vector map on one grid, a vector map
on a grid of another size in the same shape bucket (`delvjax.core.batching.bucket`), and a success rate at
two trial counts, each call twice: the first call's compile seconds (tracing, lowering and XLA's
compilation: JAX's `/jax/core/compile/*_duration` events; run time left out) and XLA compilations, the
second call's warm seconds, and the second size's compile as a percentage of the first's (target: under
10 %). Compile seconds are wall seconds: on a loaded machine compare the percentage, not the seconds.

    python benchmarks/bench_buckets.py                           # DELV on env1: spacing 25 then 30, 20 then 30 trials
    python benchmarks/bench_buckets.py --method alv --spacings 20 25
    python benchmarks/bench_buckets.py --smoke                   # tiny sizes (the suite's smoke test)
"""

from __future__ import annotations

import argparse
import os
import time

from delvjax import Grid

os.environ["DELVJAX_CACHE_DIR"] = ""  # before delvjax: no persistent cache, every compile is real

import jax

jax.config.update("jax_enable_compilation_cache", False)

from child import save_json  # noqa: E402

import delvjax  # noqa: E402
from delvjax.core import batching, maps  # noqa: E402

EVENTS = (
    "/jax/core/compile/jaxpr_trace_duration",
    "/jax/core/compile/jaxpr_to_mlir_module_duration",
    "/jax/core/compile/backend_compile_duration",
)
TARGET_PCT = 10.0
_log = {"seconds": 0.0, "compiles": 0}


def _listen(event: str, duration: float, **kwargs) -> None:
    if event in EVENTS:
        _log["seconds"] += duration
        _log["compiles"] += event == EVENTS[-1]


def measured(call) -> dict:
    """Compile seconds and XLA compilations of a first call of `call()`, then the wall seconds of a second."""
    before = dict(_log)
    jax.block_until_ready(call())
    compile_s, compiles = _log["seconds"] - before["seconds"], _log["compiles"] - before["compiles"]
    t0 = time.perf_counter()
    jax.block_until_ready(call())
    return {"compile_s": compile_s, "compiles": compiles, "warm_s": time.perf_counter() - t0}


def padded(n: int, cap: int) -> int:
    """The shape a call of n items runs in (`batching.bucket`; a tree without buckets pads to whole groups)."""
    return batching.bucket(n, cap) if hasattr(batching, "bucket") else batching.padded(n)


def row(label: str, size: int, shape: int, m: dict) -> None:
    print(f"{label:24s} {size:7d} {shape:7d} {m['compile_s']:9.2f} {m['compiles']:8d} {1e3 * m['warm_s']:8.1f}")


def ratio(what: str, first: dict, second: dict) -> float:
    pct = 100.0 * second["compile_s"] / max(first["compile_s"], 1e-9)
    verdict = "meets" if pct < TARGET_PCT else "misses"
    print(f"{what}: second compile {pct:.1f} % of the first's ({verdict} the target < {TARGET_PCT:g} %)")
    return pct


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--env", default="env1")
    p.add_argument("--method", default="delv")
    p.add_argument("--spacings", type=float, nargs=2, default=[25.0, 30.0], help="two grids (cm): first, second")
    p.add_argument("--trials", type=int, nargs=2, default=[20, 30], help="trials per distance: first, second")
    p.add_argument("--distances", type=float, nargs="+", default=[100.0, 200.0, 300.0])
    p.add_argument("--smoke", action="store_true", help="tiny sizes, ALV: that the script runs")
    p.add_argument("--json", metavar="PATH", help="also write the ratio(s) and raw numbers here (speed_targets.py)")
    a = p.parse_args()
    if a.smoke:
        a.method, a.spacings, a.trials, a.distances = "alv", [100.0, 110.0], [2, 3], [100.0]
    jax.monitoring.register_event_duration_secs_listener(_listen)
    env = delvjax.load_env(a.env)
    print(f"jax {jax.__version__} on {jax.devices()[0].platform}, {a.method} on {a.env}; persistent cache off")
    print(f"{'call':24s} {'items':>7s} {'padded':>7s} {'compile s':>9s} {'compiles':>8s} {'warm ms':>8s}")
    vm = []
    for spacing in a.spacings:
        n = maps.grid_points(env.arena, spacing).shape[0]
        m = measured(lambda s=spacing: delvjax.vector_map(a.env, method=a.method, grid=Grid(spacing=s)).error_deg)
        row(f"vector_map spacing {spacing:g}", n, padded(n, maps.DEFAULT_BATCH), m)
        vm.append(m)
    sr = []
    for trials in a.trials:
        run = lambda t=trials: delvjax.success_rate(a.env, method=a.method, trials=t, distances=a.distances).outcome  # noqa: E731
        m = measured(run)
        row(f"success_rate {trials} trials", trials, padded(trials, 1 << 14), m)
        sr.append(m)
    pct_vm = ratio("vector map, another grid size", *vm)
    pct_sr = ratio("success rate, another trial count", *sr)
    save_json(a.json, {
        "method": a.method, "env": a.env, "spacings": a.spacings, "trials": a.trials,
        "vector_map": {"first": vm[0], "second": vm[1], "pct": pct_vm},
        "success_rate": {"first": sr[0], "second": sr[1], "pct": pct_sr},
    })  # fmt: skip


if __name__ == "__main__":
    main()
