"""Seeded release points of rollouts (docs/model.md §5): uniform in the arena or at a distance from home."""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import TWO_PI, unit
from ..maps import CLEARANCE
from ..scene import Env, clear_of_landmarks
from ..types import Real

START_TRIES = 64  # candidate release points per trial before a trial counts as not placed


@partial(jax.jit, static_argnames=("n", "tries"))
def release_points(
    env: Env,
    key: Array,
    n: int,
    distance: Array | None = None,
    clearance: Real = CLEARANCE,
    min_home_distance: Real = 0.0,
    margin: Real = 0.0,
    tries: int = START_TRIES,
) -> tuple[Array, Array, Array]:
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
            pos = lo + (hi - lo) * jax.random.uniform(k_x, (2,), dtype=jnp.float32)
        else:
            pos = env.home + distance * unit(jax.random.uniform(k_phi, (), maxval=TWO_PI, dtype=jnp.float32))
        return pos, jax.random.uniform(k_head, (), maxval=TWO_PI, dtype=jnp.float32)

    def one(t):
        keys = jax.vmap(partial(jax.random.fold_in, jax.random.fold_in(key, t)))(jnp.arange(tries))
        pos, head = jax.vmap(candidate)(keys)
        ok = clear_of_landmarks(env, pos, clearance, margin)
        ok = ok & (jnp.sqrt(jnp.sum((pos - env.home) ** 2, axis=-1)) >= min_home_distance)
        first = jnp.argmax(ok)
        return pos[first], head[first], ok[first]

    return jax.vmap(one)(jnp.arange(n))
