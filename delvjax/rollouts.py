"""Homing rollouts, catchment area, success rate, trajectories and occlusion (thesis §4.3, §5.3.1; docs/model.md §5).

A rollout (docs/model.md §5): released at a point with a heading, the agent computes the homing
direction, turns to it and moves `d`; it senses the move just made as its unit movement,
asks the homing method for a direction at the new point, turns to it, and so on. It
succeeds when within `home_radius` of home at the release point or after a move, within
`max_steps` moves; a move ending outside the arena ends it as a failure; an invalid
direction keeps the heading.

Rules (docs/model.md §5), both recorded in every summary and CSV:
  * first_move = "homing" (default): at the release point the direction is computed exactly
    as in the vector map (a unit move of length d along the release heading that *ends* at
    the start, with the vector map's noise stream of that point); "release": the first move
    goes along the release heading (a robot with no stored move).
  * collisions = "ignore" (default): landmarks are no obstacles; "fail": a move ending
    inside a landmark (distance to its centre < r) ends the trial as a failure.

Noise in rollouts (docs/model.md §2.5; SPEC leaves the details to us; decided here):
  * executed heading = commanded heading + N(0, motion_heading);
  * true length = d * (1 + N(0, step)) * (1 + N(0, motion_step)); the odometry reports d_hat = d;
  * the body turns by psi ~ N(0, turn) during the move (the end view has heading
    executed + psi); odometry reports psi_hat = psi + N(0, turn_odometry);
  * bearing and compass noise come from `sensing.observe_move` (start and end snapshots
    of the move just made); the new heading is heading_end + agent-frame direction.
All draws use the key fold_in(fold_in(key_rollout, trial key index), step index), so
results do not depend on how trials are scheduled; with every sigma 0 the draws are
multiplied by 0 and the noise-free numbers are reproduced exactly.

Batching: trials run in blocks of TRIAL_BLOCK (padded), each block one call of the same
jitted program (one compilation per set of methods, `program`, and landmark count), so memory is bounded by the
block. Inside a block `lanes` trials advance together (vmap) in a `lax.while_loop`; a lane
whose trial ends (most succeed within 15 moves) is refilled with the next pending trial, so
the loop costs about sum(steps + 1) / lanes iterations instead of max_steps per chunk. A
lane's first iteration computes the vector map's direction at its release point (the
method appears once in the program). An invalid first direction keeps the heading at the
end of that imagined unit move (release heading + turn noise, which is 0 by default).
"""

from __future__ import annotations

import dataclasses
import itertools
from functools import partial
from pathlib import Path
from typing import Sequence

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from scipy import stats
from jax import Array

from .config import Config
from .errors import InputError
from .geometry import TWO_PI, unit, wrap
from .maps import grid_included, grid_points, random_headings, stream_keys
from .methods import METHODS, get_method, uses_gray, uses_start_view
from .metrics import angular_error_deg, error_point_rates
from .scene import Env
from .sensing import UnitMove, observe_move, record_home, unit_move_poses

# Trial outcome codes (a running trial is RUNNING; a grid cell never released is EXCLUDED).
OUTCOMES = ("success", "timeout", "landmark", "arena")
SUCCESS, TIMEOUT, LANDMARK, ARENA = range(4)
RUNNING, EXCLUDED = -1, -2
FIRST_MOVES = ("homing", "release")
COLLISIONS = ("ignore", "fail")
DEFAULT_RULES = {"first_move": "homing", "collisions": "ignore"}
PHYSICAL_RULES = {"first_move": "release", "collisions": "fail"}
# "Within home_radius" is inclusive; 1e-3 cm absorbs float32 rounding of a release placed at
# exactly home_radius (the first success-rate bin), so such a release counts as home.
HOME_TOLERANCE = 1e-3
DEFAULT_LANES = 256
DEFAULT_DISTANCES = tuple(float(v) for v in range(50, 451, 50))
TRIAL_BLOCK = 16384
MASK_ROWS = 64  # visibility masks are padded to this many rows (all k of 6 landmarks: 42; one program)
START_TRIES = 64  # candidate release points per trial before a trial counts as not placed


def rollout_keys(key: Array) -> tuple[Array, Array, Array]:
    """(home record, rollout steps, release points) keys of one seed.

    The home record and per-point headings use the same streams as `maps.vector_map`, so a
    catchment map and the vector map of the same seed share the home record and headings.
    """
    k_home, _, _ = stream_keys(key)
    return k_home, jax.random.fold_in(key, 3), jax.random.fold_in(key, 4)


# --- one trial ---------------------------------------------------------------------------

def position_status(env: Env, pos: Array, home_radius: Array, collide: Array | bool = True) -> Array:
    """docs/model.md §5 status of a point: LANDMARK (inside a cylinder; only where `collide`, the rule
    collisions="fail"), ARENA (outside), SUCCESS (at home) or RUNNING."""
    lm = env.landmarks
    dist = jnp.sqrt(jnp.sum((pos[None, :] - lm[:, :2]) ** 2, axis=-1))
    inside = jnp.any(env.valid & (dist < lm[:, 2])) & collide
    a = env.arena
    outside = (pos[0] < a[0]) | (pos[0] > a[2]) | (pos[1] < a[1]) | (pos[1] > a[3])
    at_home = jnp.sqrt(jnp.sum((pos - env.home) ** 2)) <= home_radius + HOME_TOLERANCE
    return jnp.where(inside, LANDMARK, jnp.where(outside, ARENA, jnp.where(at_home, SUCCESS, RUNNING)))


