"""Measure what sub-degree refinement (`delv-refined`, least squares after the heading search)
changes in the angular error of whole vector maps (docs/differentiable.md "Sub-degree refinement").

    python benchmarks/bench_refine.py [--spacing 25]

Rows: env1 with the default 1 degree search, with 3 degree bearing noise, and a layout with every
landmark in one corner (far from home, where the heading matters most) with 10 and 1 degree searches;
mean and median error of plain and refined DELV, and the time of each map (warm).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import delvjax
from delvjax import Grid

CORNER = [[800, 800, 30], [880, 690, 25], [690, 880, 20], [900, 900, 15]]


def errors(env, method: str, spacing: float, **kw) -> tuple[np.ndarray, float]:
    delvjax.vector_map(env, method, grid=Grid(spacing=spacing), **kw)  # compile
    t = time.perf_counter()
    vm = delvjax.vector_map(env, method, grid=Grid(spacing=spacing), **kw)
    return np.asarray(vm.error_deg)[np.asarray(vm.included)], time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--spacing", type=float, default=25.0)
    a = ap.parse_args()
    corner = delvjax.make_env(CORNER, name="corner")
    cases = [
        ("env1", "env1", {}),
        ("env1, 3 deg bearing noise", "env1", {"bearing_noise_deg": 3.0}),
        ("corner, 10 deg search", corner, {"n_heading": 36}),
        ("corner, 1 deg search", corner, {}),
    ]
    print(f"{'case':28s} {'plain mean/median':>18s} {'refined mean/median':>20s} {'plain ms':>8s} {'refined ms':>10s}")
    for label, env, kw in cases:
        (p, tp), (r, tr) = errors(env, "delv", a.spacing, **kw), errors(env, "delv-refined", a.spacing, **kw)
        print(
            f"{label:28s} {p.mean():8.3f} / {np.median(p):7.3f} {r.mean():9.3f} / {np.median(r):8.3f} "
            f"{1e3 * tp:8.1f} {1e3 * tr:10.1f}",
            flush=True,
        )


if __name__ == "__main__":
    main()
