"""Soft cyclic order of landmark slots and the pairing of every cyclic shift as weight matrices
(docs/differentiable.md "A continuous loss").

The hard methods pair two bearing-sorted lists of the blobs they see under every cyclic shift
(thesis §3.2.4, `pairing.shift_pairs`). The soft views keep one slot per landmark with a
visibility weight w (`soft.sensing`), so the lists become places counted by visibility. Slot
l's place is

    rank_l = sum_{m != l} w_m sigmoid((b_l - b_m) / s),   b in [0, 2 pi),

the visible slots before it, in a cycle of n = sum_m w_m places; its share of place i is the hat
max(0, 1 - |rank_l - i|_n) (cyclic distance modulo n). As in `shift_pairs`, the shorter list's
place j meets the longer list's place (j + k) mod n_long under shift k (place j counting
min(1, n_short - j), shift k counting min(1, n_long - k)), so reference slot m and current slot l
pair with weight C_k[m, l] = sum_{j,i} P_short[., j] hat((j + k - i) mod n_long) P_long[., i];
which list is the shorter is blended (`shift_weights`).

With weights 0 or 1 and bearings farther apart than s, the places are the hard lists' indices and
C_k their pairing. Every quantity is continuous in the weights and bearings: a landmark fading
out leaves the cycle gradually, a hidden one crossing behind another counts for nothing, and a
slot crossing bearing 0 turns every place by one, which the shifts absorb.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

ORDER_WIDTH = 1e-3  # rad: s, how close two bearings are before their places blend (docs/differentiable.md)
BLEND_PLACES = 0.05  # places: how close two lists' lengths are before the shorter-list choice blends


def _hat(x: Array, n: Array) -> Array:
    """max(0, 1 - |x|) with x taken cyclically modulo n, in [-n/2, n/2)."""
    return jnp.maximum(0.0, 1.0 - jnp.abs(jnp.mod(x + n / 2, n) - n / 2))


def soft_places(bearing: Array, weight: Array, valid: Array, width: float | Array = ORDER_WIDTH) -> tuple[Array, Array]:
    """(P (L slots, L places): slot l's share of place i, n: the number of places sum w)."""
    size = bearing.shape[0]
    w = jnp.where(valid, weight, 0.0)
    n = jnp.sum(w)
    others = ~jnp.eye(size, dtype=bool)
    rank = jnp.sum(
        jnp.where(others, w[None, :] * jax.nn.sigmoid((bearing[:, None] - bearing[None, :]) / width), 0.0), 1
    )
    place = jnp.arange(size, dtype=jnp.float32)
    return jnp.where(valid[:, None], _hat(rank[:, None] - place[None, :], jnp.maximum(n, 1e-6)), 0.0), n


def _pairing(p_short: Array, n_short: Array, p_long: Array, n_long: Array) -> Array:
    """(K, short slot, long slot): short place j meets long place (j + k) mod n_long."""
    place = jnp.arange(p_long.shape[1], dtype=jnp.float32)
    k, j, i = place[:, None, None], place[None, :, None], place[None, None, :]
    q = _hat(j + k - i, jnp.maximum(n_long, 1e-6)) * jnp.clip(n_short - j, 0.0, 1.0) * jnp.clip(n_long - i, 0.0, 1.0)
    return jnp.einsum("sj,kji,gi->ksg", p_short, q, p_long)


def shift_weights(p_ref: Array, n_ref: Array, p_cur: Array, n_cur: Array) -> tuple[Array, Array]:
    """(C (2K, L_ref, L_cur): how much reference slot m pairs current slot l under each candidate
    shift, how much each candidate counts (2K,) in [0, 1]); K = L places.

    The first K candidates take the current list as the shorter, the last K the reference list
    (`shift_pairs` chooses by n_cur <= n_ref). Here the choice is a blend, sigmoid((n_ref -
    n_cur) / BLEND_PLACES), on the candidates' counts: with whole counts that differ it is the hard
    choice, with equal counts both halves are the same pairings (weighted 1/2 each, which leaves a
    softmin unchanged), and in between nothing jumps."""
    cur_short = jnp.swapaxes(_pairing(p_cur, n_cur, p_ref, n_ref), 1, 2)
    ref_short = _pairing(p_ref, n_ref, p_cur, n_cur)
    shifts = jnp.arange(p_ref.shape[1], dtype=jnp.float32)
    count = jnp.clip(jnp.maximum(n_ref, n_cur) - shifts, 0.0, 1.0)
    b = jax.nn.sigmoid((n_ref - n_cur) / BLEND_PLACES)
    return jnp.concatenate([cur_short, ref_short]), jnp.concatenate([count * b, count * (1.0 - b)])
