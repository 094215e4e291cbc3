"""Success rate vs release distance (Figs 4.10b, 5.7b; docs/model.md §5)."""

from __future__ import annotations

from collections.abc import Sequence
from functools import partial

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array
from jax.typing import ArrayLike

from ..batching import bucket
from ..deprecation import refuse_unknown
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensor import Sensor
from ..types import Bins, BinTrialFlag, BinTrialFloat, BinTrialInt, BinTrialPoints, Real
from .config import Grid, Rules, legacy_config
from .release import release_points
from .rules import (
    DEFAULT_DISTANCES,
    DEFAULT_FIRST_MOVE,
    EXCLUDED,
    NO_CONTACT,
    OUTCOMES,
    SUCCESS,
    TRIALS_PER_DISTANCE,
    Outcomes,
    outcome_names,
    rollout_keys,
    rule_columns,
)
from .trials import run_trials

RELEASE_BUCKETS = 1024  # trials a distance up to which the release draws run in shape buckets (memory: 9 bins
# of 16384 trials would hold 0.9 GB of candidates at once, against 0.5 GB for 5000)


class SuccessRate(Outcomes):
    """Success rate per release distance (Figs 4.10b, 5.7b).

    distances: (D,) cm; start: (D, n, 2); heading: (D, n) rad; placed: (D, n) a release
    point was found (docs/model.md §5: a start inside a landmark or outside the arena is redrawn);
    outcome, steps: (D, n) (outcome EXCLUDED where not placed); contact: (D, n) the step of the
    trial's first landmark contact, NO_CONTACT if none (`rules.under_collisions`).
    """

    distances: Bins
    start: BinTrialPoints
    heading: BinTrialFloat
    placed: BinTrialFlag
    outcome: BinTrialInt
    steps: BinTrialInt
    contact: BinTrialInt
    first_move: str = eqx.field(static=True, default=DEFAULT_FIRST_MOVE)
    collisions: str = eqx.field(static=True, default="ignore")

    def columns(self, method: str = "") -> dict:
        """Per trial, the success-rate trial CSV's columns (`success_trial_columns`)."""
        return success_trial_columns(self, method)

    def table(self) -> list[dict]:
        """Per-bin rows: distance_cm, trials, placed, successes, success_pct (of placed) with its 95% Wilson
        interval (ci_lo_pct, ci_hi_pct), mean_steps_success, and a count per failure outcome."""
        outcome, steps, placed = (np.asarray(v) for v in (self.outcome, self.steps, self.placed))
        rows = []
        for b, dist in enumerate(np.asarray(self.distances)):  # D <= a dozen bins: post-processing
            ok = outcome[b] == SUCCESS
            n_placed = int(placed[b].sum())
            rows.append(
                {
                    "distance_cm": float(dist),
                    "trials": int(placed.shape[1]),
                    "placed": n_placed,
                    "successes": int(ok.sum()),
                    "success_pct": 100.0 * float(ok.sum()) / n_placed if n_placed else float("nan"),
                    **wilson_interval_pct(int(ok.sum()), n_placed),
                    "mean_steps_success": float(steps[b][ok].mean()) if ok.any() else float("nan"),
                    **{
                        f"{name}_count": int((outcome[b] == code).sum())
                        for code, name in enumerate(OUTCOMES)
                        if code != SUCCESS
                    },
                }
            )
        return rows


def wilson_pct(successes, trials, confidence: float = 0.95) -> tuple[np.ndarray, np.ndarray]:
    """The Wilson score interval of success rates, in %, for counts or arrays of counts: (lo, hi), NaN
    where there are no trials. The one Wilson interval of delvjax (success-rate tables, sweeps, figures).
    Newcombe's (1998) form, written as scipy's `binomtest(k, n).proportion_ci(method="wilson")` computes
    it (the same numbers to the bit, tests/sweeps/test_rollouts.py), vectorised and without importing
    scipy.stats (0.5-1 s)."""
    from scipy.special import ndtri  # scipy.special: loaded where an interval is asked for

    k, n = (a.astype(np.float64) for a in np.broadcast_arrays(np.asarray(successes), np.asarray(trials)))
    if np.any((k < 0) | (k > n)):  # as binomtest: a count is no rate of these trials
        raise ValueError(f"successes must lie in 0..trials, got {successes!r} of {trials!r}")
    with np.errstate(divide="ignore", invalid="ignore"):
        p = k / n
        z = ndtri(0.5 + 0.5 * confidence)
        denom = 2 * (n + z**2)
        center = (2 * n * p + z**2) / denom
        delta = z / denom * np.sqrt(4 * n * p * (1 - p) + z**2)
        lo = np.where(k == 0, 0.0, center - delta)
        hi = np.where(k == n, 1.0, center + delta)
    none = n == 0
    return np.where(none, np.nan, 100.0 * lo), np.where(none, np.nan, 100.0 * hi)