def move_poses(pos: Array, heading: Array, key: Array, config: Config):
    """The poses and odometry of one rollout move from `pos` with commanded `heading` (module
    docstring's noise): (start, end, executed heading, heading at the end, psi_hat, observation key),
    the same tuple as `sensing.unit_move_poses`."""
    noise = config.noise
    k_draw, k_obs = jax.random.split(key)
    z_heading, z_step, z_motion_step, z_turn, z_odometry = jax.random.normal(k_draw, (5,))
    executed = heading + noise.motion_heading * z_heading
    length = config.d * (1.0 + noise.step * z_step) * (1.0 + noise.motion_step * z_motion_step)
    psi = noise.turn * z_turn
    return pos, pos + length * unit(executed), executed, executed + psi, psi + noise.turn_odometry * z_odometry, k_obs


# --- a set of trials in one program ------------------------------------------------------

class _Outcomes(eqx.Module):
    """Results with an `outcome` field (codes into OUTCOMES)."""

    @property
    def success(self) -> Array:
        """True where the trial reached home."""
        return np.asarray(self.outcome) == SUCCESS  # type: ignore[attr-defined]

    @property
    def rules(self) -> dict[str, str]:
        """The rollout rules used (module docstring): {"first_move": ..., "collisions": ...}."""
        return {"first_move": self.first_move, "collisions": self.collisions}  # type: ignore[attr-defined]


class Trials(_Outcomes):
    """Per-trial results, T trials.

    outcome: (T,) int, index into OUTCOMES; steps: (T,) moves made; end: (T, 2) final
    position cm; invalid_steps: (T,) moves after which the method gave no direction;
    path: (T, max_steps + 1, 2) positions after 0, 1, ... moves, NaN after the end (or None);
    first_direction: (T,) world homing direction at the release point, rad, NaN where invalid
    (the vector map's direction there, under either first_move rule); first_valid: (T,).
    """

    outcome: Array
    steps: Array
    end: Array
    invalid_steps: Array
    first_direction: Array
    first_valid: Array
    path: Array | None = None
    first_move: str = eqx.field(static=True, default="homing")
    collisions: str = eqx.field(static=True, default="ignore")


@jax.jit
def home_record(env: Env, key: Array, config: Config) -> UnitMove:
    """The home record of a rollout seed (docs/model.md §3.3; the same as the vector map's of that seed)."""
    return record_home(env, rollout_keys(key)[0], config)


def run_trials(env: Env, starts: Array, headings: Array, key_index: Array, mask_index: Array, masks: Array,
               key: Array, config: Config, method: str, home_radius: float = 50.0, max_steps: int = 50,
               lanes: int = DEFAULT_LANES, record_paths: bool = False, first_move: str = "homing",
               collisions: str = "ignore", program: Sequence[str] | None = None) -> Trials:
    """Roll out T trials (docs/model.md §5), in blocks of one compiled program.

    starts: (T, 2) cm; headings: (T,) release headings rad; key_index: (T,) int, the trial's
    noise stream fold_in(key_rollout, key_index) and the vector map's view stream of its
    first direction (equal indices = common random numbers); mask_index: (T,) int into
    masks (M, L) bool, the landmarks visible during homing (the home record,
    `home_record(env, key, config)`, always sees all). `lanes` trials run side by side;
    finished lanes are refilled from the queue of pending trials. `first_move` and
    `collisions` are the rules of the module docstring. `program`: the methods compiled into
    the same program (`program_method`; default just `method`): callers that run several
    methods compile once, at the price of a larger program.
    """
    methods = check_program(method, program)
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
    home = home_record(env, key, config)
    flags = jnp.asarray(first_move == "homing"), jnp.asarray(collisions == "fail")
    blocks = []
    for i in range(0, padded, block):  # chunked driver: every block is the same compiled program
        res = _run_trials(env, home, starts[i:i + block], headings[i:i + block], key_index[i:i + block],
                          mask_index[i:i + block], masks, key, config, methods, jnp.int32(methods.index(method)),
                          home_radius, max_steps, lanes,
                          jnp.int32(min(block, n - i)), *flags)
        blocks.append(res if record_paths else eqx.tree_at(lambda r: r.path, res, None, is_leaf=lambda x: x is None))
    res = jax.tree.map(lambda *a: jax.device_put(np.concatenate([np.asarray(x) for x in a])[:n]), *blocks)
    return dataclasses.replace(res, first_move=first_move, collisions=collisions)


def trial_block(n: int) -> int:
    """Trials run in blocks of TRIAL_BLOCK (padded), so catchments of every environment and
    occlusion, success-rate tables and trajectories share one compiled program; each
    trial keeps its own noise streams, so the numbers do not depend on the blocking."""
    return TRIAL_BLOCK


def check_program(method: str, program: Sequence[str] | None) -> tuple[str, ...]:
    """The validated methods of one rollout program (`run_trials`), a tuple containing `method`."""
    get_method(method)
    if program is not None and (isinstance(program, (str, bytes)) or not hasattr(program, "__iter__")):
        raise InputError("program", program, "must be a list of method names")
    methods = (method,) if program is None else tuple(program)
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        raise InputError("program", list(methods), f"unknown method {unknown[0]!r} (choose from {', '.join(METHODS)})")
    if method not in methods:
        raise InputError("program", list(methods), f"must contain the method {method!r}")
    return methods


