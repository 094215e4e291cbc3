"""DELV without a compass in O(B^2 + B A) per view: Eq 3.5's terms of every (rotation, shift) pairing from
window and prefix sums, the best few rescored exactly as the full table scores them (docs/model.md §3.3).

Without a compass each heading hypothesis a pairs the current list rotated to start at blob
r = offsets[a] (`delv.list_offsets`), so the search covers B rotations x B shifts, each a sum over B
pairs: B^3 per view when every pairing is summed on its own (`delv.pairing_table` over all rotations).
Written with the pair sums (complex numbers, n pairs, S_a = sum a_i, Q_a = sum |a_i|^2, likewise b),

    const = Q_a - |S_a|^2 / n + Q_b - |S_b|^2 / n,    z = sum conj(a_i) b_i - conj(S_a) S_b / n,

and every one of these is a window sum or a difference of prefix sums (docs/model.md §3.3 gives the
index algebra), so the (rotation, shift) table costs O(B^2) and the hypotheses O(B A), as before.
Below `MIN_SLOTS` blob slots the direct table is the faster one and is used (every thesis
environment: outputs there are the direct table's, bit for bit). The sums are rounded differently
from the direct table, so the table only nominates: the
`CANDIDATES` smallest entries are rescored by the direct formula of `delv.pairing_table`, bit for bit,
and the first minimum among them wins. The direct table's winner is among them unless more than
`CANDIDATES` entries lie within rounding (~1e-6 relative) of the minimum; tested against the full
table on random views (tests/core/methods/test_delv_rotations.py).
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import rotate
from ..types import BlobFlags, BlobVectors, CurrentFlags, CurrentVectors, Hypotheses, Point, Scalar

CANDIDATES = 16  # entries of the fast table rescored exactly
MIN_SLOTS = 12  # fewer blob slots: the direct B^3 table is as cheap or cheaper, and kept (bit for bit)
# (a vector map at L = 8: 47-57 CPU-us a point direct, 81 here; at L = 16: 235 direct, 168-185 here)


def _padded(v: Array, valid: Array, size: int) -> Array:
    """Vectors (B, 2) centred on their valid mean, zero where invalid, padded to (size, 2) (var is
    unchanged by a shift of all a or all b; centring keeps the sums small, so they round less)."""
    w = valid.astype(v.dtype)[:, None]
    mean = jnp.sum(v * w, axis=0) / jnp.maximum(jnp.sum(w), 1.0)
    return jnp.pad((v - mean) * w, ((0, size - v.shape[0]), (0, 0)))


def _cross(a: Array, b: Array) -> tuple[Array, Array]:
    """Re and Im of conj(a) b over the last axis (x, y)."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1], a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _terms(sa: Array, qa: Array, sb: Array, qb: Array, x_re: Array, x_im: Array, inv_n: Array) -> tuple:
    """(const, z_re, z_im) of Eq 3.5 from the pair sums (module docstring)."""
    sab_re, sab_im = _cross(sa, sb)
    const = qa - jnp.sum(sa * sa, axis=-1) * inv_n + qb - jnp.sum(sb * sb, axis=-1) * inv_n
    return const, x_re - sab_re * inv_n, x_im - sab_im * inv_n


def rotation_table(
    ref_v: BlobVectors, ref_valid: BlobFlags, cur_v: CurrentVectors, cur_valid: CurrentFlags
) -> tuple[Array, Array, Array]:
    """(const, z_re, z_im), each (R, K) = (size, size): rotation r (the current list starting at blob
    r mod M), shift k of `pairing.shift_pairs`, in O(size^2) (docs/model.md §3.3)."""
    size = max(ref_valid.shape[0], cur_valid.shape[0])
    n_ref, n_cur = jnp.sum(ref_valid), jnp.sum(cur_valid)
    n_r, n_c = jnp.maximum(n_ref, 1), jnp.maximum(n_cur, 1)
    inv_n = 1.0 / jnp.maximum(jnp.minimum(n_ref, n_cur), 1).astype(ref_v.dtype)
    a, b = _padded(ref_v, ref_valid, size), _padded(cur_v, cur_valid, size)
    i = jnp.arange(size)
    r, k = i[:, None], i[None, :]  # (R, 1), (1, K)
    r_eff = r % n_c
    sq = lambda v: jnp.sum(v * v, axis=(-2, -1))  # noqa: E731
    # M <= N: current c pairs reference (c + d) mod N, d = (k - r) mod N for c >= r, (k - r + M) mod N below
    a_win = a[(i[:, None] + i[None, :]) % n_r] * (i < n_cur)[None, :, None]  # (K, S, 2): window at shift k
    d_re, d_im = _cross(a[(i[:, None] + i[None, :]) % n_r], b[None])  # (d, c); b is 0 for c >= M
    zero = jnp.zeros((size, 1), a.dtype)
    p_re = jnp.concatenate([zero, jnp.cumsum(d_re, axis=1)], axis=1)  # (d, c + 1) prefix sums
    p_im = jnp.concatenate([zero, jnp.cumsum(d_im, axis=1)], axis=1)
    d1, d2 = (k - r_eff) % n_r, (k - r_eff + n_cur) % n_r
    x_re = p_re[d1, size] - p_re[d1, r_eff] + p_re[d2, r_eff]
    x_im = p_im[d1, size] - p_im[d1, r_eff] + p_im[d2, r_eff]
    sa = jnp.sum(a_win, axis=1)
    fewer = _terms(sa[None], sq(a_win)[None], jnp.sum(b, 0), sq(b), x_re, x_im, inv_n)
    # M > N: reference s pairs current (s + k + r) mod M: rotation r is shift (k + r) mod M
    b_win = b[(i[:, None] + i[None, :]) % n_c] * (i < n_ref)[None, :, None]  # (K', S, 2)
    y_re, y_im = _cross(a[None], b_win)
    more = _terms(jnp.sum(a, 0), sq(a), jnp.sum(b_win, 1), sq(b_win), jnp.sum(y_re, 1), jnp.sum(y_im, 1), inv_n)
    kk = (k + r_eff) % n_c
    table = tuple(jnp.where(n_cur <= n_ref, f, m[kk]) for f, m in zip(fewer, more))
    # materialised: fused into the per-hypothesis gather, these few B^2 sums were redone B A times
    return jax.lax.optimization_barrier(table)


