"""Soft (differentiable) versions of the landmark methods on analytic views (docs/differentiable.md).

The hard methods make discrete choices: DELV picks each blob's parallax partner (the nearest
bearing, Eqs 3.2-3.3) and the best cyclic shift x heading hypothesis (Eqs 3.4-3.6), ACV the best
shift. Here each choice is a softmin with temperature `tau`:

  * partner: weights softmax(-|parallax| / tau + log visibility) over the partner slots; the
    parallax used is their weighted mean (tau in radians);
  * arrangement: weights softmax(-var(k, alpha) / (tau * scale)) over every shift k and
    hypothesis alpha, `scale` the mean over the shifts of sum |a'|^2 + |b'|^2 (var / scale is
    dimensionless, in [0, 2]); the homing vector is the weighted mean of every hypothesis's
    vector Rot(-alpha)(-p(k, alpha)), and the direction its angle;
  * ACV's shift: softmax(-cost(k) / tau) with cost in rad^2.

As tau -> 0 each softmin becomes the hard argmin, so the soft direction tends to the hard one
wherever the minimum is unique and every landmark is seen (`tests/gradients/test_loss.py`
measures it). The lists are one slot per landmark, paired under each shift by the soft cyclic
order of `soft.order`, and the blob weights (the soft visibility of `soft.sensing`) weight every
pair: where a landmark is hidden the hard method pairs shorter lists, so there soft and hard
differ (docs/differentiable.md "A continuous loss"). A direction's validity is a number in
[0, 1] (`_validity`), so a loss that counts an undefined direction as 2 stays continuous. Quantization (Eq 3.17) stays a staircase: its
gradient with respect to a distance is 0, with respect to the scale a it is ceil(R Q / a) / Q.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

from ..errors import InputError
from ..estimation import SIN_EPS, quantize
from ..geometry import angle_of, rotate, safe_norm, unit, wrap, wrap_positive
from ..methods.acv import ACV
from ..methods.alv import ALV
from ..methods.base import HomingMethod
from ..methods.delv import DELV
from ..methods.heading import Compass
from ..types import Real
from .order import shift_weights, soft_places
from .sensing import SoftMove

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


def _partner_parallax(rows: Array, cols: Array, col_ok: Array, col_w: Array, tau: Array) -> Array:
    """Soft nearest partner: the weighted parallax wrap(rows_i - cols_j) over the slots j, with
    weights softmax(-|parallax| / tau + log visibility_j) (a hidden partner fades out), (L,)."""
    par = wrap(rows[:, None] - cols[None, :])
    ok = col_ok & (col_w > 0)
    log_w = jnp.log(jnp.where(ok, col_w, 1.0))  # -> -inf as a partner fades out: continuous, and no NaN gradient
    logits = jnp.where(ok[None, :], -jnp.abs(par) / tau + log_w[None, :], -jnp.inf)
    w = jax.nn.softmax(jnp.where(jnp.any(ok), logits, 0.0), axis=-1)
    return jnp.sum(w * par, axis=-1)


def _guarded(r: Array, sin_delta: Array, r_max: Real) -> Array:
    """docs/model.md §3.1 guard: not positive, non-finite, > r_max or |sin delta| tiny -> r_max."""
    bad = (jnp.abs(sin_delta) < SIN_EPS) | ~jnp.isfinite(r) | (r <= 0) | (r > r_max)
    return jnp.where(bad, r_max, r)


def soft_vectors(move: SoftMove, settings: DELV, tau: Array, at_start: bool) -> Array:
    """Landmark vectors (L, 2) of the start view (reference map, Eq 3.3) or of the end view
    (current vectors, Eq 3.2), with soft partners; cm, frame of that view."""
    beta = move.end.bearing + move.psi_hat
    theta = move.start.bearing
    if at_start:
        delta = -_partner_parallax(theta, beta, move.end.valid, move.end.weight, tau)  # wrap(beta - theta)
        s = jnp.sin(delta)
        r = move.d_hat * jnp.sin(theta + delta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
        bearing, other_ok = theta, move.end.valid
    else:
        delta = _partner_parallax(beta, theta, move.start.valid, move.start.weight, tau)
        s = jnp.sin(delta)
        r = move.d_hat * jnp.sin(beta - delta) / jnp.where(jnp.abs(s) < SIN_EPS, 1.0, s)
        bearing, other_ok = move.end.bearing, move.start.valid
    r = jnp.where(jnp.any(other_ok), _guarded(r, s, settings.r_max), settings.r_max)
    r = quantize(r, settings.levels, settings.scale)
    return r[:, None] * unit(bearing)


def _validity(ref_w: Array, cur_w: Array, min_blobs: int) -> Array:
    """How far a direction is defined, in [0, 1]: min(seen blobs of either view) - min_blobs + 1,
    clipped (the hard rule "at least min_blobs blobs", continuous in the visibility weights)."""
    return jnp.clip(jnp.minimum(jnp.sum(ref_w), jnp.sum(cur_w)) - min_blobs + 1.0, 0.0, 1.0)


def soft_delv(method: DELV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """Soft DELV: (homing vector in the agent frame (2,), validity in [0, 1])."""
    ref_v, ref_ok, ref_w = soft_vectors(home, method, tau, True), home.start.valid, home.start.weight
    cur_v, cur_ok, cur_w = soft_vectors(view, method, tau, False), view.end.valid, view.end.weight
    alphas = method.alphas(home, view)
    pairs, row_w = shift_weights(
        *soft_places(home.start.bearing, ref_w, ref_ok), *soft_places(view.end.bearing, cur_w, cur_ok)
    )
    row_ok = row_w > 0
    w = pairs * ref_w[None, :, None] * cur_w[None, None, :]  # (H, L_ref, L_cur)
    total = jnp.maximum(jnp.sum(w, axis=(1, 2)), 1e-12)[:, None]  # (H, 1)
    a_mean = jnp.einsum("hml,md->hd", w, ref_v) / total
    b_mean = jnp.einsum("hml,ld->hd", w, cur_v) / total
    a_c, b_c = ref_v[None] - a_mean[:, None], cur_v[None] - b_mean[:, None]  # (H, L, 2)
    const = jnp.einsum("hml,hm->h", w, jnp.sum(a_c * a_c, -1)) + jnp.einsum("hml,hl->h", w, jnp.sum(b_c * b_c, -1))
    z_re = jnp.einsum("hml,hmd,hld->h", w, a_c, b_c)
    z_im = jnp.einsum("hml,hm,hl->h", w, a_c[..., 0], b_c[..., 1]) - jnp.einsum(
        "hml,hm,hl->h", w, a_c[..., 1], b_c[..., 0]
    )
    var = const[:, None] - 2.0 * (jnp.cos(alphas)[None, :] * z_re[:, None] - jnp.sin(alphas)[None, :] * z_im[:, None])
    scale = jnp.maximum(jnp.sum(row_w * const) / jnp.maximum(jnp.sum(row_w), 1e-6), 1e-6)
    best = jnp.min(jnp.where(row_ok[:, None], var, jnp.inf))
    logits = jnp.where(
        row_ok[:, None], -(var - best) / (tau * scale) + jnp.log(jnp.maximum(row_w, 1e-30))[:, None], -jnp.inf
    )
    sel = jax.nn.softmax(jnp.where(jnp.any(row_ok), logits, 0.0).reshape(-1)).reshape(var.shape)
    p = a_mean[:, None, :] - rotate(b_mean[:, None, :], alphas[None, :])  # (H, A, 2)
    v = rotate(-p, -alphas[None, :])
    vec = jnp.sum(sel[..., None] * v, axis=(0, 1))
    min_pairs = 1 if method.heading is not None else 2
    return vec, _validity(ref_w, cur_w, min_pairs) * (safe_norm(vec) > 0)


def soft_alv(method: ALV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """ALV (Eqs 3.11-3.12) with weighted blobs: (homing vector in the agent frame, validity in [0, 1])."""
    heading = method.heading(home, view)
    here = jnp.sum(view.end.weight[:, None] * unit(view.end.bearing + heading), axis=0)
    there = jnp.sum(home.start.weight[:, None] * unit(home.start.bearing), axis=0)
    h = rotate(here - there, -heading)
    return h, _validity(home.start.weight, view.end.weight, 1) * (safe_norm(h) > 0)


def soft_acv(method: ACV, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array]:
    """ACV (Eq 5.2) with a softmin over the cyclic shifts: (homing vector in the agent frame, validity)."""
    heading = method.heading(home, view)
    theta, theta_ok, theta_w = home.start.bearing, home.start.valid, home.start.weight
    a, a_ok, a_w = wrap_positive(view.end.bearing + heading), view.end.valid, view.end.weight
    pairs, shift_w = shift_weights(*soft_places(theta, theta_w, theta_ok), *soft_places(a, a_w, a_ok))
    shift_ok = shift_w > 0
    w = pairs * theta_w[None, :, None] * a_w[None, None, :]  # (K, L_ref, L_cur)
    diff = wrap(theta[:, None] - a[None, :])  # (m, l)
    cost = jnp.sum(w * diff * diff, axis=(1, 2))
    best = jnp.min(jnp.where(shift_ok, cost, jnp.inf))
    logits = jnp.where(shift_ok, -(cost - best) / tau + jnp.log(jnp.maximum(shift_w, 1e-30)), -jnp.inf)
    sel = jax.nn.softmax(jnp.where(jnp.any(shift_ok), logits, 0.0))
    corr = jnp.einsum("kml,ld->kd", w * -diff[None], unit(a + jnp.pi / 2))  # (K, 2)
    hv = rotate(jnp.sum(sel[:, None] * corr, axis=0), -heading)
    return hv, _validity(theta_w, a_w, 1) * (safe_norm(hv) > 0)


def soft_direction(method: HomingMethod, home: SoftMove, view: SoftMove, tau: Array) -> tuple[Array, Array, Array]:
    """(homing vector (2,), its angle in the agent frame (NaN where validity is 0), validity in [0, 1])
    of a differentiable method (`check_differentiable` first, outside jit)."""
    fn = {DELV: soft_delv, ALV: soft_alv, ACV: soft_acv}[type(method)]
    vec, valid = fn(method, home, view, tau)
    return vec, jnp.where(valid > 0, angle_of(vec), jnp.nan), valid