def check_rules(first_move: str, collisions: str) -> dict[str, str]:
    """Validated rollout rules (module docstring) as the dict recorded in summaries."""
    if first_move not in FIRST_MOVES:
        raise InputError("first_move", first_move, f"must be one of {', '.join(FIRST_MOVES)}")
    if collisions not in COLLISIONS:
        raise InputError("collisions", collisions, f"must be one of {', '.join(COLLISIONS)}")
    return {"first_move": first_move, "collisions": collisions}


def program_method(methods: tuple[str, ...]):
    """One method function for the methods of one program: `fn(home, view, config, index)` runs
    methods[index]. With several methods the traced index selects a branch of a `lax.switch`
    (unbatched, so only that branch runs): the methods share one compiled rollout program."""
    fns = [get_method(m) for m in methods]
    if len(fns) == 1:
        return lambda home, view, config, index: fns[0](home, view, config)

    def typed(fn):
        def branch(home, view, config):
            angle, valid = fn(home, view, config)
            return jnp.asarray(angle, jnp.float32), jnp.asarray(valid, bool)
        return branch

    branches = [typed(fn) for fn in fns]
    return lambda home, view, config, index: jax.lax.switch(index, branches, home, view, config)


@partial(jax.jit, static_argnames=("methods", "max_steps", "lanes"))
def _run_trials(env: Env, home: UnitMove, starts: Array, headings: Array, key_index: Array, mask_index: Array,
                masks: Array, key: Array, config: Config, methods: tuple[str, ...], method_index: Array,
                home_radius: float, max_steps: int, lanes: int, n_valid: Array, homing_first: Array,
                collide: Array) -> Trials:
    """One block of trials, the first `n_valid` real (the padding is never run). A lane first spends one iteration at its release point computing the
    vector map's direction there (a unit move ending at the release point, the vector map's
    noise stream; recorded as first_direction, and the first heading under first_move="homing"),
    then one move per iteration, so the method appears once in the program."""
    fn = program_method(methods)

    def needs(flags: list[bool]) -> Array | bool:  # the same for every method: decided when tracing
        return flags[0] if len(set(flags)) == 1 else jnp.asarray(flags)[method_index]

    with_start = needs([uses_start_view(m) for m in methods])
    with_gray = needs([uses_gray(m, config.channel) for m in methods])
    n_trials = starts.shape[0]
    n_lanes = max(1, min(lanes, n_trials))
    _, k_roll, _ = rollout_keys(key)
    _, k_views, _ = stream_keys(key)
    radius = jnp.asarray(home_radius, jnp.float32)

    def init_lane(t):
        ok = t < n_valid
        ts = jnp.minimum(t, n_trials - 1)
        pos = starts[ts]
        status = jnp.where(ok, position_status(env, pos, radius, collide), RUNNING)
        return pos, headings[ts], status

    def advance_lane(t, pos, heading, step, first):
        ts = jnp.minimum(t, n_trials - 1)
        at_release = unit_move_poses(pos, heading, jax.random.fold_in(k_views, key_index[ts]), config, end_at=pos)
        k = jax.random.fold_in(jax.random.fold_in(k_roll, key_index[ts]), step)
        moving = move_poses(pos, heading, k, config)
        start, end, h_start, h_end, psi_hat, k_obs = jax.tree.map(lambda a, b: jnp.where(first, a, b),
                                                                  at_release, moving)
        view = observe_move(env, masks[mask_index[ts]], start, end, h_start, h_end, config.d, psi_hat, k_obs, config,
                            with_start, with_gray)
        angle, valid = fn(home, view, config, method_index)
        direction = jnp.where(valid, wrap(h_end + angle), jnp.nan)
        new_heading = jnp.where(valid, direction, wrap(h_end))
        first_heading = jnp.where(homing_first, new_heading, heading)
        status = position_status(env, end, radius, collide)
        status = jnp.where((status == RUNNING) & (step + 1 >= max_steps), TIMEOUT, status)
        return end, jnp.where(first, first_heading, new_heading), status, valid, direction

    lane_t = jnp.arange(n_lanes, dtype=jnp.int32)
    lane_t = jnp.where(lane_t < n_valid, lane_t, n_trials)
    pos, heading, status = jax.vmap(init_lane)(lane_t)
    zeros_t = jnp.zeros(n_trials, jnp.int32)
    out = dict(outcome=jnp.full(n_trials, RUNNING, jnp.int32), steps=zeros_t, invalid=zeros_t,
               end=jnp.zeros((n_trials, 2), jnp.float32), first_dir=jnp.full(n_trials, jnp.nan, jnp.float32),
               first_valid=jnp.zeros(n_trials, bool))
    path = jnp.full((n_trials, max_steps + 1, 2), jnp.nan, jnp.float32).at[:, 0].set(starts)
    lane = dict(t=lane_t, pos=pos, heading=heading, status=status, first=jnp.ones(n_lanes, bool),
                step=jnp.zeros(n_lanes, jnp.int32), invalid=jnp.zeros(n_lanes, jnp.int32))
    state = (lane, out, path, jnp.minimum(jnp.int32(n_lanes), n_valid))

    def cond(state):
        return jnp.any(state[0]["t"] < n_valid)

    def body(state):
        lane, out, path, next_t = state
        # 1. every active lane: its first direction (at the release point) or one move
        active = lane["t"] < n_valid
        first = active & lane["first"]
        moving = active & ~lane["first"] & (lane["status"] == RUNNING)
        end, new_heading, status, valid, direction = jax.vmap(advance_lane)(
            lane["t"], lane["pos"], lane["heading"], lane["step"], lane["first"])
        idx0 = jnp.where(first, lane["t"], n_trials)
        out = dict(out, first_dir=out["first_dir"].at[idx0].set(direction, mode="drop"),
                   first_valid=out["first_valid"].at[idx0].set(valid, mode="drop"))
        lane = dict(
            t=lane["t"],
            pos=jnp.where(moving[:, None], end, lane["pos"]),
            heading=jnp.where(moving | first, new_heading, lane["heading"]),
            status=jnp.where(moving, status, lane["status"]),
            first=lane["first"] & ~active,
            step=lane["step"] + moving.astype(jnp.int32),
            invalid=lane["invalid"] + (moving & ~valid & (status == RUNNING)).astype(jnp.int32),
        )
        path = path.at[jnp.where(moving, lane["t"], n_trials), lane["step"]].set(lane["pos"], mode="drop")
        # 2. write the lanes whose trial has ended (after its first direction)
        done = active & ~lane["first"] & (lane["status"] != RUNNING)
        idx = jnp.where(done, lane["t"], n_trials)
        out = dict(out, outcome=out["outcome"].at[idx].set(lane["status"], mode="drop"),
                   steps=out["steps"].at[idx].set(lane["step"], mode="drop"),
                   invalid=out["invalid"].at[idx].set(lane["invalid"], mode="drop"),
                   end=out["end"].at[idx].set(lane["pos"], mode="drop"))
        # 3. refill them from the queue
        new_t = jnp.where(done, next_t + jnp.cumsum(done) - 1, lane["t"])
        new_t = jnp.where(done & (new_t >= n_valid), n_trials, new_t).astype(jnp.int32)
        pos0, heading0, status0 = jax.vmap(init_lane)(new_t)
        lane = dict(
            t=new_t,
            pos=jnp.where(done[:, None], pos0, lane["pos"]),
            heading=jnp.where(done, heading0, lane["heading"]),
            status=jnp.where(done, status0, lane["status"]),
            first=lane["first"] | done,
            step=jnp.where(done, 0, lane["step"]),
            invalid=jnp.where(done, 0, lane["invalid"]),
        )
        return lane, out, path, next_t + jnp.sum(done).astype(jnp.int32)

    _, out, path, _ = jax.lax.while_loop(cond, body, state)
    return Trials(outcome=out["outcome"], steps=out["steps"], end=out["end"], invalid_steps=out["invalid"],
                  first_direction=out["first_dir"], first_valid=out["first_valid"], path=path)


