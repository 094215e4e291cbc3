"""The lane scheduler: a block of trials in one `lax.while_loop` (docs/reproduce.md, docs/model.md §5).

`lanes` trials advance side by side (vmap over `Rollout.advance`); a lane whose trial ends is
refilled with the next pending trial (one `tree.map` over the `Lanes` state), so a block costs
about sum(steps + 1) / lanes iterations instead of max_steps per chunk. A lane first spends one
iteration at its release point computing the vector map's direction there, then one move per
iteration, so the method appears once in the program.

Every lane also records its trial's first landmark contact (the first position, release point or
move end, inside a landmark while the trial runs): its step, position and invalid-move count. Up to
that contact a trial is the same under either `collisions` rule, so a run under "ignore" also gives
the run under "fail" (`rules.under_collisions`; docs/model.md §5).
"""

from __future__ import annotations

from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..batching import fixed_width_map, item_width, padded
from .rules import LANDMARK, NO_CONTACT, RUNNING, position_status
from .step import Rollout


class Lanes(eqx.Module):
    """State of the lanes: trial index t (n_trials when idle), position, heading, status, whether
    the next iteration is the trial's first (at its release point), moves made, invalid moves, and
    the first landmark contact: its step (NO_CONTACT: none yet), position and invalid moves before it."""

    t: Array
    pos: Array
    heading: Array
    status: Array
    first: Array
    step: Array
    invalid: Array
    contact: Array
    contact_end: Array
    contact_invalid: Array


def _where(cond: Array, new, old):
    """`new` on the lanes where `cond`, else `old`, leaf by leaf."""
    return jax.tree.map(lambda a, b: jnp.where(cond.reshape(cond.shape + (1,) * (a.ndim - 1)), a, b), new, old)


class Results(eqx.Module):
    """Per-trial results of one block: outcome, steps, invalid moves, end point, first direction, its validity,
    path, and the first landmark contact (step, NO_CONTACT if none; position; invalid moves before it)."""

    outcome: Array
    steps: Array
    invalid: Array
    end: Array
    first_dir: Array
    first_valid: Array
    path: Array
    contact: Array
    contact_end: Array
    contact_invalid: Array


