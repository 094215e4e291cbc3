"""MinWarping and 2D-Warping vector maps (issue 26; docs/model.md §4.7): time per image pair, compile
time separate, and the ratio to the plain NumPy twin (tests/twins/minwarping.py) in the same run.

The headline: env1 rendered at spacing 25 cm (a 40 x 40 grid, 1559 views against home), 288 x 48 gray
panoramas, the authors' defaults (96 x 96 hypotheses, 9 scale planes 0.5-2, threshold 2.5, NSAD on
vertical edges, double and fine search, byte stack). Target: the whole map under 15 s on 2 CPU cores
warm, under 10 ms a pair. On a CPU-only machine the map is split over one JAX device per core
(`--xla_force_host_platform_device_count`, set here before JAX loads unless XLA_FLAGS is given); on a
GPU it runs unchanged on the GPU.

The twin is plain loops, hours for a full-size pair: its time per pair is measured on a small
configuration (96 x 12 panoramas, 32 x 32 hypotheses) beside JAX on the same configuration, and
extrapolated to the full size from its stack (timed whole) and one psi row of its search (x 96).

    python benchmarks/bench_minwarping.py              # headline map + twin ratios
    python benchmarks/bench_minwarping.py --big        # also a 100 x 100 grid: time and peak memory
    python benchmarks/bench_minwarping.py --errors     # the error table of issue 26 (env1 at 100 cm)
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

if "XLA_FLAGS" not in os.environ:
    os.environ["XLA_FLAGS"] = f"--xla_force_host_platform_device_count={os.cpu_count() or 1}"
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the twin lives in tests/

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import numpy as np  # noqa: E402

from delvjax.core.images import Camera  # noqa: E402
from delvjax.core.methods import minwarping as mw  # noqa: E402
from delvjax.images import render_in_memory  # noqa: E402
from delvjax.images._evaluate import database_vector_map  # noqa: E402
from delvjax.images._render import ImageSettings  # noqa: E402
from tests.twins import minwarping as tw  # noqa: E402

CAMERA = Camera(rows=48, cols=288)
# the authors' configuration: 96 x 96 hypotheses on 288 columns (the defaults are 72 x 72: mw.AUTHORS_GRID)
GRID = {
    "minwarping": dict(mw.AUTHORS_GRID),
    "hybrid": dict(mw.AUTHORS_GRID),
    "warping2d": dict(mw.AUTHORS_GRID),
}


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def time_map(method: str, spacing: float) -> dict:
    t0 = time.perf_counter()
    db = render_in_memory("env1", spacing=spacing, settings=ImageSettings(camera=CAMERA), panoramas=True)
    render = time.perf_counter() - t0
    t0 = time.perf_counter()
    vm = database_vector_map(db, method, **GRID[method])
    jax.block_until_ready(vm.direction)
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    vm = database_vector_map(db, method, **GRID[method])
    jax.block_until_ready(vm.direction)
    warm = time.perf_counter() - t0
    e = np.asarray(vm.error_deg)[np.asarray(vm.included)]
    return {
        "points": len(e),
        "render_s": render,
        "compile_s": first - warm,
        "warm_s": warm,
        "ms_per_pair": 1e3 * warm / len(e),
        "mean_err": e.mean(),
        "median_err": np.median(e),
    }


def small_ratio(seed: int = 0) -> tuple[float, float]:
    """(JAX ms, twin ms) per pair on 96 x 12 panoramas, 32 x 32 hypotheses, defaults otherwise."""
    w, h, n = 96, 12, 32
    rng = np.random.default_rng(seed)
    ss, cv = (rng.random((h, w)).astype(np.float32) for _ in range(2))
    elev = np.radians(30 - 60 / h * (np.arange(h) + 0.5))
    cfg = mw.MinWarping(n_alpha=n, n_psi=n)
    f = jax.jit(lambda s, c: mw.search(s, c, jnp.asarray(elev, jnp.float32), cfg))
    jax.block_until_ready(f(ss, cv))
    t0 = time.perf_counter()
    for _ in range(20):
        jax.block_until_ready(f(ss, cv))
    jax_ms = (time.perf_counter() - t0) / 20 * 1e3
    t0 = time.perf_counter()
    tw.search(ss, cv, elev, n, n)
    return jax_ms, (time.perf_counter() - t0) * 1e3


def full_twin_estimate_s() -> float:
    """Seconds per full-size pair of the twin: its stack (x2, both directions) timed whole, one psi row of
    its search x 96 x 2 (double search; the fine search's 25 hypotheses left out)."""
    rng = np.random.default_rng(1)
    ss, cv = (rng.random((48, 288)) for _ in range(2))
    elev = np.radians(30 - 60 / 48 * (np.arange(48) + 0.5))
    scales = tw.scale_factors(9, 2.0)
    t0 = time.perf_counter()
    stk = tw.quantise(tw.stack(ss, cv, elev, scales), "nsad")
    stack_s = time.perf_counter() - t0
    template = tw.min_template(288, scales, 2.5)
    t0 = time.perf_counter()
    for a in range(96):
        tw.match_at(stk, template, 3 * a, 0)
    row_s = time.perf_counter() - t0
    return 2 * stack_s + 2 * 96 * row_s


def error_table() -> None:
    """Mean and median error, error classes and catchment of the panorama, landmark and 1-D image methods
    on env1 rendered at 100 cm (98 views against home, 288 x 48, no camera noise)."""
    from delvjax.images._evaluate import catchment_numbers, database_catchment

    db = render_in_memory("env1", spacing=100.0, settings=ImageSettings(camera=CAMERA), panoramas=True)
    print("| method | mean err deg | median | e>45 (of 98) | e>90 | catchment % |")
    print("|---|---|---|---|---|---|")
    runs = [("minwarping", {}), ("warping2d", {}), ("hybrid", {}), ("delv", {})]
    runs += [("warping", {"channel": c, "n_psi": 72}) for c in ("gray", "mask")]
    for method, opts in runs:
        vm = database_vector_map(db, method, **{**GRID.get(method, {}), **opts})
        e = np.asarray(vm.error_deg)[np.asarray(vm.included)]
        c = catchment_numbers(database_catchment(db, vm)[1])
        name = f"{method} {opts.get('channel', '')}".strip()
        print(
            f"| {name} | {e.mean():.1f} | {np.median(e):.1f} | {(e > 45).sum()} | {(e > 90).sum()} | {c['catchment_pct']:.1f} |"
        )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--big", action="store_true", help="also a 100 x 100 grid (spacing 10 cm): time and peak memory")
    p.add_argument("--no-twin", action="store_true", help="skip the twin (minutes)")
    p.add_argument("--errors", action="store_true", help="only the error table at 100 cm")
    args = p.parse_args()
    if args.errors:
        error_table()
        return
    print(f"jax {jax.__version__} on {jax.devices()[0].platform}, {jax.device_count()} device(s)")
    print("| method | grid | views | compile s | warm s | ms / pair | mean err deg | median | render s | peak RSS MB |")
    print("|---|---|---|---|---|---|---|---|---|---|", flush=True)
    rows = [("minwarping", "40 x 40", 25.0), ("warping2d", "40 x 40", 25.0)]
    rows += [("minwarping", "100 x 100", 10.0)] if args.big else []
    head = None
    for method, grid, spacing in rows:  # each row as soon as it is measured (a time limit keeps the rest)
        r = time_map(method, spacing)
        head = head or r["ms_per_pair"]
        print(
            f"| {method} | {grid} | {r['points']} | {r['compile_s']:.1f} | {r['warm_s']:.2f} | {r['ms_per_pair']:.2f} | "
            f"{r['mean_err']:.1f} | {r['median_err']:.1f} | {r['render_s']:.1f} | {peak_rss_mb():.0f} |",
            flush=True,
        )
    if not args.no_twin:
        jax_ms, twin_ms = small_ratio()
        print(
            f"small pair (96 x 12, 32 x 32): JAX {jax_ms:.2f} ms, twin {twin_ms:.0f} ms: ratio {twin_ms / jax_ms:.0f}x"
        )
        est = full_twin_estimate_s()
        print(
            f"full pair (288 x 48, 96 x 96, double): twin ~{est:.0f} s (extrapolated), JAX {head:.2f} ms: "
            f"ratio ~{est * 1e3 / head:.0f}x"
        )


if __name__ == "__main__":
    main()