# --- occlusion masks ---------------------------------------------------------------------

def occlusion_masks(env: Env, k: int) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """All C(N, k) visibility masks (M, L) bool with k of the N landmarks hidden, and the hidden index tuples."""
    n = env.n_landmarks
    combos = list(itertools.combinations(range(n), k))
    masks = np.tile(np.asarray(env.valid, bool), (len(combos), 1))
    for m, hidden in enumerate(combos):  # input preparation: C(N, k) <= 20 small rows
        masks[m, list(hidden)] = False
    return masks, combos


def hidden_masks(env: Env, hidden: Sequence[int] | None) -> tuple[np.ndarray, list[tuple[int, ...]]]:
    """The single mask (1, L) hiding `hidden` (or none)."""
    masks = np.asarray(env.valid, bool)[None, :].copy()
    hidden = tuple(int(i) for i in (hidden or ()))
    masks[0, list(hidden)] = False
    return masks, [hidden]


# --- catchment area ----------------------------------------------------------------------

class Catchment(_Outcomes):
    """Catchment area of one method on the docs/model.md §5 grid under M visibility masks.

    points: (P, 2) all grid cells; included: (P,); heading: (P,) release heading rad;
    visible: (M, L) landmarks seen while homing; outcome, steps, invalid_steps: (M, P)
    (outcome EXCLUDED for cells that are not grid points); end: (M, P, 2); the vector map
    under each mask with the same headings and home record: direction (M, P) world rad
    (NaN where invalid), valid (M, P), error_deg (M, P).
    """

    points: Array
    included: Array
    heading: Array
    visible: Array
    outcome: Array
    steps: Array
    end: Array
    invalid_steps: Array
    direction: Array
    valid: Array
    error_deg: Array
    hidden: tuple = eqx.field(static=True, default=((),))
    first_move: str = eqx.field(static=True, default="homing")
    collisions: str = eqx.field(static=True, default="ignore")

    def catchment_pct(self) -> np.ndarray:
        """% of grid points whose rollout succeeds, per mask (M,)."""
        inc = np.asarray(self.included)
        return 100.0 * np.asarray(self.success)[:, inc].mean(axis=1)


