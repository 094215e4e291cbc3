"""Benchmark: catchment rollouts (docs/model.md §5) — compile and warm times, the NumPy reference, the ratio.

    python benchmarks/bench_rollouts.py [--env env1] [--spacing 25] [--ref-points 12] [--strategies]

Times (2-core CPU target: DELV catchment on env1 at spacing 25 < 2 s warm):
  * compile: first call minus a warm call; warm: best of --reps calls with new seeds;
  * the rollouts alone (`run_trials`, 40 x 40 starts, up to 50 moves) and the whole
    `catchment` (rollouts + the vector map drawn under the squares);
  * warping's catchment if the "warping" method is registered;
  * the per-point NumPy reference rollout (tests/twins/rollouts.py) on --ref-points
    grid points, extrapolated to the grid, and the ratio reference / JAX warm;
  * with --strategies: lanes refilled from a queue (the library) vs chunks that each run
    until their slowest trial ends (no refill).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from delvjax import Grid, Rules

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the repository root: tests.twins
from delvjax.core import rollouts
from delvjax.core.maps import grid_included, grid_points, random_headings
from delvjax.core.sensor import Sensor
from delvjax.envs._presets import load_env
from delvjax.options._registry import METHODS
from tests.twins.rollouts import HomeRecord, reference_rollout


def timed(fn, *args, **kw):
    t = time.perf_counter()
    out = fn(*args, **kw)
    jax.block_until_ready(out)
    return out, time.perf_counter() - t


def grid_trials(env, spacing, seed):
    key = jax.random.PRNGKey(seed)
    pts = jnp.asarray(grid_points(env.arena, spacing))
    heads = random_headings(key, pts.shape[0])
    cells = np.flatnonzero(np.asarray(grid_included(env, pts, 10.0)))
    return pts[cells], heads[cells], jnp.asarray(cells, jnp.int32), key


def bench_method(env, method, spacing, reps, lanes):
    config, module = Sensor(), METHODS[method]

    def rollouts_only(seed):
        pts, heads, cells, key = grid_trials(env, spacing, seed)
        n = pts.shape[0]
        return rollouts.run_trials(
            env,
            pts,
            heads,
            cells,
            jnp.zeros(n, jnp.int32),
            env.valid[None],
            key,
            config,
            module,
            rules=Rules(lanes=lanes),
        )

    res, first = timed(rollouts_only, 0)
    warm = min(timed(rollouts_only, s)[1] for s in range(1, reps + 1))

    def full_catchment(seed):
        grid, rules = Grid(spacing=spacing), Rules(lanes=lanes)
        return timed(rollouts.catchment_area, env, module, config, grid, rules, key=jax.random.PRNGKey(seed))

    _, first_full = full_catchment(0)
    full = min(full_catchment(s)[1] for s in range(1, reps + 1))
    steps = np.asarray(res.steps)
    print(
        f"{method:13s} rollouts: {steps.size} starts, {int(steps.sum())} moves (mean {steps.mean():.1f}, "
        f"max {steps.max()}), catchment {100 * float(np.mean(np.asarray(res.success))):.2f} %"
    )
    print(
        f"{'':13s} rollouts only: compile {first - warm:6.2f} s  warm {warm:6.3f} s "
        f"({1e6 * warm / max(int(steps.sum()), 1):.1f} us per move)"
    )
    print(f"{'':13s} catchment (rollouts + vector map): compile {first_full - full:6.2f} s  warm {full:6.3f} s")
    return warm, full, res


def bench_reference(env, method, spacing, n_points):
    pts, heads, _, _ = grid_trials(env, spacing, 1)
    lms = np.asarray(env.landmarks)[np.asarray(env.valid)].astype(float)
    arena, home = np.asarray(env.arena, float), np.asarray(env.home, float)
    record = HomeRecord(lms, arena, home)
    pick = np.linspace(0, pts.shape[0] - 1, n_points).astype(int)
    t = time.perf_counter()
    moves = 0
    for i in pick:  # the reference is a per-point loop by design
        _, steps, _ = reference_rollout(
            lms, arena, home, np.asarray(pts[i], float), float(heads[i]), method, record=record
        )
        moves += steps
    per_point = (time.perf_counter() - t) / n_points
    return per_point, moves / n_points, pts.shape[0]


def bench_strategies(env, method, spacing):
    """Queue with refill (lanes) vs chunks without refill (each chunk waits for its slowest trial)."""
    config, module = Sensor(), METHODS[method]
    pts, heads, cells, key = grid_trials(env, spacing, 1)
    n = pts.shape[0]
    masks = env.valid[None]
    print(f"strategies ({method}, {n} starts):")
    for lanes in (64, 128, 256, 512, n):

        def run(lanes=lanes):
            return rollouts.run_trials(
                env, pts, heads, cells, jnp.zeros(n, jnp.int32), masks, key, config, module, rules=Rules(lanes=lanes)
            )

        timed(run)
        print(f"  queue, {lanes:4d} lanes: warm {min(timed(run)[1] for _ in range(2)):.3f} s")
    for chunk in (128, 256):
        pad = (-n) % chunk
        p = jnp.concatenate([pts, jnp.repeat(pts[:1], pad, 0)])
        h = jnp.concatenate([heads, jnp.repeat(heads[:1], pad)])
        c = jnp.concatenate([cells, jnp.repeat(cells[:1], pad)])

        def chunked():
            return [
                rollouts.run_trials(
                    env,
                    p[i : i + chunk],
                    h[i : i + chunk],
                    c[i : i + chunk],
                    jnp.zeros(chunk, jnp.int32),
                    masks,
                    key,
                    config,
                    module,
                    rules=Rules(lanes=chunk),
                )
                for i in range(0, n + pad, chunk)
            ]

        timed(chunked)
        print(f"  chunks of {chunk} without refill: warm {min(timed(chunked)[1] for _ in range(2)):.3f} s")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--env", default="env1")
    ap.add_argument("--spacing", type=float, default=25.0)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--lanes", type=int, default=rollouts.DEFAULT_LANES)
    ap.add_argument("--ref-points", type=int, default=12, help="grid points the NumPy reference rolls out")
    ap.add_argument("--strategies", action="store_true", help="also compare batching strategies")
    args = ap.parse_args()
    env = load_env(args.env)
    print(
        f"jax {jax.__version__} on {jax.devices()[0].platform}; {args.env}, spacing {args.spacing:g}, "
        f"lanes {args.lanes}"
    )
    warm, _, _ = bench_method(env, "delv", args.spacing, args.reps, args.lanes)
    if "warping" in METHODS:
        bench_method(env, "warping", args.spacing, args.reps, args.lanes)
    else:
        print("warping       not registered (skipped)")
    per_point, mean_moves, n = bench_reference(env, "delv", args.spacing, args.ref_points)
    print(
        f"NumPy reference (delv): {per_point:.3f} s per start ({mean_moves:.1f} moves) on {args.ref_points} "
        f"starts -> {per_point * n:.1f} s for {n} starts"
    )
    print(f"ratio reference / JAX warm rollouts: {per_point * n / warm:.0f}x")
    if args.strategies:
        bench_strategies(env, "delv", args.spacing)


if __name__ == "__main__":
    main()
