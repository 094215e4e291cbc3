"""Time the holistic comparators (warping, docs/model.md §4.3; MFDID, §4.5) against their NumPy twins.

For each (method, channel): compile time and warm time of the jitted map program
(`maps.homing_directions`, all cells of the grid: 40 x 40 on env1 at spacing 25), the
per-point time of the plain NumPy twin (tests/twins/holistic.py) on a few of the
same points, the ratio, and for warping the operation/byte count and the floor it
implies on this CPU (see `floor`).
Run: python benchmarks/bench_warping.py [--env env1] [--spacing 25] [--ref-points 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
from pathlib import Path

import jax

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the repository root: tests.twins
sys.path.insert(0, str(Path(__file__).resolve().parent))
from timing import reference_seconds_per_point, time_map_program

from delvjax.core.sensor import BACKGROUNDS, Sensor
from delvjax.options._registry import METHODS
from tests.twins import holistic as ref

LANES = 8  # 32-bit lanes per vector instruction in the code XLA emits here (256-bit AVX2/AVX-512VL)


def cpu_ghz() -> float:
    """Nominal clock from /proc/cpuinfo (GHz), 2.6 if unknown."""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("cpu MHz"):
                return float(line.split(":")[1]) / 1e3
    except OSError:
        pass
    return 2.6


def floor(n_points: int, sensor: Sensor, channel: str) -> dict:
    """Operation and byte counts of the exhaustive warping search and the time they bound.

    mask: per hypothesis ceil(n_pix/32) words of xor + population count + add (+ key, min).
    Population count issues one vector instruction per cycle per core, so the floor is
    hypotheses * words / LANES cycles over all cores. gray: per hypothesis n_pix
    subtract + abs + add; at three vector instructions per cycle, hypotheses * n_pix / LANES
    cycles. Bytes: the predicted-image table is read once per hypothesis row but stays in
    cache (its size is printed); per point only the image and its rotations are new.
    """
    w = METHODS["warping"]
    hyps = n_points * w.n_alpha * w.n_rho * w.n_psi
    n_ar = w.n_alpha * w.n_rho
    cores = os.cpu_count() or 1
    hz = cpu_ghz() * 1e9
    if channel == "mask":
        words = -(-sensor.n_pix // 32)
        ops = hyps * (3 * words + 2)
        cycles = hyps * words / LANES
        table = n_ar * words * 4
    else:
        ops = hyps * (3 * sensor.n_pix + 2)
        cycles = hyps * sensor.n_pix / LANES
        table = n_ar * sensor.n_pix * 4
    return {"hypotheses": hyps, "gops": ops / 1e9, "table_kb": table / 1e3, "floor_ms": 1e3 * cycles / (cores * hz)}


def bench(env_name: str, method: str, channel: str, spacing: float, repeats: int, ref_points: int) -> dict:
    cfg = Sensor(channel=channel)
    run = time_map_program(env_name, method, cfg, spacing, repeats)
    compile_s, warm, cpu, points = run["compile_s"], run["warm"], run["cpu"], run["points"]
    ref_per_point = reference_seconds_per_point(
        ref.reference_direction, run, method, ref_points, channel=channel, background=BACKGROUNDS[int(cfg.background)]
    )
    warm_s = min(warm)
    n = points.shape[0]
    out = {
        "method": method,
        "channel": channel,
        "points": n,
        "compile_s": compile_s,
        "warm_ms": 1e3 * warm_s,
        "median_ms": 1e3 * statistics.median(warm),
        "cpu_ms": 1e3 * min(cpu),
        "ref_s_per_point": ref_per_point,
        "ratio": ref_per_point / (warm_s / n),
    }
    if method == "warping":
        out.update(floor(n, cfg, channel))
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--env", default="env1")
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--repeats", type=int, default=10)
    p.add_argument("--ref-points", type=int, default=3)
    p.add_argument(
        "--cases",
        nargs="+",
        default=["warping:mask", "warping:gray", "mfdid:mask", "mfdid:gray"],
        help="method:channel pairs",
    )
    a = p.parse_args()
    print(
        f"jax {jax.__version__} on {jax.devices()[0].platform}, {os.cpu_count()} cores at ~{cpu_ghz():.2f} GHz, "
        f"env {a.env}, spacing {a.spacing:g}; warm = best of {a.repeats}, load average {os.getloadavg()[0]:.2f}"
    )
    print(
        f"{'method':8s} {'chan':4s} {'points':>6s} {'compile s':>9s} {'warm ms':>8s} {'median':>7s} {'cpu ms':>7s} "
        f"{'ref s/pt':>8s} {'ratio':>8s} | {'hyps':>9s} {'Gops':>6s} {'table KB':>8s} {'floor ms':>8s}"
    )
    for case in a.cases:
        method, channel = case.split(":")
        r = bench(a.env, method, channel, a.spacing, a.repeats, a.ref_points)
        tail = (
            f" | {r['hypotheses']:9.3g} {r['gops']:6.1f} {r['table_kb']:8.0f} {r['floor_ms']:8.1f}"
            if "floor_ms" in r
            else ""
        )
        print(
            f"{method:8s} {channel:4s} {r['points']:6d} {r['compile_s']:9.2f} {r['warm_ms']:8.1f} {r['median_ms']:7.1f} "
            f"{r['cpu_ms']:7.1f} {r['ref_s_per_point']:8.3f} {r['ratio']:7.0f}x" + tail,
            flush=True,
        )


if __name__ == "__main__":
    main()
