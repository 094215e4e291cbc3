"""Benchmark: world ensembles (docs/reproduce.md "Ensembles") as one catchment sweep, on whatever device JAX finds.

    python benchmarks/bench_ensembles.py [--members 44] [--spacing 100] [--families env1 env2 env3]

The ensembles study's first sweep at a chosen size: `--members` worlds of each family (docs/model.md §6.1)
with DELV (compass), ACV and ALV, k = 0, 1, 2 hidden landmarks (every choice), the default rules. Printed:
the first run (compilation included), a second run on other members (warm: the same program), cells and
rollouts per second warm, and the members' drawing alone. The issue's GPU target: --members 256 --spacing 25
(the thesis's grid). A smoke size (--members 2 --spacing 200) checks the script runs.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from delvjax.envs import ensemble_envs
from delvjax.sweeps import run_sweep
from delvjax.sweeps._spec import parse_sweep

METHODS = ("delv-compass", "acv", "alv")


def sweep_text(families, members: int, seed: int, spacing: float) -> str:
    envs = ", ".join(f'{{ensemble = "{f}", members = {members}, seed = {seed}}}' for f in families)
    methods = ", ".join(f'"{m}"' for m in METHODS)
    return (
        '[sweep]\nkind = "catchment"\nmetrics = ["catchment_pct", "gt45_pct", "points"]\n'
        f"[axes]\nenv = [{envs}]\nmethod = [{methods}]\nocclude = [0, 1, 2]\nspacing = [{spacing}]\n"
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--members", type=int, default=44)
    ap.add_argument("--spacing", type=float, default=100.0)
    ap.add_argument("--families", nargs="+", default=["env1", "env2", "env3"])
    args = ap.parse_args()
    t0 = time.perf_counter()
    for f in args.families:
        ensemble_envs(f, args.members, seed=0)
    print(f"drawing {args.members} members of {len(args.families)} families: {time.perf_counter() - t0:.2f} s")
    times, ds = [], None
    for seed in (0, 1):  # the second run draws other members: the same program, warm
        spec = parse_sweep(sweep_text(args.families, args.members, seed, args.spacing), "bench")
        t0 = time.perf_counter()
        ds = run_sweep(spec)
        times.append(time.perf_counter() - t0)
    cells = spec.n_cells
    masks = 1 + 4 + 6  # k = 0, 1, 2 of four landmarks
    rollouts = int(np.sum(ds.points.sel({"occlude": 0}).values)) * masks
    print(f"{cells} cells, {rollouts} rollouts, spacing {args.spacing:g} cm, {args.members} members per family")
    print(f"cold (compilation included): {times[0]:.1f} s; warm: {times[1]:.1f} s")
    print(f"warm: {cells / times[1]:.1f} cells/s, {rollouts / times[1]:.0f} rollouts/s")
    print(
        f"median DELV (compass) catchment at k = 1: {float(np.median(ds.catchment_pct.sel({'homing_method': 'delv-compass', 'occlude': 1}).values)):.1f} %"
    )


if __name__ == "__main__":
    main()
