"""Cyclic-shift pairing of two sorted, padded bearing lists (docs/model.md §3.4, used by DELV and ACV)."""

from __future__ import annotations

import jax.numpy as jnp

from ..types import BlobFlags, CurrentFlags, Pairing, PairingFlags, RowFlags


def shift_pairs(ref_valid: BlobFlags, cur_valid: CurrentFlags) -> tuple[Pairing, Pairing, PairingFlags, RowFlags]:
    """Index arrays of every cyclic shift k (thesis §3.2.4, Algorithm 3).

    N reference, M current entries (valid first), n = min(N, M) pairs and max(N, M)
    shifts. If M <= N current j pairs reference (j + k) mod N, else reference i pairs
    current (i + k) mod M. Returns (ref_idx (K, S), cur_idx (K, S), pair_ok (K, S),
    shift_ok (K,)) with K = S = max(len(ref_valid), len(cur_valid)).
    """
    size = max(ref_valid.shape[0], cur_valid.shape[0])
    n_ref, n_cur = jnp.sum(ref_valid), jnp.sum(cur_valid)
    k = jnp.arange(size)[:, None]
    s = jnp.arange(size)[None, :]
    cur_fewer = n_cur <= n_ref
    ref_idx = jnp.where(cur_fewer, (s + k) % jnp.maximum(n_ref, 1), s)
    cur_idx = jnp.where(cur_fewer, s, (s + k) % jnp.maximum(n_cur, 1))
    pair_ok = jnp.broadcast_to(s < jnp.minimum(n_ref, n_cur), (size, size))
    shift_ok = jnp.arange(size) < jnp.maximum(n_ref, n_cur)
    ref_idx = jnp.minimum(ref_idx, ref_valid.shape[0] - 1)
    cur_idx = jnp.minimum(cur_idx, cur_valid.shape[0] - 1)
    return ref_idx, cur_idx, pair_ok, shift_ok
