"""Blob extraction per view: the closed form (core/cylinder_blobs.py) against rendering the ring and
extracting its runs (sensing.blob_runs of ray_hits), and against the NumPy reference (tests/).

Run: python benchmarks/bench_blobs.py [--views N]
Prints compile seconds and warm microseconds per view of each path and the ratios. A benchmark,
not a test (tests/core/test_sensing.py checks that the two JAX paths agree bit for bit).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import jax
import numpy as np

from delvjax.core.batching import fixed_width_map
from delvjax.core.cylinder_blobs import blobs_of_cylinders
from delvjax.core.sensing import blob_runs, ray_hits

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the repository root: tests.twins
from tests.twins import sensing as ref


def timed(fn, *args, repeats: int = 5) -> tuple[float, float]:
    """(compile s, warm s per call) of jit(fn)."""
    t0 = time.perf_counter()
    compiled = jax.jit(fn).lower(*args).compile()
    compile_s = time.perf_counter() - t0
    jax.block_until_ready(compiled(*args))
    t0 = time.perf_counter()
    for _ in range(repeats):
        jax.block_until_ready(compiled(*args))
    return compile_s, (time.perf_counter() - t0) / repeats


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--views", type=int, default=8192)
    a = p.parse_args()
    rng = np.random.default_rng(0)
    n, n_lm, n_pix = a.views, 6, 360
    lms = np.zeros((n_lm, 3), np.float32)
    lms[:, :2] = rng.uniform(-300, 300, (n_lm, 2))
    lms[:, 2] = rng.uniform(5, 40, n_lm)
    origin = rng.uniform(-300, 300, (n, 2)).astype(np.float32)
    heading = rng.uniform(0, 2 * np.pi, n).astype(np.float32)
    visible = np.ones(n_lm, bool)

    def rendered(o, h):
        return fixed_width_map(lambda p, q: blob_runs(ray_hits(lms, visible, p, q, n_pix), n_lm), (o, h))

    def closed_form(o, h):
        return fixed_width_map(lambda p, q: blobs_of_cylinders(lms, visible, p, q, n_pix), (o, h))

    c_old, t_old = timed(rendered, origin, heading)
    c_new, t_new = timed(closed_form, origin, heading)
    m = min(n, 200)
    t0 = time.perf_counter()
    for i in range(m):  # the per-view NumPy reference, as the tests use it
        ref.extract_blobs(ref.render(lms, origin[i], heading[i], [-400, -400, 400, 400], "none", n_pix)[0])
    t_ref = (time.perf_counter() - t0) / m
    us = lambda t: 1e6 * t / n  # noqa: E731
    print(f"{'path':28s} {'compile s':>9s} {'us/view':>9s}")
    print(f"{'NumPy reference':28s} {'-':>9s} {1e6 * t_ref:9.2f}")
    print(f"{'render + blob_runs (JAX)':28s} {c_old:9.2f} {us(t_old):9.3f}")
    print(f"{'closed form (JAX)':28s} {c_new:9.2f} {us(t_new):9.3f}")
    print(f"closed form: {t_old / t_new:.1f}x the rendered path, {1e6 * t_ref / us(t_new):.0f}x the NumPy reference")


if __name__ == "__main__":
    main()
