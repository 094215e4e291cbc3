"""The loss along one coordinate at several scales, with the sensitivity drawn as a tangent
(docs/differentiable.md "Sensitivity at a stated scale"; `delvjax sensitivity --profile`).

For a landmark coordinate c (x, y or r of landmark i) and each scale sigma: Q_sigma(c + t) over
t in [-extent, extent] from one set of draws (common random numbers, so the curve is the smooth
function whose gradient `homing_loss_grad` returns), and that gradient at t = 0. The point scale
(sigma None) is the soft loss itself with its exact gradient, rough at the centimetre scale.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from ._loss import LossProblem, problem_loss, problem_value_and_grad
from ._smoothing import Smoothing, _value_and_grad, smoothed_loss, smoothing_draws

COORDS = ("x", "y", "r")


def _moved(params: dict, index: jax.Array | int, coord: jax.Array | int, t: jax.Array) -> dict:
    """`params` with landmark `index`'s coordinate `coord` moved by t."""
    return dict(params, landmarks=params["landmarks"].at[index, coord].add(t))


@jax.jit
def _point_curve(problem: LossProblem, ts: jax.Array, index: jax.Array, coord: jax.Array) -> jax.Array:
    return jax.lax.map(lambda t: problem_loss(_moved(problem.params, index, coord, t), problem), ts)


@jax.jit
def _smoothed_curve(problem: LossProblem, sigmas: dict, eps: dict, ts, index, coord) -> jax.Array:
    return jax.lax.map(lambda t: smoothed_loss(_moved(problem.params, index, coord, t), problem, sigmas, eps), ts)


def loss_profile(
    problem: LossProblem,
    index: int = 0,
    coord: str = "x",
    scales: tuple[float | None, ...] = (None, 1.0, 5.0),
    extent: float = 15.0,
    steps: int = 31,
    samples: int = 8,
    deg: float = Smoothing().deg,
) -> list[dict]:
    """Rows {scale_cm ("" for the point), t_cm, loss, slope_at_0, loss_at_0}: the curve of each scale
    and its gradient at t = 0 (the tangent loss_at_0 + slope_at_0 * t)."""
    c = COORDS.index(coord)
    ts = jnp.linspace(-extent, extent, steps, dtype=jnp.float32)
    rows = []
    for sigma in scales:
        if sigma is None:
            curve = _point_curve(problem, ts, index, c)
            value, grads = problem_value_and_grad(problem)
        else:
            smoothing = Smoothing(sigma, deg, Smoothing().fraction, samples)
            scaled, sig, eps = smoothing_draws(problem, smoothing)
            curve = _smoothed_curve(scaled, sig, eps, ts, index, c)
            value, grads, _ = _value_and_grad(scaled, sig, eps)
        slope = float(np.asarray(grads["landmarks"])[index, c])
        for t, q in zip(np.asarray(ts, np.float64), np.asarray(curve, np.float64)):
            rows.append(
                {
                    "scale_cm": "" if sigma is None else sigma,
                    "landmark": index,
                    "coordinate": coord,
                    "t_cm": float(t),
                    "loss": float(q),
                    "loss_at_0": float(value),
                    "slope_at_0": slope,
                }
            )
    return rows
