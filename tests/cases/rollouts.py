"""Shared cases of the rollout tests: landmark layouts, noise, rule sets and a `run_trials` helper."""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from delvjax import Rules
from delvjax.core import rollouts
from delvjax.options import _registry as registry
from delvjax.options._setup import make_sensor

ARENA = [0.0, 0.0, 1000.0, 1000.0]
HOME = [500.0, 500.0]
NOISE = dict(
    bearing_noise_deg=2.0,
    step_noise=0.05,
    turn_noise_deg=3.0,
    odometry_turn_noise_deg=1.0,
    compass_noise_deg=2.0,
    motion_heading_noise_deg=5.0,
    motion_step_noise=0.1,
)
# four cylinders [x, y, r] around the default home (explicit: the built-in layouts may change)
FOUR = np.array([[330.0, 640.0, 30.0], [640.0, 720.0, 40.0], [720.0, 390.0, 25.0], [420.0, 300.0, 35.0]])
DEFAULT, PHYSICAL = rollouts.DEFAULT_RULES, rollouts.PHYSICAL_RULES
RULE_SETS = (DEFAULT, PHYSICAL)


def random_landmarks(rng, n):
    lms = []
    while len(lms) < n:
        r = rng.uniform(20, 40)
        x, y = rng.uniform(150, 850, 2)
        if math.hypot(x - 500, y - 500) < r + 60 or any(math.hypot(x - a, y - b) < r + c + 20 for a, b, c in lms):
            continue
        lms.append((x, y, r))
    return np.array(lms)


def run(
    env,
    starts,
    heads,
    method,
    config=None,
    lanes=rollouts.DEFAULT_LANES,
    key=0,
    masks=None,
    record_paths=False,
    first_move="homing",
    collisions="ignore",
    method_set=None,
):
    """`rollouts.run_trials` with trial i on noise stream i under one mask; lanes default as the public API
    (so that these programs are the ones `catchment` and `success_rate` compile)."""
    n = starts.shape[0]
    masks = env.valid[None] if masks is None else masks
    module = registry.METHODS[method] if method_set is None else registry.method_set(method, method_set)[0]
    return rollouts.run_trials(
        env,
        jnp.asarray(starts),
        jnp.asarray(heads),
        jnp.arange(n, dtype=jnp.int32),
        jnp.zeros(n, jnp.int32),
        masks,
        jax.random.PRNGKey(key),
        make_sensor() if config is None else config,
        module,
        record_paths=record_paths,
        rules=Rules(first_move=first_move, collisions=collisions, lanes=lanes),
    )


def angle_diff(a, b):
    return np.abs((np.asarray(a, float) - np.asarray(b, float) + math.pi) % (2 * math.pi) - math.pi)
