"""Agreement of every method with the per-point NumPy twin on the 20 random test environments.

Prints, per method, the share of sampled grid points whose world direction is within
2 degrees of the twin's (both invalid counts as agreement). All 20 environments run as
one batched program. Run: python benchmarks/agreement.py [--points 30] [--seed 1]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the repository root: tests.twins
import delvjax
from delvjax.core.maps import grid_included, grid_points, homing_directions, random_headings
from delvjax.core.scene import stack_envs
from delvjax.core.sensor import Sensor
from delvjax.options._registry import METHODS
from tests.conftest import random_landmarks
from tests.twins import methods as ref

ARENA, HOME = [0, 0, 1000, 1000], [500, 500]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--points", type=int, default=30, help="points per environment and method")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--methods", nargs="+", default=["delv", "delv-compass", "alv", "acv", "delv-visual"])
    a = p.parse_args()
    layouts = [random_landmarks(s) for s in range(20)]
    envs = stack_envs([delvjax.make_env(lm, name="random", pad_to=6) for lm in layouts])
    points = jnp.asarray(grid_points(ARENA, 100.0))
    key = jax.random.PRNGKey(7)
    headings = random_headings(key, points.shape[0])
    included = np.asarray(jax.vmap(lambda e: grid_included(e, points, 10.0))(envs))
    batched = jax.vmap(homing_directions, in_axes=(0, None, None, None, None, None))
    for method in a.methods:
        direction, valid = (np.asarray(v) for v in batched(envs, points, headings, key, Sensor(), METHODS[method]))
        rng = np.random.default_rng(a.seed)
        agree = total = 0
        for e, lms in enumerate(layouts):  # the twin is per point by design
            for i in rng.choice(np.nonzero(included[e])[0], a.points, replace=False):
                x = ref.reference_direction(lms, ARENA, HOME, np.asarray(points[i], float), float(headings[i]), method)
                total += 1
                if np.isnan(x) or not valid[e, i]:
                    agree += int(np.isnan(x) and not valid[e, i])
                else:
                    agree += int(abs(ref.wrap(x - direction[e, i])) <= np.radians(2.0))
        print(f"{method:13s} {agree}/{total} = {100 * agree / total:.1f} % within 2 deg of the twin", flush=True)


if __name__ == "__main__":
    main()