@partial(jax.jit, static_argnames=("lanes", "path_length"))
def run_block(
    rollout: Rollout,
    starts: Array,
    headings: Array,
    n_valid: Array,
    lanes: int,
    path_length: int = 1,
) -> Results:
    """Run the first `n_valid` trials of a block (the padding is never run). With `path_length` > 1 the
    paths are recorded into (T, path_length, 2) (path_length >= rollout.max_steps + 1; positions past a
    trial's end stay NaN); with 1 `path` holds the starts (T, 1, 2), so memory does not grow with max_steps.
    `rollout.max_steps` is traced: rollouts of every max_steps share the program of their path length."""
    n_trials = starts.shape[0]
    n_lanes = max(1, min(lanes, n_trials))
    width = item_width(rollout.method.reads_panorama())  # lanes per vectorised step (core/batching.py)
    n_slots = padded(n_lanes, width)  # slots past n_lanes stay idle (core/batching.py: fixed width)

    def fresh(t):
        """A lane starting trial t (t >= n_valid: idle)."""
        ok = t < n_valid
        ts = jnp.minimum(t, n_trials - 1)
        status = jnp.where(ok, position_status(rollout.env, starts[ts], rollout.radius, rollout.collide), RUNNING)
        touching = ok & (position_status(rollout.env, starts[ts], rollout.radius, True) == LANDMARK)
        zero = jnp.zeros((), jnp.int32)
        return Lanes(
            t=t,
            pos=starts[ts],
            heading=headings[ts],
            status=status,
            first=jnp.ones((), bool),
            step=zero,
            invalid=zero,
            contact=jnp.where(touching, zero, NO_CONTACT),
            contact_end=starts[ts],
            contact_invalid=zero,
        )

    lane_t = jnp.arange(n_slots, dtype=jnp.int32)
    lanes0 = jax.vmap(fresh)(jnp.where((lane_t < n_valid) & (lane_t < n_lanes), lane_t, n_trials))
    zeros_t = jnp.zeros(n_trials, jnp.int32)
    out0 = Results(
        outcome=jnp.full(n_trials, RUNNING, jnp.int32),
        steps=zeros_t,
        invalid=zeros_t,
        end=jnp.zeros((n_trials, 2), jnp.float32),
        first_dir=jnp.full(n_trials, jnp.nan, jnp.float32),
        first_valid=jnp.zeros(n_trials, bool),
        path=jnp.full((n_trials, path_length, 2), jnp.nan, jnp.float32).at[:, 0].set(starts),
        contact=jnp.full(n_trials, NO_CONTACT, jnp.int32),
        contact_end=jnp.zeros((n_trials, 2), jnp.float32),
        contact_invalid=zeros_t,
    )

    def cond(state):
        return jnp.any(state[0].t < n_valid)

    def body(state):
        lane, out, next_t = state
        # 1. every active lane: its first direction (at the release point) or one move
        active = lane.t < n_valid
        first = active & lane.first
        moving = active & ~lane.first & (lane.status == RUNNING)
        ts = jnp.minimum(lane.t, n_trials - 1)
        end, new_heading, status, valid, direction = fixed_width_map(
            rollout.advance, (ts, lane.pos, lane.heading, lane.step, lane.first), active, width
        )
        idx0 = jnp.where(first, lane.t, n_trials)
        out = eqx.tree_at(
            lambda o: (o.first_dir, o.first_valid),
            out,
            (out.first_dir.at[idx0].set(direction, mode="drop"), out.first_valid.at[idx0].set(valid, mode="drop")),
        )
        # the first move of a running trial that ends inside a landmark (under "fail" its last move)
        touching = moving & (lane.contact == NO_CONTACT)
        touching = touching & (jax.vmap(position_status, (None, 0, None))(rollout.env, end, rollout.radius) == LANDMARK)
        lane = Lanes(
            t=lane.t,
            pos=jnp.where(moving[:, None], end, lane.pos),
            heading=jnp.where(moving | first, new_heading, lane.heading),
            status=jnp.where(moving, status, lane.status),
            first=lane.first & ~active,
            step=lane.step + moving.astype(jnp.int32),
            invalid=lane.invalid + (moving & ~valid & (status == RUNNING)).astype(jnp.int32),
            contact=jnp.where(touching, lane.step + 1, lane.contact),
            contact_end=jnp.where(touching[:, None], end, lane.contact_end),
            contact_invalid=jnp.where(touching, lane.invalid, lane.contact_invalid),
        )
        path = (
            out.path.at[jnp.where(moving, lane.t, n_trials), lane.step].set(lane.pos, mode="drop")
            if path_length > 1
            else out.path
        )
        # 2. write the lanes whose trial has ended (after its first direction)
        done = active & ~lane.first & (lane.status != RUNNING)
        idx = jnp.where(done, lane.t, n_trials)
        out = Results(
            outcome=out.outcome.at[idx].set(lane.status, mode="drop"),
            steps=out.steps.at[idx].set(lane.step, mode="drop"),
            invalid=out.invalid.at[idx].set(lane.invalid, mode="drop"),
            end=out.end.at[idx].set(lane.pos, mode="drop"),
            first_dir=out.first_dir,
            first_valid=out.first_valid,
            path=path,
            contact=out.contact.at[idx].set(lane.contact, mode="drop"),
            contact_end=out.contact_end.at[idx].set(lane.contact_end, mode="drop"),
            contact_invalid=out.contact_invalid.at[idx].set(lane.contact_invalid, mode="drop"),
        )
        # 3. refill them from the queue
        new_t = next_t + jnp.cumsum(done) - 1
        new_t = jnp.where(new_t >= n_valid, n_trials, new_t).astype(jnp.int32)
        lane = _where(done, jax.vmap(fresh)(jnp.where(done, new_t, lane.t)), lane)
        return lane, out, next_t + jnp.sum(done).astype(jnp.int32)

    _, out, _ = jax.lax.while_loop(cond, body, (lanes0, out0, jnp.minimum(jnp.int32(n_lanes), n_valid)))
    return out
