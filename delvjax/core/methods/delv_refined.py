"""DELV with sub-degree refinement: least squares on position and heading after the search
(docs/differentiable.md "Sub-degree refinement"; beyond the thesis).

The search of `delv.match_arrangement` (Eqs 3.4-3.6) tries n_heading discrete hypotheses alpha
(1 degree apart by default), so the heading, and with it the home vector, is off by up to half a
step. Here the best pairing of the search is kept and (alpha, p) are refined by least squares,

    min over alpha, p of  sum_i |V^R_i - Rot(alpha) V_j(i) - p|^2,

started at the search's answer (optimistix Gauss-Newton, a few steps; kept only if it lowers
the sum). With a compass the
heading is refined too: the landmarks then correct a noisy compass reading.
"""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array

from ..geometry import rotate
from ..types import BlobFlags, BlobVectors, Hypotheses, Point, Scalar
from .delv import DELV, search_pairings

STEPS = 32


def solver() -> eqx.Module:
    """optimistix's Gauss-Newton (nearly linear: 8 steps where Levenberg-Marquardt took 23). Built at each trace:
    constructing one at import starts JAX's backend (which must wait for jax.distributed), and one
    instance shared by traces of other shapes made jit run a program compiled for another shape."""
    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    return optx.GaussNewton(rtol=1e-6, atol=1e-6)


def refined_match(
    ref_v: BlobVectors,
    ref_valid: BlobFlags,
    cur_v: BlobVectors,
    cur_valid: BlobFlags,
    alphas: Hypotheses,
    offsets: Array | None = None,
) -> tuple[Point, Scalar, Scalar, Array]:
    """`match_arrangement` (with its `offsets`), then least squares on (alpha, p) for its pairing:
    (p, alpha, var, n)."""
    p0, alpha0, _, n, (ref_row, cur_row, paired) = search_pairings(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
    ref, cur, w = ref_v[ref_row], cur_v[cur_row], paired.astype(ref_v.dtype)[:, None]

    def residuals(y, _):
        return (w * (ref - rotate(cur, y[0]) - y[1:])).ravel()

    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    y0 = jnp.concatenate([alpha0[None], p0])
    sol = optx.least_squares(residuals, solver(), y0, max_steps=STEPS, throw=False)
    cost = lambda y: jnp.sum(residuals(y, None) ** 2)  # noqa: E731
    ok = jnp.all(jnp.isfinite(sol.value)) & (cost(sol.value) <= cost(y0))  # never worse than the search
    y = jnp.where(ok, sol.value, y0)
    return y[1:], y[0], cost(y), n


class DELVRefined(DELV):
    """DELV whose best (pairing, alpha) is refined by least squares (module docstring)."""

    def match(self, ref_v, ref_valid, cur_v, cur_valid, alphas, offsets=None):
        return refined_match(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
