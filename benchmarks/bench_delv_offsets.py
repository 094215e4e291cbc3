"""Benchmark: the home-frame list offsets of DELV without a compass (docs/model.md §3.3), 360 heading
hypotheses x 6 blobs per view, in a 128-wide vmap as in a rollout step.

    python benchmarks/bench_delv_offsets.py [--items 128] [--reps 20]

Times, warm (compile printed apart), per view:
  * remainder: the first formula, an (A, B) table with one float remainder per entry, reduced over B;
  * now: `delv.list_offsets` ((B, A) table, two exact subtractions, reduced over the blobs);
  * the whole no-compass match (`match_arrangement` with those offsets);
  * a per-view NumPy reference (np.mod, np.argmin), and the ratio reference / now.
The two JAX versions are checked equal before timing.
"""

from __future__ import annotations

import argparse
import time

import jax
import jax.numpy as jnp
import numpy as np

from delvjax.core.estimation import TIE_RAD
from delvjax.core.geometry import TWO_PI
from delvjax.core.methods import delv
from delvjax.core.search import first_argmin


def remainder_offsets(bearing, valid, alphas):
    home_frame = jnp.mod(bearing[None, :] + alphas[:, None] + TIE_RAD, TWO_PI)
    return first_argmin(jnp.where(valid[None, :], home_frame, jnp.inf), axis=-1)


def numpy_offsets(bearing, valid, alphas):
    home_frame = np.mod(bearing[None, :] + alphas[:, None] + np.float32(TIE_RAD), np.float32(TWO_PI))
    return np.argmin(np.where(valid[None, :], home_frame, np.inf), axis=-1)


def best_time(fn, args, reps):
    jax.block_until_ready(fn(*args))
    best = float("inf")
    for _ in range(5):
        t = time.perf_counter()
        for _ in range(reps):
            jax.block_until_ready(fn(*args))
        best = min(best, (time.perf_counter() - t) / reps)
    return best


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--items", type=int, default=128)
    p.add_argument("--reps", type=int, default=20)
    a = p.parse_args()
    n, blobs = a.items, 6
    alphas = TWO_PI * jnp.arange(360, dtype=jnp.float32) / 360
    rng = np.random.default_rng(0)
    bearing = jnp.asarray(np.sort(rng.uniform(0, TWO_PI, (n, blobs)), axis=1), jnp.float32)
    valid = jnp.asarray(rng.random((n, blobs)) < 0.85)
    vectors = jnp.asarray(rng.normal(size=(2, n, blobs, 2)) * 300, jnp.float32)
    progs = {
        "remainder": jax.jit(jax.vmap(lambda b, v: remainder_offsets(b, v, alphas))),
        "now": jax.jit(jax.vmap(lambda b, v: delv.list_offsets(b, v, alphas))),
    }
    match = jax.jit(
        jax.vmap(lambda r, c, b, v: delv.match_arrangement(r, v, c, v, alphas, delv.list_offsets(b, v, alphas)))
    )
    for name, f in progs.items():
        t = time.perf_counter()
        jax.block_until_ready(f(bearing, valid))
        print(f"compile {name:10s} {time.perf_counter() - t:6.2f} s")
    assert np.array_equal(np.asarray(progs["remainder"](bearing, valid)), np.asarray(progs["now"](bearing, valid)))
    times = {name: best_time(f, (bearing, valid), a.reps) / n * 1e6 for name, f in progs.items()}
    times["match (now)"] = best_time(match, (vectors[0], vectors[1], bearing, valid), a.reps) / n * 1e6
    b_np, v_np, a_np = np.asarray(bearing), np.asarray(valid), np.asarray(alphas)
    t = time.perf_counter()
    for i in range(n):  # the per-view reference: a plain loop over views, for timing
        numpy_offsets(b_np[i], v_np[i], a_np)
    times["numpy reference"] = (time.perf_counter() - t) / n * 1e6
    print(f"{'offsets per view':24s} {'us':>8s}")
    for name, us in times.items():
        print(f"{name:24s} {us:8.2f}")
    print(
        f"remainder / now: {times['remainder'] / times['now']:.1f}x; "
        f"numpy reference / now: {times['numpy reference'] / times['now']:.1f}x"
    )


if __name__ == "__main__":
    main()
