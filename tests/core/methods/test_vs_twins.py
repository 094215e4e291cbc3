"""Every method against the per-point NumPy twin on 20 random environments (>= 98% within 2 deg).

All 20 environments run as ONE batched program: `homing_directions` vmapped over a stacked Env, and
every method of this file runs in it as one `MethodSet` (its traced index picks the method, and only
that branch runs: tests/core/methods/test_modules.py checks that each of these seven gives its own
program's numbers bit for bit there), so the file compiles one program, not ten.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.maps import grid_included, grid_points, homing_directions, random_headings
from delvjax.core.scene import stack_envs
from delvjax.core.sensor import Sensor
from delvjax.options._registry import METHODS, configure, method_set
from tests.twins import methods as ref

# points checked per environment against the (slow, readable) twin
SUBSET = {"delv": 12, "delv-compass": 8, "alv": 8, "acv": 8, "delv-visual": 4, "alv-visual": 3, "acv-visual": 3}


@pytest.fixture(scope="module")
def batch(random_envs):
    envs = stack_envs([env for _, env in random_envs])
    points = jnp.asarray(grid_points((0, 0, 1000, 1000), 100.0))
    key = jax.random.PRNGKey(7)
    headings = random_headings(key, points.shape[0])
    included = jax.vmap(lambda e: grid_included(e, points, 10.0))(envs)
    return envs, points, headings, key, np.asarray(included)


NAMES = tuple(SUBSET)


@pytest.fixture(scope="module")
def directions(batch):
    """`directions(method, levels, visible)`: (direction, valid) of every environment and point, from
    the one compiled program of this file (a `MethodSet` of NAMES; every landmark visible by default)."""
    envs, points, headings, key, _ = batch
    shared, _ = method_set(NAMES[0], NAMES)
    run = jax.jit(jax.vmap(homing_directions, in_axes=(0, None, None, None, None, None, None)))

    def directions(method, levels=None, visible=None):
        i = NAMES.index(method)
        module = eqx.tree_at(lambda p: (p.index, p.methods[i]), shared, (i, configure(METHODS[method], levels=levels)))
        seen = jnp.ones(envs.landmarks.shape[1], bool) if visible is None else visible
        direction, valid = run(envs, points, headings, key, Sensor(), module, seen)
        return np.asarray(direction), np.asarray(valid)

    return directions


@pytest.mark.parametrize("method", list(SUBSET))
def test_method_agrees_with_reference(random_envs, batch, directions, method):
    envs, points, headings, key, included = batch
    levels = 3 if method == "delv-compass" else None
    direction, valid = directions(method, levels)
    rng = np.random.default_rng(0)
    agree, total = 0, 0
    for e, (lms, _) in enumerate(random_envs):  # the twin is per point by design
        for i in rng.choice(np.nonzero(included[e])[0], SUBSET[method], replace=False):
            expect = ref.reference_direction(
                lms,
                [0, 0, 1000, 1000],
                [500, 500],
                np.asarray(points[i], float),
                float(headings[i]),
                method,
                levels=levels,
            )
            total += 1
            if np.isnan(expect) or not valid[e, i]:
                agree += int(np.isnan(expect) and not valid[e, i])
            else:
                agree += int(abs(ref.wrap(expect - direction[e, i])) <= np.radians(2.0))
    assert agree / total >= 0.98, f"{method}: {agree}/{total}"


@pytest.mark.parametrize("method, points_per_env", [("delv-compass", 5), ("delv-visual", 2), ("delv", 3)])
def test_one_visible_landmark_agrees_with_reference(random_envs, batch, directions, method, points_per_env):
    """docs/model.md §3.4: all landmarks but the first hidden during homing (the home record sees all).
    With a compass (true or visual) one pair suffices: the direction is defined at every grid
    point and agrees with the twin (pairing the first shift, k = 0); without one it is undefined."""
    envs, points, headings, key, included = batch
    visible = jnp.arange(envs.landmarks.shape[1]) == 0
    direction, valid = directions(method, visible=visible)
    if method == "delv":
        assert not valid.any() and np.isnan(direction).all()
    else:
        assert valid[included].all()
    rng = np.random.default_rng(1)
    agree, total = 0, 0
    for e, (lms, _) in enumerate(random_envs):
        for i in rng.choice(np.nonzero(included[e])[0], points_per_env, replace=False):
            expect = ref.reference_direction(
                lms,
                [0, 0, 1000, 1000],
                [500, 500],
                np.asarray(points[i], float),
                float(headings[i]),
                method,
                visible=np.arange(len(lms)) == 0,
            )
            total += 1
            if np.isnan(expect) or not valid[e, i]:
                agree += int(np.isnan(expect) and not valid[e, i])
            else:
                agree += int(abs(ref.wrap(expect - direction[e, i])) <= np.radians(2.0))
    assert agree / total >= 0.98, f"{method}: {agree}/{total}"
