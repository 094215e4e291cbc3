"""Soft (differentiable) versions of the landmark methods on analytic views (docs/differentiable.md).

The hard methods make discrete choices: DELV picks each blob's parallax partner (the nearest
bearing, Eqs 3.2-3.3) and the best cyclic shift x heading hypothesis (Eqs 3.4-3.6), ACV the best
shift. Here each choice is a softmin with temperature `tau`:

  * partner: weights softmax(-|parallax| / tau) over the valid partners; the parallax used is
    their weighted mean (tau in radians);
  * arrangement: weights softmax(-var(k, alpha) / (tau * scale)) over every shift k and
    hypothesis alpha, `scale` the mean over the shifts of sum |a'|^2 + |b'|^2 (var / scale is
    dimensionless, in [0, 2]); the homing vector is the weighted mean of every hypothesis's
    vector Rot(-alpha)(-p(k, alpha)), and the direction its angle;
  * ACV's shift: softmax(-cost(k) / tau) with cost in rad^2.

As tau -> 0 each softmin becomes the hard argmin, so the soft direction tends to the hard one
wherever the minimum is unique (`tests/gradients/test_loss.py` measures it). Blob weights (the soft
visibility of `soft.sensing`) weight every pair. Quantization (Eq 3.17) stays a staircase: its
gradient with respect to a distance is 0, with respect to the scale a it is ceil(R Q / a) / Q.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

from ..errors import InputError
from ..estimation import SIN_EPS, quantize
from ..geometry import angle_of, rotate, safe_norm, unit, wrap
from ..methods.acv import ACV
from ..methods.alv import ALV
from ..methods.base import HomingMethod
from ..methods.delv import DELV
from ..methods.heading import Compass
from ..methods.pairing import shift_pairs
from ..types import Real
from .sensing import SoftMove, _sorted

DIFFERENTIABLE = (DELV, ALV, ACV)  # exactly these classes, with no heading source or a `Compass`


def check_differentiable(method: HomingMethod) -> None:
    """`InputError` naming the method when it has no soft version (image methods search pixel
    shifts or descend image differences; the visual compass reads a gray image)."""
    name = type(method).__name__
    if type(method) not in DIFFERENTIABLE:
        raise InputError(
            "method",
            name,
            "has no differentiable (soft) version: the soft path covers DELV, ALV and ACV "
            "(image methods and gap-aware DELV make discrete pixel or gap choices)",
        )
    heading = getattr(method, "heading", None)
    if heading is not None and type(heading) is not Compass:
        raise InputError(
            "method",
            name,
            f"with the heading source {type(heading).__name__} has no soft version "
            "(the visual compass searches pixel shifts of a gray image)",
        )


def _partner_parallax(rows: Array, cols: Array, col_ok: Array, tau: Array) -> Array:
    """Soft nearest partner: the softmin-weighted parallax wrap(rows_i - cols_j) over valid j, (B,)."""
    par = wrap(rows[:, None] - cols[None, :])
    logits = jnp.where(col_ok[None, :], -jnp.abs(par) / tau, -jnp.inf)
    w = jax.nn.softmax(jnp.where(jnp.any(col_ok), logits, 0.0), axis=-1)
    return jnp.sum(w * par, axis=-1)


def _guarded(r: Array, sin_delta: Array, r_max: Real) -> Array:
    """docs/model.md §3.1 guard: not positive, non-finite, > r_max or |sin delta| tiny -> r_max."""
    bad = (jnp.abs(sin_delta) < SIN_EPS) | ~jnp.isfinite(r) | (r <= 0) | (r > r_max)
    return jnp.where(bad, r_max, r)


def soft_vectors(move: SoftMove, settings: DELV, tau: Array, at_start: bool) -> Array:
    """Landmark vectors (B, 2) of the start view (reference map, Eq 3.3) or of the end view
    (current vectors, Eq 3.2), with soft partners; cm, frame of that view."""
    beta = move.end.bearing + move.psi_hat
    theta = move.start.bearing
    if at_start:
        delta = _partner_parallax(theta, beta, move.end.valid, tau)  # wrap(theta - beta), sign flipped below
        delta = -delta
        s = jnp.sin(delta)
        r = move.d_hat * jnp.sin(theta + delta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
        bearing, other_ok = theta, move.end.valid
    else:
        delta = _partner_parallax(beta, theta, move.start.valid, tau)
        s = jnp.sin(delta)
        r = move.d_hat * jnp.sin(beta - delta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
        bearing, other_ok = move.end.bearing, move.start.valid
    r = jnp.where(jnp.any(other_ok), _guarded(r, s, settings.r_max), settings.r_max)
    r = quantize(r, settings.levels, settings.scale)
    return r[:, None] * unit(bearing)


def soft_delv(method: DELV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """Soft DELV: (homing vector in the agent frame (2,), valid)."""
    ref_v, ref_ok, ref_w = soft_vectors(home, method, tau, True), home.start.valid, home.start.weight
    cur_v, cur_ok, cur_w = soft_vectors(view, method, tau, False), view.end.valid, view.end.weight
    alphas = method.alphas(home, view)
    ref_idx, cur_idx, pair_ok, row_ok = shift_pairs(ref_ok, cur_ok)
    w = pair_ok * ref_w[ref_idx] * cur_w[cur_idx]  # (H, S)
    total = jnp.maximum(jnp.sum(w, axis=1), 1e-12)[:, None]  # (H, 1)
    a, b = ref_v[ref_idx], cur_v[cur_idx]  # (H, S, 2)
    a_mean = jnp.sum(w[..., None] * a, axis=1) / total
    b_mean = jnp.sum(w[..., None] * b, axis=1) / total
    a_c, b_c = a - a_mean[:, None], b - b_mean[:, None]
    const = jnp.sum(w * jnp.sum(a_c * a_c + b_c * b_c, axis=-1), axis=1)  # (H,)
    z_re = jnp.sum(w * (a_c[..., 0] * b_c[..., 0] + a_c[..., 1] * b_c[..., 1]), axis=1)
    z_im = jnp.sum(w * (a_c[..., 0] * b_c[..., 1] - a_c[..., 1] * b_c[..., 0]), axis=1)
    var = const[:, None] - 2.0 * (jnp.cos(alphas)[None, :] * z_re[:, None] - jnp.sin(alphas)[None, :] * z_im[:, None])
    scale = jnp.maximum(jnp.sum(jnp.where(row_ok, const, 0.0)) / jnp.maximum(jnp.sum(row_ok), 1), 1e-6)
    logits = jnp.where(
        row_ok[:, None], -(var - jnp.min(jnp.where(row_ok[:, None], var, jnp.inf))) / (tau * scale), -jnp.inf
    )
    sel = jax.nn.softmax(jnp.where(jnp.any(row_ok), logits, 0.0).reshape(-1)).reshape(var.shape)
    p = a_mean[:, None, :] - rotate(b_mean[:, None, :], alphas[None, :])  # (H, A, 2)
    v = rotate(-p, -alphas[None, :])
    vec = jnp.sum(sel[..., None] * v, axis=(0, 1))
    n = jnp.sum(pair_ok[0])
    min_pairs = 1 if method.heading is not None else 2
    valid = (n >= min_pairs) & (n >= 1) & (safe_norm(vec) > 0)
    return vec, valid


def soft_alv(method: ALV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """ALV (Eqs 3.11-3.12) with weighted blobs: (homing vector in the agent frame, valid)."""
    heading = method.heading(home, view)
    here = jnp.sum(view.end.weight[:, None] * unit(view.end.bearing + heading), axis=0)
    there = jnp.sum(home.start.weight[:, None] * unit(home.start.bearing), axis=0)
    h = rotate(here - there, -heading)
    valid = jnp.any(view.end.valid) & jnp.any(home.start.valid) & (safe_norm(h) > 0)
    return h, valid


def soft_acv(method: ACV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """ACV (Eq 5.2) with a softmin over the cyclic shifts: (homing vector in the agent frame, valid)."""
    heading = method.heading(home, view)
    theta, theta_ok, theta_w = home.start.bearing, home.start.valid, home.start.weight
    a, a_w = _sorted(view.end.bearing + heading, view.end.valid, view.end.weight)
    a_ok = a_w > 0.5
    ref_idx, cur_idx, pair_ok, shift_ok = shift_pairs(theta_ok, a_ok)
    diff = wrap(theta[ref_idx] - a[cur_idx])  # (K, S)
    w = pair_ok * theta_w[ref_idx] * a_w[cur_idx]
    cost = jnp.sum(w * diff * diff, axis=1)
    logits = jnp.where(shift_ok, -(cost - jnp.min(jnp.where(shift_ok, cost, jnp.inf))) / tau, -jnp.inf)
    sel = jax.nn.softmax(jnp.where(jnp.any(shift_ok), logits, 0.0))
    corr = jnp.sum((w * -diff)[..., None] * unit(a[cur_idx] + jnp.pi / 2), axis=1)  # (K, 2)
    hv = rotate(jnp.sum(sel[:, None] * corr, axis=0), -heading)
    valid = jnp.any(pair_ok[0]) & (safe_norm(hv) > 0)
    return hv, valid


def soft_direction(method: HomingMethod, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array, Array]:
    """(homing vector (2,), its angle in the agent frame (NaN where invalid), valid) of a
    differentiable method (`check_differentiable` first, outside jit)."""
    fn = {DELV: soft_delv, ALV: soft_alv, ACV: soft_acv}[type(method)]
    vec, valid = fn(method, home, view, tau)
    return vec, jnp.where(valid, angle_of(vec), jnp.nan), valid