def catchment_area(env: Env, method: str, config: Config, spacing: float = 25.0, heading: float | None = None,
                   key: Array | None = None, clearance: float = 10.0, masks: np.ndarray | None = None,
                   hidden: Sequence[tuple[int, ...]] = ((),), home_radius: float = 50.0, max_steps: int = 50,
                   lanes: int = DEFAULT_LANES, first_move: str = "homing", collisions: str = "ignore",
                   program: Sequence[str] | None = None) -> Catchment:
    """Rollouts from every grid point under every mask in `masks` (M, L), one program (docs/model.md §5).

    Headings: fixed (rad) or per point from `key` as in `maps.random_headings`. The trial of
    grid cell i uses noise stream i under every mask (common random numbers across masks).
    The vector map under each mask comes from the same program (each trial's first direction).
    """
    key = jax.random.PRNGKey(0) if key is None else key
    masks = np.asarray(env.valid, bool)[None, :] if masks is None else np.asarray(masks, bool)
    # input preparation on the host (NumPy): eager device ops would compile once per shape
    points = grid_points(env.arena, spacing)
    n_cells = points.shape[0]
    headings = np.asarray(random_headings(key, n_cells) if heading is None else np.full(n_cells, heading, np.float32))
    included = np.asarray(grid_included(env, points, clearance))
    cells = np.flatnonzero(included)  # which cells are released
    if cells.size == 0:
        raise InputError("spacing", spacing, "leaves no grid point clear of the landmarks (r + clearance)")
    n_masks, n_inc = masks.shape[0], cells.size
    trial_cell = np.tile(cells, n_masks).astype(np.int32)
    trial_mask = np.repeat(np.arange(n_masks, dtype=np.int32), n_inc)
    trials = run_trials(env, points[trial_cell], headings[trial_cell], trial_cell, trial_mask, masks, key, config, method,
                        home_radius=home_radius, max_steps=max_steps, lanes=lanes, first_move=first_move,
                        collisions=collisions, program=program)

    def per_cell(values, fill):
        values = np.asarray(values)
        full = np.full((n_masks, n_cells) + values.shape[1:], fill, values.dtype)
        full[:, cells] = values.reshape((n_masks, n_inc) + values.shape[1:])
        return jax.device_put(full)  # host to device without an eager op (no compile per shape)

    direction = per_cell(trials.first_direction, jnp.nan)  # the vector map under each mask
    valid = per_cell(trials.first_valid, False)
    error = angular_error_deg(direction, valid, points[None], env.home)
    return Catchment(points=jax.device_put(points), included=jax.device_put(included), heading=jax.device_put(headings),
                     visible=jax.device_put(masks),
                     outcome=per_cell(trials.outcome, EXCLUDED), steps=per_cell(trials.steps, 0),
                     end=per_cell(trials.end, jnp.nan), invalid_steps=per_cell(trials.invalid_steps, 0),
                     direction=direction, valid=valid, error_deg=error,
                     hidden=tuple(tuple(int(i) for i in h) for h in hidden), first_move=first_move,
                     collisions=collisions)


def catchment_summary(result: Catchment) -> dict:
    """Headline numbers: catchment % and error point rates per mask, and their mean, min and max (Tables 5.1-5.4)."""
    pct = result.catchment_pct()
    inc = np.asarray(result.included)
    outcome = np.asarray(result.outcome)[:, inc]
    steps = np.asarray(result.steps)[:, inc]
    per_mask = []
    for m, hidden in enumerate(result.hidden):  # M <= 20 rows of post-processing
        rates = error_point_rates(np.asarray(result.error_deg)[m], inc)
        ok = outcome[m] == SUCCESS
        per_mask.append({
            "hidden": list(hidden), "catchment_pct": float(pct[m]), **rates,
            "invalid_pct": 100.0 * float((~np.asarray(result.valid)[m][inc]).mean()),
            "mean_steps_success": float(steps[m][ok].mean()) if ok.any() else float("nan"),
            **{f"{name}_count": int((outcome[m] == code).sum()) for code, name in enumerate(OUTCOMES)},
        })

    def spread(field):
        v = np.array([row[field] for row in per_mask])
        return {"mean": float(v.mean()), "min": float(v.min()), "max": float(v.max())}

    return {"rules": result.rules, "points": int(inc.sum()), "masks": len(per_mask), "catchment_pct": spread("catchment_pct"),
            "gt45_pct": spread("gt45_pct"), "gt90_pct": spread("gt90_pct"), "per_mask": per_mask}


# --- release points ----------------------------------------------------------------------

def clear_of_landmarks(env: Env, pos: Array, clearance: float, margin: float = 0.0) -> Array:
    """At least `margin` inside the arena and farther than r + clearance + margin from every landmark centre.

    margin 0 is the grid rule of docs/model.md §5; margin d keeps the first move, whatever its heading, clear.
    """
    a = env.arena
    inside = ((pos[..., 0] >= a[0] + margin) & (pos[..., 0] <= a[2] - margin)
              & (pos[..., 1] >= a[1] + margin) & (pos[..., 1] <= a[3] - margin))
    dist = jnp.sqrt(jnp.sum((pos[..., None, :] - env.landmarks[:, :2]) ** 2, axis=-1))
    near = jnp.any(env.valid & (dist <= env.landmarks[:, 2] + clearance + margin), axis=-1)
    return inside & ~near


