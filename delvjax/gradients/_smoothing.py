"""The homing loss smoothed at a stated scale and its gradient (docs/differentiable.md
"Sensitivity at a stated scale").

    L_sigma(theta) = E_eps[ L(theta + sigma * eps) ],   eps ~ N(0, I),

one sigma per kind of parameter in its own unit: `smoothing_cm` for every landmark's x, y and r,
home, d and DELV's quantization scale; `smoothing_deg` for the noise sigmas in degrees;
`smoothing_fraction` for the step-noise fractions. The soft loss is continuous in every
parameter (`core.soft`), so the gradient of L_sigma is the mean of the pathwise gradients
at the perturbed parameters. It is estimated with common random numbers: `samples` draws
fixed by the seed, taken as antithetic pairs (eps, -eps), so the estimate is one smooth
function of theta whose central differences equal its gradient. A parameter that must stay
non-negative (a radius, d, a noise sigma, the scale) is reflected at 0 (|theta + sigma eps|).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import NamedTuple

import equinox as eqx
import jax
import jax.numpy as jnp

from ..core.checks import positive
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.maps import CLEARANCE, SPACING
from ..core.methods import HomingMethod
from ..core.scene import Env
from ..core.soft.sensing import VISIBILITY_WIDTH
from ..core.types import Real
from ..options._limits import MAX_POINTS
from ..options._setup import NOISE_FIELDS_DEG, NOISE_FIELDS_FRACTION
from ._loss import TAU, LossProblem, loss_problem, problem_loss, problem_value_and_grad, readable_grads

SMOOTHING_CM = 5.0  # default scale for positions, radii, home, d and the quantization scale, cm
SMOOTHING_DEG = 1.0  # default scale for the noise sigmas given in degrees
SMOOTHING_FRACTION = 0.01  # default scale for the step-noise fractions
SAMPLES = 8  # default draws (4 antithetic pairs): ALV 9.8 hard maps, ACV 16, DELV 38-50 (benchmarks/bench_grad.py)
SMOOTHING_STREAM = 56  # the draws' stream, folded into the problem's key
VIEW_CM = 50.0  # cm: the distance at which a move of sigma sets the visibility width (the unit move d)


class Smoothing(NamedTuple):
    """The scale of a sensitivity: sigma per unit (None: the gradient at the point) and the draws."""

    cm: float | None = SMOOTHING_CM
    deg: float | None = SMOOTHING_DEG
    fraction: float | None = SMOOTHING_FRACTION
    samples: int = SAMPLES

    def describe(self) -> dict:
        """The scale as the outputs name it."""
        if self.cm is None:
            return {"smoothing": "none (gradient at the point)"}
        return {
            "smoothing_cm": self.cm,
            "smoothing_deg": self.deg,
            "smoothing_fraction": self.fraction,
            "samples": self.samples,
        }


def check_smoothing(cm: float | None, deg: float | None, fraction: float | None, samples: int, arena) -> Smoothing:
    """`InputError` naming the option for a scale that is not positive, a length scale larger than
    the arena (xmin, ymin, xmax, ymax), or a sample count that is not an even number >= 2; None for
    `cm` means no smoothing."""
    if cm is None:
        return Smoothing(None, None, None, samples)
    cm = positive(cm, "smoothing_cm")
    xmin, ymin, xmax, ymax = (float(v) for v in arena)
    arena_cm = max(xmax - xmin, ymax - ymin)
    if cm > arena_cm:
        raise InputError("smoothing_cm", cm, f"must not exceed the arena's size ({arena_cm:g} cm)")
    deg = positive(deg, "smoothing_deg")
    if deg > 90:
        raise InputError("smoothing_deg", deg, "must be at most 90 degrees")
    fraction = positive(fraction, "smoothing_fraction")
    if fraction > 1:
        raise InputError("smoothing_fraction", fraction, "must be at most 1")
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 2 or samples % 2:
        raise InputError("samples", samples, "must be an even whole number >= 2 (antithetic pairs)")
    return Smoothing(cm, deg, fraction, samples)


def _sigmas(problem: LossProblem, s: Smoothing) -> dict:
    """Per parameter leaf, its sigma (0 for padded landmark slots)."""
    valid = jnp.asarray(problem.env.valid, jnp.float32)[:, None]
    noise = problem.params["noise"]
    fields = {f: math.radians(s.deg) for f in NOISE_FIELDS_DEG.values()}
    fields.update({f: s.fraction for f in NOISE_FIELDS_FRACTION.values()})
    sig_noise = jax.tree.map(lambda x: jnp.zeros_like(jnp.asarray(x, jnp.float32)), noise)
    names = [f for f in fields if hasattr(sig_noise, f)]
    sig_noise = eqx.tree_at(
        lambda m: [getattr(m, f) for f in names], sig_noise, [jnp.float32(fields[f]) for f in names]
    )
    out = {
        "landmarks": s.cm * jnp.broadcast_to(valid, problem.params["landmarks"].shape),
        "home": jnp.full((2,), s.cm, jnp.float32),
        "d": jnp.float32(s.cm),
        "noise": sig_noise,
    }
    if "scale" in problem.params:
        out["scale"] = jnp.float32(s.cm)
    return out


def _perturbed(params: dict, sigmas: dict, eps: dict) -> dict:
    """theta + sigma eps, reflected at 0 for the quantities that must stay non-negative."""
    moved = jax.tree.map(lambda p, s, e: p + s * e, params, sigmas, eps)
    lm = moved["landmarks"]
    moved["landmarks"] = lm.at[:, 2].set(jnp.abs(lm[:, 2]))
    for name in ("d", "scale", "noise"):
        if name in moved:
            moved[name] = jax.tree.map(jnp.abs, moved[name])
    return moved


def _draws(problem: LossProblem, samples: int) -> dict:
    """`samples` standard normal draws per parameter leaf, as antithetic pairs: (samples, ...)."""
    leaves, tree = jax.tree.flatten(problem.params)
    keys = jax.random.split(jax.random.fold_in(problem.key, SMOOTHING_STREAM), len(leaves))
    half = [jax.random.normal(k, (samples // 2, *jnp.shape(x)), dtype=jnp.float32) for k, x in zip(keys, leaves)]
    return jax.tree.unflatten(tree, [jnp.concatenate([e, -e]) for e in half])


def smoothed_loss(
    params: dict, problem: LossProblem, sigmas: dict, eps: dict, visible: jax.Array | None = None
) -> jax.Array:
    """The common-random-number estimate of L_sigma at `params`: the mean loss over the draws
    (`visible`: the landmarks the current views see, as `problem_loss`)."""
    losses = jax.lax.map(lambda e: problem_loss(_perturbed(params, sigmas, e), problem, visible), eps)
    return jnp.mean(losses)


@jax.jit
def _value_and_grad(problem: LossProblem, sigmas: dict, eps: dict):
    """Mean value and gradient over the draws, and the gradient's standard error from the
    antithetic pairs (each pair's mean is one independent estimate)."""
    grad = jax.value_and_grad(lambda p, e: problem_loss(_perturbed(p, sigmas, e), problem))
    values, grads = jax.lax.map(lambda e: grad(problem.params, e), eps)
    half = values.shape[0] // 2

    def pair_se(g):
        pairs = (g[:half] + g[half:]) / 2
        return jnp.std(pairs, axis=0, ddof=1) / jnp.sqrt(half) if half > 1 else jnp.full_like(pairs[0], jnp.nan)

    return jnp.mean(values), jax.tree.map(lambda g: jnp.mean(g, axis=0), grads), jax.tree.map(pair_se, grads)


def at_scale(problem: LossProblem, smoothing: Smoothing) -> LossProblem:
    """`problem` with its soft edges set for the smoothing scale sigma: the grid rule's edge sigma cm
    (no narrower than EDGE_CM) and the visibility width the angle sigma subtends at VIEW_CM (no
    narrower than the given sharpness): a transition no sharper than the scale it is smoothed at."""
    return problem._replace(
        edge=jnp.float32(max(float(problem.edge), smoothing.cm)),
        sharpness=jnp.float32(max(float(problem.sharpness), smoothing.cm / VIEW_CM)),
    )


def smoothing_draws(problem: LossProblem, smoothing: Smoothing) -> tuple[LossProblem, dict, dict]:
    """(the problem at the scale, sigma per parameter, the draws) of `smoothing`; with no smoothing
    (cm None) the problem itself, zero sigmas and one pair of draws (the loss at the point)."""
    if smoothing.cm is None:
        return problem, jax.tree.map(jnp.zeros_like, problem.params), _draws(problem, 2)
    scaled = at_scale(problem, smoothing)
    return scaled, _sigmas(scaled, smoothing), _draws(scaled, smoothing.samples)


def smoothed_value_and_grad(problem: LossProblem, smoothing: Smoothing):
    """(L_sigma estimate, its gradient by parameter, the gradient's standard error by parameter) of
    `problem` at the scale `smoothing`."""
    return _value_and_grad(*smoothing_draws(problem, smoothing))


@keywords_after(2, ("spacing", "seed", "tau", "sharpness", "heading_deg", "clearance", "max_points"))
def homing_loss_grad(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    sharpness: float = VISIBILITY_WIDTH,
    heading_deg: float | None = None,
    clearance: Real = CLEARANCE,
    max_points: int = MAX_POINTS,
    smoothing_cm: float | None = SMOOTHING_CM,
    smoothing_deg: float = SMOOTHING_DEG,
    smoothing_fraction: float = SMOOTHING_FRACTION,
    samples: int = SAMPLES,
    **options,
) -> tuple[float, dict]:
    """The soft homing loss smoothed at a stated scale and its gradient, one program: a dict with
    landmarks (N, 3) per [x, y, r] cm, home (2,) per cm, d per cm, scale per cm (DELV only), each
    noise sigma under its option name (per degree for *_deg, per unit for the step factors), and
    "standard_error": the same layout, each derivative's standard error over the draws (None
    without smoothing), and "smoothing": the scale it holds at (docs/differentiable.md
    "Sensitivity at a stated scale").

    smoothing_cm (positions, radii, home, d, scale), smoothing_deg (noise sigmas in degrees),
    smoothing_fraction (step-noise fractions): the sigmas of the Gaussian smoothing, estimated from
    `samples` common random draws; smoothing_cm=None: the exact gradient of the soft loss at the
    point (rough at the centimetre scale). The grid points and their headings are held fixed."""
    problem = loss_problem(env, method, spacing, seed, tau, sharpness, heading_deg, clearance, max_points, **options)
    smoothing = check_smoothing(smoothing_cm, smoothing_deg, smoothing_fraction, samples, problem.env.arena)
    if smoothing.cm is None:
        value, grads = problem_value_and_grad(problem)
        se = None
    else:
        value, grads, se = smoothed_value_and_grad(problem, smoothing)
    out = readable_grads(grads, problem.n_landmarks)
    out["standard_error"] = None if se is None else readable_grads(se, problem.n_landmarks)
    out["smoothing"] = smoothing.describe()
    return float(value), out