UNROLLED_SLOTS = 64  # beyond, one reduction: an unrolled sum of 10,000 slots took 17 s to trace (a refusal's wait)


def _in_order(x: Array) -> Array:
    """Sum over axis 1, one slot after another (the order of XLA's CPU reductions over the short slot axis);
    beyond `UNROLLED_SLOTS` slots one `jnp.sum` (the last bits may differ from the direct table's there)."""
    if x.shape[1] > UNROLLED_SLOTS:
        return jnp.sum(x, 1)
    total = x[:, 0]
    for s in range(1, x.shape[1]):
        total = total + x[:, s]
    return total


def best_rotated(
    ref_v: BlobVectors,
    ref_valid: BlobFlags,
    cur_v: CurrentVectors,
    cur_valid: CurrentFlags,
    alphas: Hypotheses,
    offsets: Array,
    pairs: tuple[Array, Array, Array, Array],
    n: Array,
) -> tuple[Point, Scalar, Scalar, tuple[Array, Array, Array]]:
    """The first minimum of var over shifts x hypotheses, hypothesis a pairing the list rotated to
    start at offsets[a] (`delv.match_arrangement`'s search without a compass): (p, alpha, var,
    (ref_row, cur_row, pair_ok_row) of the winner). `pairs` is `pairing.shift_pairs`'s output."""
    ref_idx, cur_idx, pair_ok, shift_ok = pairs
    const, z_re, z_im = (t[offsets].T for t in rotation_table(ref_v, ref_valid, cur_v, cur_valid))  # (H, A)
    cos, sin = jnp.cos(alphas), jnp.sin(alphas)
    var = const - 2.0 * (cos[None, :] * z_re - sin[None, :] * z_im)
    var = jnp.where(shift_ok[:, None], jnp.where(n > 1, var, 0.0), jnp.inf).reshape(-1)  # n <= 1: every var is 0
    _, cand = jax.lax.top_k(-jnp.where(jnp.isnan(var), jnp.inf, var), min(CANDIDATES, var.shape[0]))
    h, hyp = cand // alphas.shape[0], cand % alphas.shape[0]
    m = jnp.maximum(jnp.sum(cur_valid), 1)
    ref_row = ref_idx[h]
    cur_row = jnp.minimum((cur_idx[h] + offsets[hyp][:, None]) % m, cur_valid.shape[0] - 1)
    # rescored exactly as `delv.pairing_table` scores an entry (the same operations, in the same order)
    w = pair_ok[h].astype(ref_v.dtype)[..., None]  # (C, S, 1)
    inv_n = 1.0 / jnp.maximum(n, 1).astype(ref_v.dtype)
    a = ref_v[ref_row] * w
    b = cur_v[cur_row] * w
    a_mean = _in_order(a) * inv_n
    b_mean = _in_order(b) * inv_n
    a_c = (a - a_mean[:, None]) * w
    b_c = (b - b_mean[:, None]) * w
    const = _in_order(jnp.sum(a_c * a_c + b_c * b_c, axis=2))
    z_re = _in_order(a_c[..., 0] * b_c[..., 0] + a_c[..., 1] * b_c[..., 1])
    z_im = _in_order(a_c[..., 0] * b_c[..., 1] - a_c[..., 1] * b_c[..., 0])
    exact = const - 2.0 * (cos[hyp] * z_re - sin[hyp] * z_im)
    exact = jnp.where(shift_ok[h], exact, jnp.inf)
    key = jnp.where(jnp.isnan(exact), jnp.inf, exact)
    best = jnp.argmin(jnp.where(key <= jnp.min(key), cand, var.shape[0]))  # the first minimum, row-major
    alpha = alphas[hyp[best]]
    p = a_mean[best] - rotate(b_mean[best], alpha)
    return p, alpha, exact[best], (ref_row[best], cur_row[best], pair_ok[h[best]])