@partial(jax.jit, static_argnames=("n", "tries"))
def release_points(env: Env, key: Array, n: int, distance: Array | None = None, clearance: float = 10.0,
                   min_home_distance: float = 0.0, margin: float = 0.0,
                   tries: int = START_TRIES) -> tuple[Array, Array, Array]:
    """n seeded release points: (points (n, 2), headings (n,), placed (n,)).

    Trial t draws candidates j = 0.. tries-1 from fold_in(fold_in(key, t), j): a uniform
    direction at `distance` from home, or (distance None) a uniform point in the arena,
    and a uniform heading. The first candidate that is `clear_of_landmarks(clearance, margin)`
    and at least `min_home_distance` from home is taken; `placed` is False if none.
    """

    def candidate(k):
        k_phi, k_x, k_head = jax.random.split(k, 3)
        if distance is None:
            lo, hi = env.arena[:2], env.arena[2:]
            pos = lo + (hi - lo) * jax.random.uniform(k_x, (2,))
        else:
            pos = env.home + distance * unit(jax.random.uniform(k_phi, (), maxval=TWO_PI))
        return pos, jax.random.uniform(k_head, (), maxval=TWO_PI)

    def one(t):
        keys = jax.vmap(partial(jax.random.fold_in, jax.random.fold_in(key, t)))(jnp.arange(tries))
        pos, head = jax.vmap(candidate)(keys)
        ok = clear_of_landmarks(env, pos, clearance, margin)
        ok = ok & (jnp.sqrt(jnp.sum((pos - env.home) ** 2, axis=-1)) >= min_home_distance)
        first = jnp.argmax(ok)
        return pos[first], head[first], ok[first]

    return jax.vmap(one)(jnp.arange(n))


# --- success rate vs release distance -----------------------------------------------------

class SuccessRate(_Outcomes):
    """Success rate per release distance (Figs 4.10b, 5.7b).

    distances: (D,) cm; start: (D, n, 2); heading: (D, n) rad; placed: (D, n) a release
    point was found (SPEC: start inside a landmark or outside the arena -> resampled);
    outcome, steps: (D, n) (outcome EXCLUDED where not placed).
    """

    distances: Array
    start: Array
    heading: Array
    placed: Array
    outcome: Array
    steps: Array
    first_move: str = eqx.field(static=True, default="homing")
    collisions: str = eqx.field(static=True, default="ignore")

    def table(self) -> list[dict]:
        """Per-bin rows: distance_cm, trials, placed, successes, success_pct (of placed) with its 95% Wilson
        interval (ci_lo_pct, ci_hi_pct), mean_steps_success, and a count per failure outcome."""
        outcome, steps, placed = (np.asarray(v) for v in (self.outcome, self.steps, self.placed))
        rows = []
        for b, dist in enumerate(np.asarray(self.distances)):  # D <= a dozen bins: post-processing
            ok = outcome[b] == SUCCESS
            n_placed = int(placed[b].sum())
            rows.append({
                "distance_cm": float(dist), "trials": int(placed.shape[1]), "placed": n_placed,
                "successes": int(ok.sum()),
                "success_pct": 100.0 * float(ok.sum()) / n_placed if n_placed else float("nan"),
                **wilson_interval_pct(int(ok.sum()), n_placed),
                "mean_steps_success": float(steps[b][ok].mean()) if ok.any() else float("nan"),
                **{f"{name}_count": int((outcome[b] == code).sum()) for code, name in enumerate(OUTCOMES)
                   if code != SUCCESS},
            })
        return rows


def wilson_interval_pct(successes: int, trials: int, confidence: float = 0.95) -> dict[str, float]:
    """95% Wilson score interval of a success rate, in % (scipy's binomtest): ci_lo_pct, ci_hi_pct."""
    if trials == 0:
        return {"ci_lo_pct": float("nan"), "ci_hi_pct": float("nan")}
    ci = stats.binomtest(successes, trials).proportion_ci(confidence_level=confidence, method="wilson")
    return {"ci_lo_pct": 100.0 * ci.low, "ci_hi_pct": 100.0 * ci.high}


def success_rate_trials(env: Env, method: str, config: Config, distances: Sequence[float] = DEFAULT_DISTANCES,
                        trials: int = 100, heading: float | None = None, key: Array | None = None,
                        clearance: float = 10.0, visible: Array | None = None, home_radius: float = 50.0,
                        max_steps: int = 50, lanes: int = DEFAULT_LANES, first_move: str = "homing",
                        collisions: str = "ignore", program: Sequence[str] | None = None) -> SuccessRate:
    """`trials` rollouts per release distance: random direction from home, random heading (docs/model.md §5)."""
    key = jax.random.PRNGKey(0) if key is None else key
    dist = np.asarray(distances, np.float32)
    n_bins = dist.shape[0]
    starts, heads, placed = (np.asarray(a) for a in _release_bins(env.arrays(), key, dist, trials, clearance))
    if heading is not None:
        heads = np.full_like(heads, heading)
    visible = np.asarray(env.valid if visible is None else visible, bool)
    total = n_bins * trials
    res = run_trials(env, starts.reshape(total, 2), heads.reshape(total), np.arange(total, dtype=np.int32),
                     np.zeros(total, np.int32), visible[None, :], key, config, method,
                     home_radius=home_radius, max_steps=max_steps, lanes=lanes, first_move=first_move,
                     collisions=collisions, program=program)
    placed_flat = placed.reshape(total)
    outcome = np.where(placed_flat, np.asarray(res.outcome), EXCLUDED).reshape(n_bins, trials)
    steps = np.where(placed_flat, np.asarray(res.steps), 0).reshape(n_bins, trials)
    return SuccessRate(**{k: jax.device_put(v) for k, v in dict(distances=dist, start=starts, heading=heads, placed=placed,
                                                                outcome=outcome, steps=steps).items()},
                       first_move=first_move, collisions=collisions)