def wilson_interval_pct(successes: int, trials: int, confidence: float = 0.95) -> dict[str, float]:
    """95% Wilson score interval of one success rate, in %: ci_lo_pct, ci_hi_pct (`wilson_pct`)."""
    lo, hi = wilson_pct(successes, trials, confidence)
    return {"ci_lo_pct": float(lo), "ci_hi_pct": float(hi)}


def success_rate_trials(
    env: Env,
    method: HomingMethod,
    sensor: Sensor,
    distances: Sequence[float] = DEFAULT_DISTANCES,
    trials: int = TRIALS_PER_DISTANCE,
    grid: Grid | None = None,
    rules: Rules | None = None,
    *,
    key: Array | None = None,
    visible: ArrayLike | None = None,
    **legacy,
) -> SuccessRate:
    """`trials` rollouts per release distance by `rules`: random direction from home, random heading unless
    `grid` fixes one; release points clear of the landmarks by `Grid.clearance` (docs/model.md §5; the
    grid's spacing is not used). `Grid`: core/grid.py, `Rules`: core/rollouts/config.py, defaults `Grid()`, `Rules()`;
    the flat keywords of earlier releases still work, deprecated (`legacy_config`)."""
    grid, rules = legacy_config(Grid, grid, legacy), legacy_config(Rules, rules, legacy)
    refuse_unknown(legacy, "success_rate_trials")
    heading, clearance = grid.heading, grid.clearance
    key = jax.random.PRNGKey(0) if key is None else key
    dist = np.asarray(distances, np.float32)
    n_bins = dist.shape[0]
    # every trial count of a shape bucket (`batching.bucket`: 1-256, 257-1024) draws its release points in one
    # program; trial t's draw depends only on t, so the first `trials` of the bucket are this call's. Above
    # RELEASE_BUCKETS trials the draw is not padded further: it holds bins x trials x START_TRIES candidates
    drawn = _release_bins(env, key, dist, bucket(trials, max(trials, RELEASE_BUCKETS)), clearance)
    starts, heads, placed = (np.asarray(a)[:, :trials] for a in drawn)
    if heading is not None:
        heads = np.full_like(heads, heading)
    visible = np.asarray(env.valid if visible is None else visible, bool)
    total = n_bins * trials
    res = run_trials(
        env,
        starts.reshape(total, 2),
        heads.reshape(total),
        np.arange(total, dtype=np.int32),
        np.zeros(total, np.int32),
        visible[None, :],
        key,
        sensor,
        method,
        rules,
    )
    placed_flat = placed.reshape(total)
    outcome = np.where(placed_flat, np.asarray(res.outcome), EXCLUDED).reshape(n_bins, trials)
    steps = np.where(placed_flat, np.asarray(res.steps), 0).reshape(n_bins, trials)
    contact = np.where(placed_flat, np.asarray(res.contact), NO_CONTACT).reshape(n_bins, trials)
    return SuccessRate(
        **{
            k: jax.device_put(v)
            for k, v in dict(
                distances=dist,
                start=starts,
                heading=heads,
                placed=placed,
                outcome=outcome,
                steps=steps,
                contact=contact,
            ).items()
        },
        first_move=rules.first_move,
        collisions=rules.collisions,
    )


@partial(jax.jit, static_argnames=("trials",))
def _release_bins(env: Env, key: Array, distances: Array, trials: int, clearance: Real) -> tuple[Array, Array, Array]:
    """`release_points` for every distance bin b, from fold_in(key_start, b)."""
    _, _, k_start = rollout_keys(key)
    return jax.vmap(lambda b, r: release_points(env, jax.random.fold_in(k_start, b), trials, r, clearance))(
        jnp.arange(distances.shape[0]), distances
    )


def success_rows(res: SuccessRate, method: str) -> list[dict]:
    """Per release distance: method, the bin statistics of `SuccessRate.table` and the rules."""
    return [{"method": method, **row, **res.rules} for row in res.table()]


def success_trial_columns(res: SuccessRate, method: str) -> dict[str, object]:
    """Per trial: method, distance_cm, trial, x, y, heading_deg, placed, success, steps, outcome, the rules."""
    placed = np.asarray(res.placed).reshape(-1)
    start = np.asarray(res.start).reshape(-1, 2)
    n_bins, n_tr = np.asarray(res.placed).shape
    return {
        "method": [method] * placed.size,
        "distance_cm": np.repeat(np.asarray(res.distances), n_tr),
        "trial": np.tile(np.arange(n_tr), n_bins),
        "x": start[:, 0],
        "y": start[:, 1],
        "heading_deg": np.degrees(np.asarray(res.heading).reshape(-1)),
        "placed": placed,
        "success": np.asarray(res.success).reshape(-1),
        "steps": np.asarray(res.steps).reshape(-1),
        "outcome": outcome_names(res.outcome),
        **rule_columns(res.rules, placed.size),
    }
