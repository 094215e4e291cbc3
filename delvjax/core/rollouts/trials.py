"""A set of trials as one compiled program, in blocks (docs/model.md §5; docs/reproduce.md).

Trials run in blocks of TRIAL_BLOCK (padded), each block one call of the same jitted program
(one compilation per method pytree structure and landmark count), so memory is bounded by the
block. Each trial keeps its own noise streams, so the numbers do not depend on the blocking.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import equinox as eqx
import jax
import numpy as np
from jax import Array

from ..batching import WIDTH, local_mesh, n_devices, over_devices, pad_rows
from ..batching import padded as padded_width
from ..deprecation import refuse_unknown
from ..errors import InputError
from ..maps import stream_keys
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensing import UnitMove, record_home
from ..sensor import Sensor
from ..types import Masks, PerTrial, PerTrialFlag, PerTrialInt, TrialPoints
from .config import Rules, legacy_config
from .lanes import run_block
from .rules import DEFAULT_FIRST_MOVE, MAX_STEPS, Outcomes, rollout_keys
from .step import Rollout

TRIAL_BLOCK = 16384
MASK_ROWS = 64  # visibility masks are padded to this many rows (all k of 6 landmarks: 42; one program)


PATH_BUDGET = 1 << 24  # positions kept per block when paths are recorded (128 MB)
# Up to this many positions a trial (max_steps + 1; the default max_steps 50 gives 51), every block keeps
# the paths in a buffer of this length (16384 x 64 x 2 float32 = 8 MB; `path_length`), so catchments, success
# rates and trajectories of every such max_steps are one compiled program; a longer rollout keeps them only
# for trajectories (docs/reproduce.md).
SHARED_PATH_STEPS = 64


def keeps_paths(max_steps: int, record_paths: bool = False) -> bool:
    """Whether the blocks of a rollout keep their paths: asked for, or cheap enough to share one program."""
    return bool(record_paths) or max_steps + 1 <= SHARED_PATH_STEPS


def path_length(max_steps: int, record_paths: bool) -> int:
    """Length of the blocks' path buffer: SHARED_PATH_STEPS for every max_steps that fits it (one program
    for them all, `Rollout.max_steps` being traced), else max_steps + 1; 1 where no path is kept."""
    if not keeps_paths(max_steps, record_paths):
        return 1
    return max(SHARED_PATH_STEPS, max_steps + 1)


def trial_block(n: int, max_steps: int = MAX_STEPS, record_paths: bool = False) -> int:
    """Trials run in blocks of TRIAL_BLOCK (padded), so catchments of every environment and
    occlusion, success-rate tables and trajectories share one compiled program. Only when the
    recorded paths of such a block would exceed PATH_BUDGET positions (a large max_steps) is the
    block cut to what fits, and to no more trials than asked."""
    if not record_paths or TRIAL_BLOCK * (max_steps + 1) <= PATH_BUDGET:
        return TRIAL_BLOCK
    fit = max(WIDTH, PATH_BUDGET // (max_steps + 1) // WIDTH * WIDTH)
    return min(padded_width(n), fit)


class Trials(Outcomes):
    """Per-trial results, T trials.

    outcome: (T,) int, index into OUTCOMES; steps: (T,) moves made; end: (T, 2) final
    position cm; invalid_steps: (T,) moves after which the method gave no direction;
    path: (T, max_steps + 1, 2) positions after 0, 1, ... moves, NaN after the end (or None);
    first_direction: (T,) world homing direction at the release point, rad, NaN where invalid
    (the vector map's direction there, under either first_move rule); first_valid: (T,);
    contact: (T,) the step of the trial's first landmark contact (NO_CONTACT: none), contact_end
    (T, 2) its position and contact_invalid (T,) the invalid moves before it (`rules.under_collisions`).
    """

    outcome: PerTrialInt
    steps: PerTrialInt
    end: TrialPoints
    invalid_steps: PerTrialInt
    first_direction: PerTrial
    first_valid: PerTrialFlag
    contact: PerTrialInt
    contact_end: TrialPoints
    contact_invalid: PerTrialInt
    path: Array | None = None
    first_move: str = eqx.field(static=True, default=DEFAULT_FIRST_MOVE)
    collisions: str = eqx.field(static=True, default="ignore")


def device_split(n_valid: int, n_dev: int, per_device: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rows of a block for each device's slice (device d: trials d q .. d q + count_d - 1, then
    padding), the counts (D,), and where the block's trials sit in the joined output."""
    q = -(-n_valid // n_dev)
    counts = np.clip(n_valid - q * np.arange(n_dev), 0, q).astype(np.int32)
    slot = np.arange(per_device)
    take = np.minimum(q * np.arange(n_dev)[:, None] + slot, n_valid - 1).ravel()
    keep = np.flatnonzero(slot[None, :] < counts[:, None])
    return take, counts, keep


@functools.lru_cache(maxsize=None)
def device_block(lanes: int, length: int = 1):
    """The per-device program of a block: one device's trials with `lanes` lanes (counts: (1,))."""

    def run(shared: Rollout, key_index, mask_index, starts, headings, counts):
        rollout = eqx.tree_at(
            lambda r: (r.key_index, r.mask_index), shared, (key_index, mask_index), is_leaf=lambda x: x is None
        )
        return run_block(rollout, starts, headings, counts[0], lanes, length)

    return run


@jax.jit
def home_record(env: Env, key: Array, sensor: Sensor) -> UnitMove:
    """The home record of a rollout seed (docs/model.md §3.3; the same as the vector map's of that seed)."""
    return record_home(env, rollout_keys(key)[0], sensor)


def run_trials(
    env: Env,
    starts: TrialPoints,
    headings: PerTrial,
    key_index: PerTrialInt,
    mask_index: PerTrialInt,
    masks: Masks,
    key: Array,
    sensor: Sensor,
    method: HomingMethod,
    rules: Rules | None = None,
    *,
    record_paths: bool = False,
    progress: Callable[[int, int], None] | None = None,
    **legacy,
) -> Trials:
    """Roll out T trials (docs/model.md §5), in blocks of one compiled program.

    starts: (T, 2) cm; headings: (T,) release headings rad; key_index: (T,) int, the trial's
    noise stream fold_in(key_rollout, key_index) and the vector map's view stream of its
    first direction (equal indices = common random numbers); mask_index: (T,) int into
    masks (M, L) bool, the landmarks visible during homing (the home record,
    `home_record(env, key, sensor)`, always sees all). `rules` (a `Rules`, core/rollouts/config.py;
    default `Rules()`): max_steps, home_radius, first_move, collisions and the `lanes` trials run side
    by side (finished lanes are refilled from the queue of pending trials). Several methods share one
    compiled program as a `methods.MethodSet`. `progress(done, T)` is called after each block. The
    flat keywords of earlier releases (max_steps=, ...) still work, deprecated (`legacy_config`).
    """
    rules = legacy_config(Rules, rules, legacy)
    refuse_unknown(legacy, "run_trials")
    max_steps, lanes = rules.max_steps, rules.lanes
    paths = keeps_paths(max_steps, record_paths)  # whether the blocks keep paths (trial_block sizes them)
    length = path_length(max_steps, record_paths)  # the blocks' static path buffer (1: none)
    n = int(starts.shape[0])
    if n == 0:
        raise InputError("starts", 0, "no trials to run")
    mesh = local_mesh()
    block = -(-trial_block(n, max_steps, paths) // n_devices(mesh)) * n_devices(mesh)
    padded = -(-n // block) * block
    # host-side padding and slicing (NumPy): no eager device op, so no compilation per shape
    pad = lambda a, dtype, size=padded: pad_rows(np.asarray(a, dtype), size)  # noqa: E731
    starts, headings = pad(starts, np.float32), pad(headings, np.float32)
    key_index, mask_index = pad(key_index, np.int32), pad(mask_index, np.int32)
    masks = pad(masks, bool, MASK_ROWS)  # C(N, k) masks of every k, padded likewise
    _, k_roll, _ = rollout_keys(key)
    _, k_views, _ = stream_keys(key)
    per_device = block // n_devices(mesh)
    blocks = []
    for i in range(0, padded, block):  # chunked driver: every block is the same compiled program
        rows = slice(i, i + block)
        rollout = Rollout(
            env=env,
            home=home_record(env, key, sensor),
            method=method,
            sensor=sensor,
            key_index=key_index[rows],
            mask_index=mask_index[rows],
            masks=masks,
            k_roll=k_roll,
            k_views=k_views,
            radius=np.float32(rules.home_radius),
            max_steps=np.int32(max_steps),
            homing_first=np.bool_(rules.first_move == "homing"),
            collide=np.bool_(rules.collisions == "fail"),
        )
        n_valid = min(block, n - i)
        if mesh is None:
            res = run_block(rollout, starts[rows], headings[rows], np.int32(n_valid), lanes, length)
        else:  # device d runs trials [d q, (d + 1) q) of the block, q = ceil(n_valid / D): whole trials, same program
            take, counts, keep = device_split(n_valid, mesh.size, per_device)
            shared = eqx.tree_at(
                lambda r: (r.key_index, r.mask_index), rollout, (None, None), is_leaf=lambda x: x is None
            )
            res = over_devices(
                device_block(-(-lanes // mesh.size), length),
                mesh,
                1,
                shared,
                rollout.key_index[take],
                rollout.mask_index[take],
                starts[rows][take],
                headings[rows][take],
                counts,
            )
            res = jax.tree.map(lambda a: np.asarray(a)[keep], res)
        res = res if record_paths else eqx.tree_at(lambda r: r.path, res, None, is_leaf=lambda x: x is None)
        blocks.append(jax.tree.map(np.asarray, res))  # waits for the block, so progress is real
        if progress is not None:
            progress(n_valid, n)
    res = jax.tree.map(lambda *a: jax.device_put(np.concatenate(a)[:n]), *blocks)
    return Trials(
        outcome=res.outcome,
        steps=res.steps,
        end=res.end,
        invalid_steps=res.invalid,
        first_direction=res.first_dir,
        first_valid=res.first_valid,
        contact=res.contact,
        contact_end=res.contact_end,
        contact_invalid=res.contact_invalid,
        path=res.path[:, : max_steps + 1] if record_paths else None,  # the buffer may be longer (path_length)
        first_move=rules.first_move,
        collisions=rules.collisions,
    )