@partial(jax.jit, static_argnames=("trials",))
def _release_bins(env: Env, key: Array, distances: Array, trials: int, clearance: float) -> tuple[Array, Array, Array]:
    """`release_points` for every distance bin b, from fold_in(key_start, b)."""
    _, _, k_start = rollout_keys(key)
    return jax.vmap(lambda b, r: release_points(env, jax.random.fold_in(k_start, b), trials, r, clearance))(
        jnp.arange(distances.shape[0]), distances)


# --- trajectories ------------------------------------------------------------------------

class Trajectories(_Outcomes):
    """Homing paths from chosen release points (Figs 4.11, 5.8).

    start: (T, 2); heading: (T,) rad; path: (T, max_steps + 1, 2), NaN after the end;
    outcome, steps, invalid_steps: (T,).
    """

    start: Array
    heading: Array
    path: Array
    outcome: Array
    steps: Array
    invalid_steps: Array
    first_move: str = eqx.field(static=True, default="homing")
    collisions: str = eqx.field(static=True, default="ignore")


def trajectory_trials(env: Env, method: str, config: Config, starts: Array, headings: Array,
                      key: Array | None = None, visible: Array | None = None, home_radius: float = 50.0,
                      max_steps: int = 50, lanes: int = DEFAULT_LANES, first_move: str = "homing",
                      collisions: str = "ignore", program: Sequence[str] | None = None) -> Trajectories:
    """Rollouts from `starts` (T, 2) with `headings` (T,) rad, recording every position."""
    key = jax.random.PRNGKey(0) if key is None else key
    starts = np.asarray(starts, np.float32)
    headings = np.asarray(headings, np.float32)
    n = starts.shape[0]
    visible = np.asarray(env.valid if visible is None else visible, bool)
    res = run_trials(env, starts, headings, np.arange(n, dtype=np.int32), np.zeros(n, np.int32),
                     visible[None, :], key, config, method, home_radius=home_radius, max_steps=max_steps,
                     lanes=lanes, record_paths=True, first_move=first_move, collisions=collisions, program=program)
    return Trajectories(start=jax.device_put(starts), heading=jax.device_put(headings), path=res.path, outcome=res.outcome, steps=res.steps,
                        invalid_steps=res.invalid_steps, first_move=first_move, collisions=collisions)


# --- public API (validated keywords; mirrors the CLI) ----------------------------------------

def _rollout_options(env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed, config_kw,
                     first_move="homing", collisions="ignore", program=None):
    """Validate the shared keywords before any work (`api.scene_request` plus the rollout limits and rules)."""
    from .api import scene_request
    from .options import positive, positive_int

    check_rules(first_move, collisions)
    check_program(method, program)
    env, config, heading, key, clearance = scene_request(env, method, clearance, heading_deg, seed, **config_kw)
    max_steps = positive_int(max_steps, "max_steps")
    home_radius = positive(home_radius, "home_radius")
    lanes = positive_int(lanes, "lanes")
    return env, config, heading, key, max_steps, home_radius, lanes, clearance


def catchment(env: str | Path | Env, method: str = "delv", spacing: float = 25.0, heading_deg: float | None = None,
              seed: int = 0, occlude: int | None = None, hidden: list[int] | None = None, max_steps: int = 50,
              home_radius: float = 50.0, clearance: float = 10.0, levels: int | None = None, d: float = 50.0,
              background: str = "distant", channel: str = "mask", n_heading: int = 360,
              lanes: int = DEFAULT_LANES, first_move: str = "homing",
              collisions: str = "ignore", program: Sequence[str] | None = None, **options: float) -> Catchment:
    """Catchment area of `method` (Figs 4.5, 5.5; Tables 5.3/5.4): a rollout from every docs/model.md §5 grid point.

    heading_deg fixes the release heading; otherwise it is random per point from `seed`
    (the headings of `vector_map` with the same seed). `occlude=k` evaluates every choice of
    k hidden landmarks (C(N, k) masks, one program; the home record sees all); `hidden`
    names one choice. `options`: noise sigmas as in `vector_map` plus motion_heading_noise_deg
    and motion_step_noise, or any other `make_config` option (e.g. warping's n_alpha).
    `first_move` ("homing" | "release") and `collisions` ("ignore" | "fail"): the rollout
    rules of the module docstring (defaults: docs/model.md §5). `program`: methods compiled into
    one rollout program with this one (`run_trials`). Returns a `Catchment` (see `catchment_summary`).
    """
    from .api import visible_mask
    from .options import occlusion_count, positive

    env, config, heading, key, max_steps, home_radius, lanes, clearance = _rollout_options(
        env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed,
        dict(d=d, levels=levels, background=background, channel=channel, n_heading=n_heading, **options),
        first_move, collisions, program)
    spacing = positive(spacing, "spacing")
    if occlude is not None and hidden:
        raise InputError("occlude", occlude, "cannot be combined with hidden")
    if occlude is not None:
        masks, combos = occlusion_masks(env, occlusion_count(occlude, env.n_landmarks))
    else:
        visible_mask(env, hidden)  # validates the indices
        masks, combos = hidden_masks(env, hidden)
    return catchment_area(env, method, config, spacing=spacing, heading=heading, key=key, clearance=clearance,
                          masks=masks, hidden=combos, home_radius=home_radius, max_steps=max_steps, lanes=lanes,
                          first_move=first_move, collisions=collisions, program=program)


