"""Landmark layouts designed for homing (docs/differentiable.md "Layout design").

`optimise_layout` moves the landmarks (radii fixed) to minimise the soft homing loss of a
method smoothed at a stated scale (docs/differentiable.md "Sensitivity at a stated scale": BFGS
assumes a smooth objective, and the soft loss at the point is rough at the centimetre scale),
averaged over every choice of `occlude` hidden landmarks, with optimistix's BFGS:

  * positions are x = lo + (hi - lo) sigmoid(u): every landmark stays inside the arena, r + WALL_CM
    from the walls, whatever u;
  * a quadratic penalty PENALTY (cm^-2) keeps each landmark r + HOME_GAP_CM from home and pairs
    r_i + r_j + GAP_CM apart, so that the result is a valid environment (docs/model.md §7);
  * the loop is optimistix's own (init / step / terminate) written out, so each step reports progress.

The layouts are then compared by the ordinary (hard) evaluation over several seeds: hard loss,
catchment and error point rates, and whether each change exceeds the seed-to-seed spread.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import occlusion_count, positive_int, seed_value
from ..core.deprecation import deprecated, keywords_after
from ..core.errors import InputError
from ..core.maps import SPACING
from ..core.rollouts import Catchment, Grid, catchment_summary, occlusion_masks
from ..core.scene import Env
from ..envs._presets import load_env, make_env, random_env
from ..evaluate._progress import Progress, with_callbacks
from ..evaluate._rollouts import catchment
from ._loss import TAU, LossProblem, homing_loss, loss_problem
from ._smoothing import SAMPLES, SMOOTHING_CM, Smoothing, check_smoothing, smoothed_loss, smoothing_draws

WALL_CM = 10.0
HOME_GAP_CM = 40.0
GAP_CM = 20.0
PENALTY = 1e-3  # per cm^2 of violation
OPT_SPACING = 50.0  # grid of the objective (the hard comparison uses the caller's spacing)
STEPS = 60
SEEDS = 3  # evaluation seeds of the hard comparison (the improvement is judged against their spread)


@dataclass
class LayoutResult:
    """The start and optimised environments, the smoothed objective along the way, the hard comparison
    rows (catchment, error rates and hard loss of both layouts, means over the evaluation seeds),
    the rows of each seed, the verdict on the improvement against the seed-to-seed spread, and the
    two catchments of the first seed."""

    start: Env
    optimised: Env
    objective: list[float]
    rows: list[dict]
    seconds: float
    method: str
    occlude: int
    catchments: tuple[Catchment, Catchment]
    per_seed: list[dict]
    verdict: dict


def _bounds(env: Env) -> tuple[np.ndarray, np.ndarray]:
    """Per landmark, the box its centre may occupy: (lo (N, 2), hi (N, 2))."""
    arena = np.asarray(env.arena, np.float64)
    r = np.asarray(env.landmarks, np.float64)[np.asarray(env.valid), 2][:, None]
    return arena[:2] + r + WALL_CM, arena[2:] - r - WALL_CM


def _objective(u, args):
    problem, masks, lo, hi, n, sigmas, eps = args
    lm = problem.env.landmarks
    pos = lo + (hi - lo) * jax.nn.sigmoid(u)
    params = dict(problem.params, landmarks=problem.params["landmarks"].at[:n, :2].set(pos))
    loss = jnp.mean(jax.vmap(lambda vis: smoothed_loss(params, problem, sigmas, eps, vis))(masks))
    r = lm[:n, 2]
    home = jnp.linalg.norm(pos - problem.env.home, axis=-1)
    diff = pos[:, None] - pos[None]
    gap = jnp.sqrt(jnp.sum(diff * diff, axis=-1) + jnp.eye(n) * 1e12)  # the diagonal: far, and no NaN gradient at 0
    penalty = jnp.sum(jax.nn.relu(r + HOME_GAP_CM - home) ** 2) + 0.5 * jnp.sum(
        jax.nn.relu(r[:, None] + r[None] + GAP_CM - gap) ** 2
    )
    return loss + PENALTY * penalty


def solver() -> eqx.Module:
    """optimistix's BFGS, built where a step is traced (equal settings: an equal solver)."""
    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    return optx.BFGS(rtol=1e-5, atol=1e-6)


F_STRUCT = jax.ShapeDtypeStruct((), jnp.float32)


def _fn(u, args):
    """The objective as optimistix's solvers take it: (value, aux)."""
    return _objective(u, args), None


