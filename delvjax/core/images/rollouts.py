"""Nearest-snapshot rollouts on an image database (docs/images.md §7), as navipy and BoB do.

The agent at x takes the snapshot of the nearest database point, moves one step along the homing
direction the method computes there (the database vector map's direction at that point), with
N(0, motion_heading) heading and step * (1 + N(0, motion_step)) length errors, and repeats. A
trial succeeds within `home_radius` of home, fails outside the arena or inside an obstacle
(cylinders and boxes of the database's world, when it has one), at an invalid direction
("undefined": no neighbour, no match) or after `max_steps` (timeout). Outcome codes are those
of docs/model.md §5 plus UNDEFINED.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..batching import fixed_width_map
from ..geometry import unit
from ..rollouts.rules import ARENA, HOME_TOLERANCE, LANDMARK, RUNNING, SUCCESS, TIMEOUT
from ..rollouts.rules import OUTCOMES as RULE_OUTCOMES

UNDEFINED = 4
OUTCOMES = (*RULE_OUTCOMES, "undefined")  # the rollout outcomes, and no direction at a snapshot


class Field(eqx.Module):
    """What a rollout reads: positions (N, 2) of the database, direction (N,) rad, valid (N,), home
    (2,), arena (4,), cylinders (C, 3) [x, y, r] and boxes (K, 4) obstacles (zero rows: none)."""

    positions: Array
    direction: Array
    valid: Array
    home: Array
    arena: Array
    cylinders: Array
    boxes: Array


class Paths(eqx.Module):
    """outcome: (T,) codes into OUTCOMES; steps: (T,) moves made; path: (T, max_steps + 1, 2) cm,
    the last position repeated after the trial ends."""

    outcome: Array
    steps: Array
    path: Array


def status(field: Field, x: Array, home_radius: Array) -> Array:
    """SUCCESS, ARENA, LANDMARK or RUNNING at position x."""
    a = field.arena
    outside = (x[0] < a[0]) | (x[0] > a[2]) | (x[1] < a[1]) | (x[1] > a[3])
    c = field.cylinders
    in_cyl = jnp.any(jnp.sum((x - c[:, :2]) ** 2, -1) < c[:, 2] ** 2)
    b = field.boxes
    in_box = jnp.any((x[0] > b[:, 0]) & (x[0] < b[:, 2]) & (x[1] > b[:, 1]) & (x[1] < b[:, 3]))
    home = jnp.sqrt(jnp.sum((x - field.home) ** 2)) <= home_radius + HOME_TOLERANCE
    return jnp.where(in_cyl | in_box, LANDMARK, jnp.where(outside, ARENA, jnp.where(home, SUCCESS, RUNNING)))


def one_trial(
    field: Field, start: Array, key: Array, step: Array, home_radius: Array, noise: Array, max_steps: int
) -> tuple[Array, Array, Array]:
    """(outcome, steps, path (max_steps + 1, 2)) of one rollout from `start`; noise = (motion_heading rad,
    motion_step); the draws of move t come from fold_in(key, t)."""

    def body(carry, t):
        x, code, steps = carry
        nearest = jnp.argmin(jnp.sum((field.positions - x) ** 2, -1))
        ok = field.valid[nearest]
        z = jax.random.normal(jax.random.fold_in(key, t), (2,), dtype=jnp.float32)
        heading = jnp.where(ok, field.direction[nearest], 0.0) + noise[0] * z[0]
        moved = x + step * (1.0 + noise[1] * z[1]) * unit(heading)
        running = code == RUNNING
        new_code = jnp.where(ok, status(field, moved, home_radius), UNDEFINED)
        x = jnp.where(running & ok, moved, x)
        code = jnp.where(running, new_code, code)
        return (x, code, steps + (running & ok)), x

    code0 = status(field, start, home_radius)
    (x, code, steps), path = jax.lax.scan(body, (start, code0, jnp.int32(0)), jnp.arange(max_steps))
    return jnp.where(code == RUNNING, TIMEOUT, code), steps, jnp.concatenate([start[None], path])


@eqx.filter_jit
def nearest_snapshot_rollouts(
    field: Field, starts: Array, key: Array, step: Array, home_radius: Array, noise: Array, max_steps: int
) -> Paths:
    """Rollouts from every start (T, 2), `batching.WIDTH` at a time; trial i draws from fold_in(key, i)."""
    keys = jax.vmap(lambda i: jax.random.fold_in(key, i))(jnp.arange(starts.shape[0]))
    run = lambda s, k: one_trial(field, s, k, step, home_radius, noise, max_steps)  # noqa: E731
    outcome, steps, path = fixed_width_map(run, (starts, keys))
    return Paths(outcome=outcome, steps=steps, path=path)
