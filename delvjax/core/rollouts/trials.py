"""A set of trials as one compiled program, in blocks (docs/model.md §5; docs/reproduce.md).

Trials run in blocks of TRIAL_BLOCK (padded), each block one call of the same jitted program
(one compilation per method pytree structure and landmark count), so memory is bounded by the
block. Each trial keeps its own noise streams, so the numbers do not depend on the blocking.
"""

from __future__ import annotations

import equinox as eqx
import jax
import numpy as np
from jax import Array

from ..errors import InputError
from ..maps import stream_keys
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensing import UnitMove, record_home
from ..sensor import Sensor
from ..types import Masks, PerTrial, PerTrialFlag, PerTrialInt, TrialPoints
from .lanes import run_block
from .rules import DEFAULT_LANES, HOME_RADIUS, MAX_STEPS, Outcomes, check_rules, rollout_keys
from .step import Rollout

TRIAL_BLOCK = 16384
MASK_ROWS = 64  # visibility masks are padded to this many rows (all k of 6 landmarks: 42; one program)


def trial_block(n: int) -> int:
    """Trials run in blocks of TRIAL_BLOCK (padded), so catchments of every environment and
    occlusion, success-rate tables and trajectories share one compiled program."""
    return TRIAL_BLOCK


class Trials(Outcomes):
    """Per-trial results, T trials.

    outcome: (T,) int, index into OUTCOMES; steps: (T,) moves made; end: (T, 2) final
    position cm; invalid_steps: (T,) moves after which the method gave no direction;
    path: (T, max_steps + 1, 2) positions after 0, 1, ... moves, NaN after the end (or None);
    first_direction: (T,) world homing direction at the release point, rad, NaN where invalid
    (the vector map's direction there, under either first_move rule); first_valid: (T,).
    """

    outcome: PerTrialInt
    steps: PerTrialInt
    end: TrialPoints
    invalid_steps: PerTrialInt
    first_direction: PerTrial
    first_valid: PerTrialFlag
    path: Array | None = None
    first_move: str = eqx.field(static=True, default="homing")
    collisions: str = eqx.field(static=True, default="ignore")


@jax.jit
def home_record(env: Env, key: Array, sensor: Sensor) -> UnitMove:
    """The home record of a rollout seed (docs/model.md §3.3; the same as the vector map's of that seed)."""
    return record_home(env, rollout_keys(key)[0], sensor)


def run_trials(env: Env, starts: TrialPoints, headings: PerTrial, key_index: PerTrialInt, mask_index: PerTrialInt, masks: Masks,
               key: Array, sensor: Sensor, method: HomingMethod, home_radius: float = HOME_RADIUS,
               max_steps: int = MAX_STEPS, lanes: int = DEFAULT_LANES, record_paths: bool = False,
               first_move: str = "homing", collisions: str = "ignore") -> Trials:
    """Roll out T trials (docs/model.md §5), in blocks of one compiled program.

    starts: (T, 2) cm; headings: (T,) release headings rad; key_index: (T,) int, the trial's
    noise stream fold_in(key_rollout, key_index) and the vector map's view stream of its
    first direction (equal indices = common random numbers); mask_index: (T,) int into
    masks (M, L) bool, the landmarks visible during homing (the home record,
    `home_record(env, key, sensor)`, always sees all). `lanes` trials run side by side;
    finished lanes are refilled from the queue of pending trials. `first_move` and
    `collisions` are the rules of `rules`. Several methods share one compiled program as a
    `methods.Program`.
    """
    check_rules(first_move, collisions)
    env = env.arrays()  # compile once per shape, not per environment name
    n = int(starts.shape[0])
    if n == 0:
        raise InputError("starts", 0, "no trials to run")
    block = trial_block(n)
    padded = -(-n // block) * block
    # host-side padding and slicing (NumPy): no eager device op, so no compilation per shape
    pad = lambda a, m, dtype: np.concatenate([np.asarray(a, dtype), np.repeat(np.asarray(a, dtype)[:1], m, axis=0)])  # noqa: E731
    starts, headings = pad(starts, padded - n, np.float32), pad(headings, padded - n, np.float32)
    key_index, mask_index = pad(key_index, padded - n, np.int32), pad(mask_index, padded - n, np.int32)
    masks = pad(masks, max(0, MASK_ROWS - len(masks)), bool)  # C(N, k) masks of every k, padded likewise
    _, k_roll, _ = rollout_keys(key)
    _, k_views, _ = stream_keys(key)
    blocks = []
    for i in range(0, padded, block):  # chunked driver: every block is the same compiled program
        rows = slice(i, i + block)
        rollout = Rollout(env=env, home=home_record(env, key, sensor), method=method, sensor=sensor,
                          key_index=key_index[rows], mask_index=mask_index[rows], masks=masks, k_roll=k_roll,
                          k_views=k_views, radius=np.float32(home_radius), max_steps=max_steps,
                          homing_first=np.bool_(first_move == "homing"), collide=np.bool_(collisions == "fail"))
        res = run_block(rollout, starts[rows], headings[rows], np.int32(min(block, n - i)), lanes)
        blocks.append(res if record_paths else eqx.tree_at(lambda r: r.path, res, None, is_leaf=lambda x: x is None))
    res = jax.tree.map(lambda *a: jax.device_put(np.concatenate([np.asarray(x) for x in a])[:n]), *blocks)
    return Trials(outcome=res.outcome, steps=res.steps, end=res.end, invalid_steps=res.invalid,
                  first_direction=res.first_dir, first_valid=res.first_valid, path=res.path if record_paths else None,
                  first_move=first_move, collisions=collisions)
