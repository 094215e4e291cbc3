"""Homing paths from chosen release points (Figs 4.11, 5.8; docs/model.md §5)."""

from __future__ import annotations

import equinox as eqx
import jax
import numpy as np
from jax import Array

from ..deprecation import refuse_unknown
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensor import Sensor
from ..types import Paths, PerTrial, PerTrialInt, TrialPoints
from .config import Rules, legacy_config
from .rules import DEFAULT_FIRST_MOVE, Outcomes, outcome_names, rule_columns
from .trials import run_trials


class Trajectories(Outcomes):
    """Homing paths from chosen release points (Figs 4.11, 5.8).

    start: (T, 2); heading: (T,) rad; path: (T, max_steps + 1, 2), NaN after the end;
    outcome, steps, invalid_steps: (T,); contact, contact_invalid: (T,) the step of the first landmark
    contact (NO_CONTACT: none) and the invalid moves before it (`rules.under_collisions`).
    """

    start: TrialPoints
    heading: PerTrial
    path: Paths
    outcome: PerTrialInt
    steps: PerTrialInt
    invalid_steps: PerTrialInt
    contact: PerTrialInt
    contact_invalid: PerTrialInt
    first_move: str = eqx.field(static=True, default=DEFAULT_FIRST_MOVE)
    collisions: str = eqx.field(static=True, default="ignore")

    def columns(self, method: str = "") -> dict:
        """Per visited position, the trajectory CSV's columns (`trajectory_columns`)."""
        return trajectory_columns(self, method)


def trajectory_trials(
    env: Env,
    method: HomingMethod,
    sensor: Sensor,
    starts: Array,
    headings: Array,
    rules: Rules | None = None,
    *,
    key: Array | None = None,
    visible: Array | None = None,
    **legacy,
) -> Trajectories:
    """Rollouts from `starts` (T, 2) with `headings` (T,) rad by `rules` (a `Rules`, core/rollouts/config.py;
    default `Rules()`), recording every position. The flat keywords of earlier releases still work,
    deprecated (`legacy_config`)."""
    rules = legacy_config(Rules, rules, legacy)
    refuse_unknown(legacy, "trajectory_trials")
    key = jax.random.PRNGKey(0) if key is None else key
    starts = np.asarray(starts, np.float32)
    headings = np.asarray(headings, np.float32)
    n = starts.shape[0]
    visible = np.asarray(env.valid if visible is None else visible, bool)
    res = run_trials(
        env,
        starts,
        headings,
        np.arange(n, dtype=np.int32),
        np.zeros(n, np.int32),
        visible[None, :],
        key,
        sensor,
        method,
        rules,
        record_paths=True,
    )
    return Trajectories(
        start=jax.device_put(starts),
        heading=jax.device_put(headings),
        path=res.path,
        outcome=res.outcome,
        steps=res.steps,
        invalid_steps=res.invalid_steps,
        contact=res.contact,
        contact_invalid=res.contact_invalid,
        first_move=rules.first_move,
        collisions=rules.collisions,
    )


def trajectory_columns(tr: Trajectories, method: str) -> dict[str, list]:
    """Per visited position: method, trial, step, x, y, release_heading_deg, success, steps, outcome, the rules."""
    path, steps = np.asarray(tr.path), np.asarray(tr.steps)
    heading, success, outcome = np.degrees(np.asarray(tr.heading)), np.asarray(tr.success), outcome_names(tr.outcome)
    t = np.repeat(np.arange(path.shape[0]), steps + 1)
    s = np.concatenate([np.arange(n + 1) for n in steps]) if steps.size else np.zeros(0, int)
    return {
        "method": [method] * t.size,
        "trial": t.tolist(),
        "step": s.tolist(),
        "x": path[t, s, 0].tolist(),
        "y": path[t, s, 1].tolist(),
        "release_heading_deg": heading[t].tolist(),
        "success": success[t].tolist(),
        "steps": steps[t].tolist(),
        "outcome": [outcome[i] for i in t],
        **rule_columns(tr.rules, t.size),
    }
