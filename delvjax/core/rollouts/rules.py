"""Rollout rules and outcomes (thesis §4.3, §5.3.1; docs/model.md §5).

A rollout: released at a point with a heading, the agent computes the homing direction,
turns to it and moves `d`; it senses the move just made as its unit movement, asks the
method for a direction at the new point, turns to it, and so on. It succeeds when within
`home_radius` of home at the release point or after a move, within `max_steps` moves; a move
ending outside the arena ends it as a failure; an invalid direction keeps the heading.
Two rules, both recorded in every summary and table:
  * first_move = "release" (default; thesis Algorithm 2, lines 3-7): a method that needs a unit
    movement (DELV and its variants) takes a snapshot, moves d along the release heading and
    only then matches; a method that reads only the current view (ALV, ACV, image matching,
    MFDID) turns to the direction it computes at the release point. "homing" (the earlier
    default): every method turns to the direction computed at the release point exactly as in
    the vector map (a unit move ending there).
  * collisions = "ignore" (default): landmarks are no obstacles; "fail": a move ending
    inside a landmark (distance to its centre < r) ends the trial as a failure.
A run under "ignore" records each trial's first landmark contact; up to it the trial is the same
under "fail", which ends it there, so `under_collisions` restates such a run under "fail" without
running it again. Under "release" the blind first move from a grid point closer than d to a wall
can leave the arena whatever the method, so the catchment counts only grid points at least d from
every wall (`catchment_counted`; docs/model.md §5); the vector map keeps the whole grid.
"""

from __future__ import annotations

import dataclasses

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..errors import InputError
from ..frames import frame
from ..maps import stream_keys
from ..scene import Env

# Trial outcome codes (a running trial is RUNNING; a grid cell never released is EXCLUDED).
OUTCOMES = ("success", "timeout", "landmark", "arena")
SUCCESS, TIMEOUT, LANDMARK, ARENA = range(4)
RUNNING, EXCLUDED = -1, -2
NO_CONTACT = -1  # a trial's first landmark contact: none (`under_collisions`)
NEAR_WALL = -3  # a catchment trial that ran but does not count: its grid point is closer than d to a wall
FIRST_MOVES = ("release", "homing")
COLLISIONS = ("ignore", "fail")
DEFAULT_FIRST_MOVE = "release"
DEFAULT_RULES = {"first_move": DEFAULT_FIRST_MOVE, "collisions": "ignore"}
HOMING_RULES = {"first_move": "homing", "collisions": "ignore"}  # the earlier default, reported beside it
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


def check_rules(first_move: str, collisions: str | None) -> dict[str, str]:
    """Validated rollout rules (module docstring) as the dict recorded in summaries."""
    if first_move not in FIRST_MOVES:
        raise InputError("first_move", first_move, f"must be one of {', '.join(FIRST_MOVES)}")
    if collisions not in COLLISIONS:
        raise InputError("collisions", collisions, f"must be one of {', '.join(COLLISIONS)}")
    return rules_record(first_move, collisions)


def rules_record(first_move: str, collisions: str) -> dict[str, str]:
    """The two rules every summary and table records: {"first_move": ..., "collisions": ...}."""
    return {"first_move": first_move, "collisions": collisions}


def wall_margin(first_move: str, d) -> float:
    """How far from every wall a grid point must be for its catchment trial to count: d under
    "release" (the blind first move must stay in the arena), 0 under "homing"."""
    return float(np.max(np.asarray(d))) if first_move == "release" else 0.0


def catchment_counted(arena, points, included, first_move: str, d) -> np.ndarray:
    """Grid points whose rollout counts in the catchment (docs/model.md §5): `included` and at
    least `wall_margin` from every wall; (P,) bool, NumPy (input preparation)."""
    a, pts, m = np.asarray(arena, np.float64), np.asarray(points, np.float64), wall_margin(first_move, d)
    clear = (
        (pts[:, 0] >= a[0] + m - 1e-3)
        & (pts[:, 0] <= a[2] - m + 1e-3)
        & (pts[:, 1] >= a[1] + m - 1e-3)
        & (pts[:, 1] <= a[3] - m + 1e-3)
    )
    return np.asarray(included, bool) & clear


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
        return rules_record(self.first_move, self.collisions)  # type: ignore[attr-defined]

    def columns(self, method: str = "") -> dict:
        """The columns of the result's CSV file (docs/model.md §7); `method` fills the method column."""
        raise NotImplementedError

    def to_dataframe(self, method: str = ""):
        """The result as a pandas DataFrame with the columns of its CSV file (`columns`); `method`
        fills the method column where there is one."""
        return frame(self.columns(method))


OUTCOME_NAMES = {**dict(enumerate(OUTCOMES)), EXCLUDED: "not_placed", RUNNING: "running", NEAR_WALL: "near_wall"}


def outcome_names(codes) -> list[str]:
    """Outcome codes as names: success, timeout, landmark, arena; not_placed (a release point that
    could not be placed); running (never in a finished result)."""
    return [OUTCOME_NAMES[int(c)] for c in np.asarray(codes).reshape(-1).tolist()]


def rule_columns(rules: dict[str, str], n: int) -> dict[str, list[str]]:
    """The rollout rules as constant columns."""
    return {name: [value] * n for name, value in rules.items()}


def under_collisions(result: Outcomes) -> Outcomes:
    """A rollout result under collisions "ignore" restated under "fail" (docs/model.md §5): a trial is
    the same under both rules up to its first landmark contact (recorded in `contact`, the step;
    `contact_end`, `contact_invalid` where the result has `end`, `invalid_steps`), where "fail" ends
    it as LANDMARK, its path (if kept) NaN after it; trials without contact keep their outcome. A
    cell that does not count (NEAR_WALL) or was not released (EXCLUDED) keeps that code; its steps,
    end and invalid moves are restated like the others. Equal, bit for bit, to running the rule
    "fail" (tests/core/rollouts/test_restated_rules.py)."""
    if result.collisions != "ignore":  # type: ignore[attr-defined]
        raise InputError("collisions", result.collisions, 'must be "ignore" (the run to restate)')  # type: ignore[attr-defined]
    contact = np.asarray(result.contact)  # type: ignore[attr-defined]
    touched = contact != NO_CONTACT
    outcome = np.asarray(result.outcome)  # type: ignore[attr-defined]
    ran = (outcome != NEAR_WALL) & (outcome != EXCLUDED)
    changes = {
        "outcome": np.where(touched & ran, LANDMARK, outcome).astype(outcome.dtype),
        "steps": np.where(touched, contact, np.asarray(result.steps)).astype(np.asarray(result.steps).dtype),  # type: ignore[attr-defined]
    }
    if hasattr(result, "end"):
        end = np.asarray(result.end)
        changes["end"] = np.where(touched[..., None], np.asarray(result.contact_end), end).astype(end.dtype)  # type: ignore[attr-defined]
    if hasattr(result, "invalid_steps"):
        inv = np.asarray(result.invalid_steps)
        changes["invalid_steps"] = np.where(touched, np.asarray(result.contact_invalid), inv).astype(inv.dtype)  # type: ignore[attr-defined]
    path = getattr(result, "path", None)
    if path is not None:  # positions after the contact: none under "fail" (NaN, as after any end)
        path = np.asarray(path)
        after = touched[..., None] & (np.arange(path.shape[-2]) > contact[..., None])
        changes["path"] = np.where(after[..., None], np.nan, path).astype(path.dtype)
    return dataclasses.replace(result, **{k: jax.device_put(v) for k, v in changes.items()}, collisions="fail")