# module-level programs: every layout of one shape reuses them (a lambda per call would recompile)
_init = eqx.filter_jit(lambda u, a: solver().init(_fn, u, a, {}, F_STRUCT, None, frozenset()))
_step = eqx.filter_jit(lambda u, s, a: solver().step(_fn, u, a, {}, s, frozenset()))
_done = eqx.filter_jit(lambda u, s, a: solver().terminate(_fn, u, a, {}, s, frozenset())[0])
_value = eqx.filter_jit(_objective)


def _minimise(
    args, u0, steps: int, report: Progress, old: Callable[[int, int, float], None] | None = None
) -> tuple[jax.Array, list[float]]:
    """optimistix BFGS, stepped by hand: (u, objective after each step). A step returns the last
    accepted point (the line search rejects a worse one), so the last u is the best. Each step reports
    `report(1, steps)` and its objective as the phase ("soft loss 0.1234"); `old`: the per-step callback
    f(step, steps, objective) of earlier releases."""
    state = _init(u0, args)
    u, history = u0, [float(_value(u0, args))]
    for i in range(steps):  # one optimisation step per iteration: a progress report between them
        if i > 0 and bool(_done(u, state, args)):
            break
        u, state, _ = _step(u, state, args)
        if i > 0:  # the first step only evaluates its trial point
            history.append(float(state.f_info.f))
        report.phase(f"soft loss {history[-1]:.4g}")
        report(1, steps)
        if old is not None:
            old(i + 1, steps, history[-1])
    return u, history


def start_layout(env: str | Path | Env | None = None, landmarks: int | None = None, seed: int = 0) -> Env:
    """The starting environment: a preset or file, or `landmarks` seeded random cylinders (`random_env`)."""
    if (env is None) == (landmarks is None):
        raise InputError("env", env, "give an environment or --landmarks N (not both)")
    if env is not None:
        return load_env(env)
    n = positive_int(landmarks, "landmarks")
    if n > 12:
        raise InputError("landmarks", n, "must be in 1..12")
    return random_env(seed_value(seed), n)


def _layout_progress(progress, options: dict) -> tuple[Progress, Callable[[int, int, float], None] | None]:
    """(the `Progress` the steps report to, the per-step callback f(step, steps, objective) of earlier
    releases, deprecated); `announce=` of earlier releases is popped from `options` (`with_callbacks`)."""
    old = None
    if progress is not None and not isinstance(progress, Progress):
        deprecated(
            "delvjax: optimise_layout(progress=f) with f(step, steps, objective) is deprecated and will be removed "
            "in the next release: pass a delvjax.evaluate.Progress (start(steps), (1, steps) per step, the "
            "objective as its phase; every step's objective is in the result's .objective)"
        )
        old, progress = progress, None
    return with_callbacks(progress, options, "optimise_layout"), old


