"""Before/after timing of the vector-map program at two revisions, in one session, side by side.

    python benchmarks/ab_vector_map.py --base 3b49f83 [--methods delv alv ...] [--rounds 2] [--repeats 100]

Checks out `--base` into a temporary git worktree and times `maps.homing_directions` (env1,
40 x 40 cells, compile excluded) there and in this working tree, alternating `--rounds`
times, each a fresh process; prints the best and median milliseconds of both and the ratio
of the bests. Works with the API before methods became modules (`delvjax.config.Config`,
method names under jit) and after (`delvjax.core`, method modules).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import json, sys, time
import jax, jax.numpy as jnp, numpy as np
import delvjax
method, repeats = sys.argv[1], int(sys.argv[2])
try:  # methods as modules
    from delvjax.core import maps
    from delvjax.core.sensor import Sensor
    try:  # the edge as packages
        from delvjax.options._registry import METHODS
    except ImportError:  # flat edge modules
        from delvjax.registry import METHODS
    args = (Sensor(), METHODS[method])
except ImportError:  # before: one Config, the method name static under jit
    from delvjax import maps
    from delvjax.config import Config
    args = (Config(), method)
env = delvjax.load_env("env1").arrays()
key = jax.random.PRNGKey(0)
pts = jnp.asarray(maps.grid_points(env.arena, 25.0))
heads = maps.random_headings(key, pts.shape[0])
compiled = maps.homing_directions.lower(env, pts, heads, key, *args).compile()
traced = args[:1] if isinstance(args[1], str) else args  # a static method name is no argument
call = lambda: compiled(env, pts, heads, key, *traced)
jax.block_until_ready(call())
times = []
for _ in range(repeats):
    t = time.perf_counter()
    jax.block_until_ready(call())
    times.append(time.perf_counter() - t)
print(json.dumps({"best_ms": 1e3 * min(times), "median_ms": 1e3 * float(np.median(times))}))
"""


def measure(tree: Path, method: str, repeats: int) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree), "DELVJAX_CACHE_DIR": ""}
    out = subprocess.run(
        [sys.executable, "-c", CHILD, method, str(repeats)],
        cwd=tree,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--base", required=True, help="git revision to compare against")
    p.add_argument(
        "--methods", nargs="+", default=["delv", "delv-compass", "delv-visual", "alv", "acv", "warping", "mfdid"]
    )
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--repeats", type=int, default=100)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp) / "base"
        subprocess.run(
            ["git", "worktree", "add", "--detach", str(base), a.base], cwd=ROOT, check=True, capture_output=True
        )
        try:
            print(
                f"{'method':13s} {'base best':>9s} {'base med':>8s} {'this best':>9s} {'this med':>8s} {'this/base':>9s}"
            )
            for m in a.methods:
                runs = {"base": [], "this": []}
                for _ in range(a.rounds):  # alternate, so drift of the machine hits both alike
                    runs["base"].append(measure(base, m, a.repeats))
                    runs["this"].append(measure(ROOT, m, a.repeats))
                b = {k: (min(r["best_ms"] for r in v), min(r["median_ms"] for r in v)) for k, v in runs.items()}
                print(
                    f"{m:13s} {b['base'][0]:9.2f} {b['base'][1]:8.2f} {b['this'][0]:9.2f} {b['this'][1]:8.2f} "
                    f"{b['this'][0] / b['base'][0]:9.3f}",
                    flush=True,
                )
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(base)], cwd=ROOT, capture_output=True)


if __name__ == "__main__":
    main()
