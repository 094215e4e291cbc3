"""Benchmark: the gradient of the soft vector-map loss against the forward evaluation.

    python benchmarks/bench_grad.py [--methods delv alv acv] [--env env1] [--spacing 25] [--repeats 10]

For each method on a 40 x 40 grid (spacing 25): compile time and warm time (median) of the soft
loss (forward), of the loss and its gradient with respect to every parameter (reverse
mode, one program: landmarks, home, d, scale, noise sigmas), their ratio (target < 5), the
cost of the same gradient by central finite differences with the forward program (2 forward
runs per parameter), and the ordinary (pixel, hard) vector map of the same grid for scale.
Then the sensitivity at a stated scale (`homing_loss_grad`'s default: smoothing 5 cm / 1 deg,
8 draws; docs/differentiable.md "Sensitivity at a stated scale") against that hard map: the
column "smoothed / hard" is issue 56's budget (target <= 10 on 2 CPU cores).
"""

from __future__ import annotations

import argparse
import statistics
import time

import jax

from delvjax.core import maps
from delvjax.gradients._loss import loss_problem, problem_loss, problem_value_and_grad
from delvjax.gradients._smoothing import Smoothing, smoothed_value_and_grad

forward = jax.jit(problem_loss)


def timed(fn, repeats: int) -> tuple[float, float]:
    """(compile + first run s, median warm s) of fn()."""
    t = time.perf_counter()
    jax.block_until_ready(fn())
    first = time.perf_counter() - t
    runs = []
    for _ in range(repeats):
        t = time.perf_counter()
        jax.block_until_ready(fn())
        runs.append(time.perf_counter() - t)
    return first, statistics.median(runs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--methods", nargs="+", default=["delv", "alv", "acv"])
    ap.add_argument("--env", default="env1")
    ap.add_argument("--spacing", type=float, default=25.0)
    ap.add_argument("--repeats", type=int, default=10)
    a = ap.parse_args()
    print(f"jax {jax.__version__} on {jax.devices()[0].platform}, env {a.env}, spacing {a.spacing:g}")
    print(
        f"{'method':7s} {'points':>6s} {'params':>6s} {'fwd ms':>7s} {'grad ms':>8s} {'ratio':>6s} {'FD ms':>8s} "
        f"{'hard map ms':>11s} {'compile fwd/grad s':>18s} {'smoothed ms':>11s} {'smoothed / hard':>15s}"
    )
    for m in a.methods:
        p = loss_problem(a.env, m, spacing=a.spacing)
        n_params = sum(x.size for x in jax.tree.leaves(p.params))
        c_f, fwd = timed(lambda: forward(p.params, p), a.repeats)
        c_g, grad = timed(lambda: problem_value_and_grad(p), a.repeats)
        env, pts, heads = p.env, jax.numpy.asarray(p.points), jax.numpy.asarray(p.headings)
        _, hard = timed(lambda: maps.homing_directions(env, pts, heads, p.key, p.sensor, p.method), a.repeats)
        _, smooth = timed(lambda: smoothed_value_and_grad(p, Smoothing()), a.repeats)
        print(
            f"{m:7s} {int(p.included.sum()):6d} {n_params:6d} {1e3 * fwd:7.1f} {1e3 * grad:8.1f} {grad / fwd:6.2f} "
            f"{2e3 * n_params * fwd:8.0f} {1e3 * hard:11.1f} {c_f:8.1f} / {c_g:.1f} {1e3 * smooth:11.1f} "
            f"{smooth / hard:15.1f}",
            flush=True,
        )


if __name__ == "__main__":
    main()
