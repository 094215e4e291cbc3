"""Rollout rules and outcomes (thesis §4.3, §5.3.1; docs/model.md §5).

A rollout: released at a point with a heading, the agent computes the homing direction,
turns to it and moves `d`; it senses the move just made as its unit movement, asks the
method for a direction at the new point, turns to it, and so on. It succeeds when within
`home_radius` of home at the release point or after a move, within `max_steps` moves; a move
ending outside the arena ends it as a failure; an invalid direction keeps the heading.
Two rules, both recorded in every summary and table:
  * first_move = "homing" (default): at the release point the direction is computed exactly
    as in the vector map; "release": the first move goes along the release heading.
  * collisions = "ignore" (default): landmarks are no obstacles; "fail": a move ending
    inside a landmark (distance to its centre < r) ends the trial as a failure.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..errors import InputError
from ..maps import stream_keys
from ..scene import Env

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
HOME_RADIUS = 50.0  # cm, docs/model.md §5
MAX_STEPS = 50
DEFAULT_LANES = 256
DEFAULT_DISTANCES = tuple(float(v) for v in range(50, 451, 50))
TRIALS_PER_DISTANCE = 100  # success rate, thesis §4.3
N_STARTS = 6  # random release points of a trajectory figure


def check_rules(first_move: str, collisions: str) -> dict[str, str]:
    """Validated rollout rules (module docstring) as the dict recorded in summaries."""
    if first_move not in FIRST_MOVES:
        raise InputError("first_move", first_move, f"must be one of {', '.join(FIRST_MOVES)}")
    if collisions not in COLLISIONS:
        raise InputError("collisions", collisions, f"must be one of {', '.join(COLLISIONS)}")
    return {"first_move": first_move, "collisions": collisions}


def rollout_keys(key: Array) -> tuple[Array, Array, Array]:
    """(home record, rollout steps, release points) keys of one seed.

    The home record and per-point headings use the same streams as `maps.vector_map`, so a
    catchment map and the vector map of the same seed share the home record and headings.
    """
    k_home, _, _ = stream_keys(key)
    return k_home, jax.random.fold_in(key, 3), jax.random.fold_in(key, 4)


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


class Outcomes(eqx.Module):
    """Base of the rollout results: an `outcome` field (codes into OUTCOMES) and the rules."""

    @property
    def success(self) -> np.ndarray:
        """True where the trial reached home."""
        return np.asarray(self.outcome) == SUCCESS  # type: ignore[attr-defined]

    @property
    def rules(self) -> dict[str, str]:
        """The rollout rules used (module docstring): {"first_move": ..., "collisions": ...}."""
        return {"first_move": self.first_move, "collisions": self.collisions}  # type: ignore[attr-defined]