@keywords_after(2, ("occlude", "spacing", "seed", "tau", "steps", "progress", "announce"))
def optimise_layout(
    env: str | Path | Env,
    method: str = "delv",
    *,
    occlude: int = 0,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    steps: int = STEPS,
    smoothing_cm: float | None = SMOOTHING_CM,
    samples: int = SAMPLES,
    seeds: int = SEEDS,
    progress: Progress | Callable[[int, int, float], None] | None = None,
    **options,
) -> LayoutResult:
    """Optimise the landmark positions of `env` for `method` (module docstring) on the soft loss
    smoothed at `smoothing_cm` (`samples` common draws; None: the soft loss at the point); compare the
    start and the result by the hard loss, catchment and error rates on the `spacing` grid under every
    choice of `occlude` hidden landmarks, for `seeds` evaluation seeds (seed, seed + 1, ...), and say
    whether the change is within the seed-to-seed spread. `progress`: a `Progress`
    (evaluate/_progress.py): `start(steps)` once every option is valid, then `(1, steps)` after each
    step with the step's objective as the phase."""
    report, old = _layout_progress(progress, options)
    env = load_env(env)
    problem: LossProblem = loss_problem(env, method, spacing=OPT_SPACING, seed=seed, tau=tau, **options)
    k = occlusion_count(occlude, env.n_landmarks) if occlude else 0
    steps = positive_int(steps, "steps")
    seeds = positive_int(seeds, "seeds")
    smoothing = check_smoothing(smoothing_cm, Smoothing().deg, Smoothing().fraction, samples, env.arena)
    problem, sigmas, eps = smoothing_draws(problem, smoothing)
    n = env.n_landmarks
    masks = occlusion_masks(env, k)[0] if k else np.asarray(env.valid, bool)[None]
    lo, hi = _bounds(env)
    pos0 = np.asarray(env.landmarks, np.float64)[np.asarray(env.valid), :2]
    frac = np.clip((pos0 - lo) / (hi - lo), 1e-3, 1 - 1e-3)
    u0 = jnp.asarray(np.log(frac / (1 - frac)), jnp.float32)
    args = (problem, jnp.asarray(masks), jnp.asarray(lo, jnp.float32), jnp.asarray(hi, jnp.float32), n, sigmas, eps)
    report.start(steps)
    t0 = time.perf_counter()
    u, history = _minimise(args, u0, steps, report, old)
    pos = lo + (hi - lo) / (1 + np.exp(-np.asarray(u, np.float64)))
    radii = np.asarray(env.landmarks, np.float64)[np.asarray(env.valid), 2]
    optimised = make_env(
        [[float(x), float(y), float(r)] for (x, y), r in zip(pos, radii)],
        home=np.asarray(env.home).tolist(),
        arena=np.asarray(env.arena).tolist(),
        name=f"{env.name}-optimised-{method}" + (f"-occlude{k}" if k else ""),
        pad_to=env.landmarks.shape[0],
    )  # the start's shape: its compiled programs serve both
    seconds = time.perf_counter() - t0
    per_seed, first = [], None
    for s in range(seed, seed + seeds):
        pair = tuple(
            catchment(e, method, seed=s, occlude=k or None, grid=Grid(spacing=spacing), **options)
            for e in (env, optimised)
        )
        first = first or pair
        for label, e, c, q in zip(("start", "optimised"), (env, optimised), pair, (history[0], history[-1])):
            loss = float(homing_loss(e, method, spacing=spacing, seed=s, soft=False, **options))
            per_seed.append({**_hard_row(label, e, c, method, k, q), "seed": s, "hard_loss": loss})
    rows = [_mean_row([r for r in per_seed if r["layout"] == label]) for label in ("start", "optimised")]
    return LayoutResult(
        start=env,
        optimised=optimised,
        objective=history,
        rows=rows,
        seconds=seconds,
        method=method,
        occlude=k,
        catchments=first,
        per_seed=per_seed,
        verdict=layout_verdict(per_seed),
    )


def _mean_row(rows: list[dict]) -> dict:
    """One layout's rows over the seeds: the means, with the seed-to-seed standard deviation beside
    catchment, e>45 and the hard loss."""
    out = {**rows[0], "seeds": len(rows)}
    out.pop("seed")
    for col in ("catchment_pct", "catchment_min_pct", "gt45_pct", "gt90_pct", "hard_loss"):
        values = np.array([r[col] for r in rows], np.float64)
        out[col] = float(values.mean())
        if col in ("catchment_pct", "gt45_pct", "hard_loss"):
            out[f"{col}_sd"] = float(values.std(ddof=1)) if len(values) > 1 else float("nan")
    return out


def layout_verdict(per_seed: list[dict]) -> dict:
    """Per measure (hard loss, catchment, e>45): the mean paired change optimised - start over the
    seeds, its standard error, and whether it lies within two standard errors of 0 (one seed: unknown)."""
    out = {}
    for col in ("hard_loss", "catchment_pct", "gt45_pct"):
        start = np.array([r[col] for r in per_seed if r["layout"] == "start"], np.float64)
        end = np.array([r[col] for r in per_seed if r["layout"] == "optimised"], np.float64)
        diff = end - start
        se = float(diff.std(ddof=1) / np.sqrt(len(diff))) if len(diff) > 1 else float("nan")
        within = None if len(diff) < 2 else bool(abs(diff.mean()) <= 2 * se)
        reading = (
            "no change"
            if not np.any(diff)
            else "one seed: cannot tell"
            if within is None
            else "within seed noise"
            if within
            else "beyond seed noise"
        )
        out[col] = {
            "change": float(diff.mean()),
            "se": se,
            "seeds": len(diff),
            "within_seed_noise": within,
            "reading": reading,
        }
    return out


def _hard_row(label: str, env: Env, c: Catchment, method: str, k: int, soft_objective: float) -> dict:
    """Catchment and error rates of `env` (mean over the C(N, k) masks), the ordinary evaluation."""
    s = catchment_summary(c)
    return {
        "layout": label,
        "env": env.name,
        "method": method,
        "occlude": k,
        "catchment_pct": s["catchment_pct"]["mean"],
        "catchment_min_pct": s["catchment_pct"]["min"],
        "gt45_pct": s["gt45_pct"]["mean"],
        "gt90_pct": s["gt90_pct"]["mean"],
        "points": s["points"],
        "soft_objective": soft_objective,
    }
