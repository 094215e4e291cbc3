"""Gap-aware DELV arrangement matching: order-preserving cyclic pairings that may skip entries.

What: the search of `delv.match_arrangement` (thesis §3.2.4, Algorithm 3, Eqs 3.4-3.6: min
over pairings and alpha of var = sum |e_i - p|^2, e_i = V^R_i - Rot(alpha) V_j(i), p = mean e_i)
over a larger set of pairings.

Why: linear rotational matching pairs the n = min(N, M) entries of the smaller list with
n CONSECUTIVE (cyclic) entries of the larger list, starting at the smaller list's first
entry. The entries it leaves out of the larger list must therefore form one cyclic run
that falls at the smaller list's wrap point; one landmark occluded in the middle of a
view (M = N - 1 with the gap away from the wrap) cannot be matched. Here every
order-preserving cyclic pairing is searched: any n-subset of the larger list, kept in
its cyclic (bearing) order, paired with the smaller list under each of the n cyclic shifts.
With N == M (one subset: the whole list; same pairings and order) `match_arrangement`'s
result is returned as is: XLA may round the same arithmetic differently at the table's
shapes under vmap, so only that keeps it bit for bit equal, ties included.

Source: beyond the thesis; addresses the limitation the thesis names in §3.2.4 ("Since
we only consider linear rotational matching of landmark vectors, difference in the
number of objects observed may influence the performance in some cases").

Pairing rule: L = max(N, M). If M <= N the reference list is the larger one and current
j pairs reference c[(j + k) mod n], else reference i pairs current c[(i + k) mod n], for
a subset c_0 < ... < c_{n-1} of range(L) and a shift k < n (n = 0: one empty pairing,
var = 0, p = 0, as `match_arrangement` gives for N != M).

Enumeration and ties: the first minimum in (subset, shift, alpha) order, subsets in the
order of itertools.combinations(range(L), n) (lexicographic), then k ascending, then the
given alphas. With N == M this is k-major then alpha, as in `match_arrangement`.

Complexity: with B = max padded length, a static table per subset size c lists every
(subset of range(B), shift) row, padded to H = max_c C(B, c) max(c, 1) rows (6, 12, 30, 60
for B = 3..6; 5544 for B = 12); the table of c = n is picked at run time and rows with a
slot >= L are masked. Work and memory per point are O(H (B + A)) for A alphas, about
H / B times `match_arrangement` (10x for B = 6: H x A = 21600 floats for A = 360), plus
one `match_arrangement` for the N == M case.
"""

from __future__ import annotations

import functools
import itertools

import jax.numpy as jnp
import numpy as np
from jax import Array

from .delv import DELV, best_pairing, match_arrangement


@functools.lru_cache(maxsize=None)
def _hypotheses(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Static (subset, shift) tables over `size` slots, one per subset size c, in tie order.

    Table c lists the subsets of range(size) of size c lexicographically, each with k < max(c, 1),
    so for any L its rows with all slots < L follow combinations(range(L), c). Returns
    (big (size + 1, H, size): slot of the larger list paired with smaller slot s, i.e.
    subset[(s + k) mod c], 0 for s >= c; top (size + 1, H): largest slot, -1 for the empty
    subset, `size` on padding rows, which therefore never go live).
    """
    tables = [
        [
            ([subset[(s + k) % c] if s < c else 0 for s in range(size)], subset[-1] if c else -1)
            for subset in itertools.combinations(range(size), c)
            for k in range(max(c, 1))
        ]
        for c in range(size + 1)
    ]
    h = max(len(rows) for rows in tables)
    big = np.zeros((size + 1, h, size), np.int32)
    top = np.full((size + 1, h), size, np.int32)
    for c, rows in enumerate(tables):
        for r, (slots, last) in enumerate(rows):
            big[c, r], top[c, r] = slots, last
    return big, top


def match_arrangement_gapped(
    ref_v: Array, ref_valid: Array, cur_v: Array, cur_valid: Array, alphas: Array, offsets: Array | None = None
) -> tuple[Array, Array, Array, Array]:
    """Best order-preserving cyclic pairing (may skip entries of the larger list) and alpha.

    Same signature and outputs as `delv.match_arrangement`: (p (2,), alpha, var, n_pairs)
    with n_pairs = min(N, M); ref_v: (B, 2) home frame, cur_v: (B', 2) agent frame (valid
    entries first, in bearing order), alphas: (A,) radians. Where N == M, exactly
    `match_arrangement`'s result, with its `offsets` (docs/model.md §3.3). The subset search needs no
    offsets: it pairs every cyclic rotation of every subset, so where the current list starts only
    relabels its pairings (ties aside).
    """
    same = match_arrangement(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
    gapped = _search(ref_v, ref_valid, cur_v, cur_valid, alphas)
    equal = jnp.sum(ref_valid) == jnp.sum(cur_valid)
    return tuple(jnp.where(equal, x, y) for x, y in zip(same, gapped))


def _search(
    ref_v: Array, ref_valid: Array, cur_v: Array, cur_valid: Array, alphas: Array
) -> tuple[Array, Array, Array, Array]:
    """The table search of `match_arrangement_gapped`, for any N, M. var(alpha) per pairing
    from centred pair vectors a'_i, b'_i: sum |a'|^2 + |b'|^2 - 2 Re(e^{i alpha} sum conj(a') b')."""
    size = max(ref_valid.shape[0], cur_valid.shape[0])
    big_np, top_np = _hypotheses(size)
    n_ref, n_cur = jnp.sum(ref_valid), jnp.sum(cur_valid)
    n, n_big = jnp.minimum(n_ref, n_cur), jnp.maximum(n_ref, n_cur)
    big = jnp.asarray(big_np)[n]  # (H, S): the table of subsets of size n
    cur_fewer = n_cur <= n_ref  # then the reference list is the larger one
    s = jnp.arange(size)[None, :]
    ref_idx = jnp.minimum(jnp.where(cur_fewer, big, s), ref_valid.shape[0] - 1)
    cur_idx = jnp.minimum(jnp.where(cur_fewer, s, big), cur_valid.shape[0] - 1)
    pair_ok = jnp.broadcast_to(s < n, big.shape)
    hyp_ok = (jnp.asarray(top_np)[n] < n_big) & (n_big > 0)
    p, alpha, var = best_pairing(ref_v, cur_v, ref_idx, cur_idx, pair_ok, hyp_ok, n, alphas)
    return p, alpha, var, n


class DELVGap(DELV):
    """DELV (docs/model.md §3) with gap-aware matching (§3.5): the settings and heading source of
    `DELV`; only the arrangement search differs (`match_arrangement_gapped`)."""

    def match(
        self,
        ref_v: Array,
        ref_valid: Array,
        cur_v: Array,
        cur_valid: Array,
        alphas: Array,
        offsets: Array | None = None,
    ):
        return match_arrangement_gapped(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