def success_rate(env: str | Path | Env, method: str = "delv", distances: Sequence[float] = DEFAULT_DISTANCES,
                 trials: int = 100, heading_deg: float | None = None, seed: int = 0, hidden: list[int] | None = None,
                 max_steps: int = 50, home_radius: float = 50.0, clearance: float = 10.0,
                 levels: int | None = None, d: float = 50.0, background: str = "distant", channel: str = "mask",
                 n_heading: int = 360, lanes: int = DEFAULT_LANES, first_move: str = "homing",
                 collisions: str = "ignore", program: Sequence[str] | None = None, **options: float) -> SuccessRate:
    """Success rate vs release distance (Figs 4.10b, 5.7b): `trials` rollouts per distance from home.

    Each trial: a random direction from home at that distance and a random heading (seeded);
    a release point inside a landmark's r + clearance or outside the arena is redrawn
    (deterministically, up to 64 times; else the trial is not placed and not counted).
    `options`, `first_move`, `collisions` and `program` as in `catchment`.
    """
    from .api import visible_mask
    from .options import positive, positive_int

    env, config, heading, key, max_steps, home_radius, lanes, clearance = _rollout_options(
        env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed,
        dict(d=d, levels=levels, background=background, channel=channel, n_heading=n_heading, **options),
        first_move, collisions, program)
    trials = positive_int(trials, "trials")
    if isinstance(distances, (str, bytes)) or not hasattr(distances, "__len__") or len(distances) == 0:
        raise InputError("distances", distances, "must be a non-empty list of distances in cm")
    distances = [positive(v, "distances") for v in distances]
    return success_rate_trials(env, method, config, distances=distances, trials=trials, heading=heading, key=key,
                               clearance=clearance, visible=visible_mask(env, hidden), home_radius=home_radius,
                               max_steps=max_steps, lanes=lanes, first_move=first_move, collisions=collisions,
                               program=program)


def trajectories(env: str | Path | Env, method: str = "delv", starts: Sequence[Sequence[float]] | None = None,
                 n_starts: int = 6, heading_deg: float | None = None, seed: int = 0, hidden: list[int] | None = None,
                 max_steps: int = 50, home_radius: float = 50.0, clearance: float = 10.0,
                 levels: int | None = None, d: float = 50.0, background: str = "distant", channel: str = "mask",
                 n_heading: int = 360, lanes: int = DEFAULT_LANES, first_move: str = "homing",
                 collisions: str = "ignore", program: Sequence[str] | None = None,
                 **options: float) -> Trajectories:
    """Homing paths (Figs 4.11, 5.8) from `starts` [(x, y), ...] or `n_starts` seeded random release points.

    Random release points are uniform in the arena, at least d from the walls, farther than
    r + clearance + d from every landmark (so that under first_move="release" the first move,
    along the random release heading, cannot end the trial) and at least 2 * home_radius
    from home; headings are
    random per trial from `seed` unless heading_deg is given. The same seed gives the same
    release points for every method. `options`, `first_move`, `collisions` and `program` as in `catchment`.
    """
    from .api import visible_mask
    from .options import finite, positive_int

    env, config, heading, key, max_steps, home_radius, lanes, clearance = _rollout_options(
        env, method, max_steps, home_radius, lanes, clearance, heading_deg, seed,
        dict(d=d, levels=levels, background=background, channel=channel, n_heading=n_heading, **options),
        first_move, collisions, program)
    visible = visible_mask(env, hidden)
    _, _, k_start = rollout_keys(key)
    if starts is None:
        n = positive_int(n_starts, "n_starts")
        pts, heads, placed = release_points(env.arrays(), k_start, n, None, clearance, 2.0 * home_radius, config.d)
        if not bool(np.all(np.asarray(placed))):
            raise InputError("n_starts", n_starts, "could not place release points clear of landmarks")
    else:
        pts = _check_starts(env, starts, finite)
        _, heads, _ = release_points(env.arrays(), k_start, pts.shape[0], None, clearance)
    if heading is not None:
        heads = jnp.full(pts.shape[0], heading, jnp.float32)
    return trajectory_trials(env, method, config, pts, heads, key=key, visible=visible, home_radius=home_radius,
                             max_steps=max_steps, lanes=lanes, first_move=first_move, collisions=collisions,
                             program=program)


def _check_starts(env: Env, starts, finite) -> Array:
    """Release points given by the user: a non-empty list of (x, y) inside the arena, outside every landmark."""
    if isinstance(starts, (str, bytes)) or not hasattr(starts, "__len__") or len(starts) == 0:
        raise InputError("starts", starts, "must be a non-empty list of (x, y) points")
    rows = []
    for i, s in enumerate(starts):
        if not hasattr(s, "__len__") or len(s) != 2:
            raise InputError(f"starts[{i}]", s, "must be an (x, y) pair")
        rows.append([finite(v, f"starts[{i}]") for v in s])
    pts = np.asarray(rows, np.float32)
    status = np.asarray(jax.vmap(lambda p: position_status(env, p, jnp.float32(0.0)))(jnp.asarray(pts)))
    for i, code in enumerate(status):
        if code in (LANDMARK, ARENA):
            raise InputError(f"starts[{i}]", starts[i], "must lie inside the arena and outside every landmark")
    return jnp.asarray(pts)


__all__ = ["Catchment", "SuccessRate", "Trajectories", "Trials", "catchment", "catchment_area", "catchment_summary",
           "occlusion_masks", "release_points", "run_trials", "success_rate", "success_rate_trials", "trajectories",
           "trajectory_trials", "OUTCOMES"]
