"""A mushroom-body familiarity model (Ardin et al. 2016; docs/familiarity.md §2.3), non-spiking: the
view's pixels, min-max normalised, are the projection neurons (PNs); every Kenyon cell (KC) sums
`pn_per_kc` random PNs with weight 1 / `pn_per_kc`; the `n_active` most driven KCs fire (an exact
top-k: a binary, sparse code); one extrinsic neuron (MBON) sums the KC -> MBON weights of the firing
KCs. Learning a route image is one-shot depression: the weights of its firing KCs become 0. The
unfamiliarity of a view is the share of its firing KCs whose weight is still 1 (0: seen before).

The wiring is uniform random k-of-N from a `jax.random` key (InvertPy's generator makes 2-PN KCs in
lexicographic order, docs/familiarity.md §2.3); there is no leak or eligibility trace (a stateless
read-out, InvertSy's route-following setting).
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from .base import FamiliarityModel


def kc_drive(pn: Array, wiring: Array) -> Array:
    """(..., K): the mean of every KC's PNs, pn (..., N), wiring (K, k). One gather of all K KCs per
    fan-in slot, summed in a `fori_loop`: 7x faster on a CPU than one gather of (..., K, k) and its mean
    (3.4 against 25 ms for 61 views, 20 000 KCs of 10 PNs)."""
    columns = wiring.T  # (k, K)
    flat = pn.reshape(-1, pn.shape[-1])

    def add(i, acc):
        return acc + jnp.take(flat, columns[i], axis=1)

    total = jax.lax.fori_loop(0, columns.shape[0], add, jnp.zeros((flat.shape[0], columns.shape[1]), pn.dtype))
    return (total / columns.shape[0]).reshape(*pn.shape[:-1], columns.shape[1])


class MushroomBody(FamiliarityModel):
    """wiring: (K, pn_per_kc) PN indices of every KC; kc_weights: (K,) KC -> MBON weights (1 untrained);
    n_active: the KCs that fire for a view."""

    wiring: Array
    kc_weights: Array
    n_active: int = eqx.field(static=True, default=200)

    def firing(self, views: ArrayLike) -> Array:
        """(..., n_active) the indices of the KCs that fire for images (..., H, W): the `n_active` most driven
        (an exact top-k, ties to the lower index)."""
        x = jnp.asarray(views, jnp.float32).reshape(*views.shape[:-2], -1)
        lo, hi = jnp.min(x, -1, keepdims=True), jnp.max(x, -1, keepdims=True)
        pn = (x - lo) / jnp.where(hi > lo, hi - lo, 1.0)
        return jax.lax.top_k(kc_drive(pn, self.wiring), self.n_active)[1]

    def kc_code(self, views: ArrayLike) -> Array:
        """(..., K) binary code of images (..., H, W): 1 for the KCs that fire (`firing`)."""
        top = self.firing(views)
        code = jnp.zeros((*top.shape[:-1], self.wiring.shape[0]), jnp.float32)
        return jnp.put_along_axis(code, top, 1.0, axis=-1, inplace=False)

    def train(self, views: ArrayLike, masks: ArrayLike | None = None) -> MushroomBody:
        """Depress, image by image, the weights of the firing KCs (the order does not matter)."""
        fired = jnp.max(self.kc_code(views), 0)
        return eqx.tree_at(lambda m: m.kc_weights, self, self.kc_weights * (1.0 - fired))

    def unfamiliarity(self, views: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None) -> Array:
        # the firing KCs' weights summed: the code's product with the weights without making the (R, K) code
        # (the same float32: sums of 0s and 1s are exact; 1440 candidates 337 -> 290 ms)
        return jnp.sum(self.kc_weights[self.firing(views)], -1) / self.n_active


def mushroom_body(
    shape: tuple[int, int], key: ArrayLike, n_kc: int = 20000, pn_per_kc: int = 10, n_active: int = 200
) -> MushroomBody:
    """An untrained `MushroomBody` for images of `shape` (H, W): `n_kc` KCs, each wired to `pn_per_kc`
    distinct PNs drawn uniformly from `key`, `n_active` firing (Ardin et al. 2016: 20 000 KCs, 10 PNs
    each, about 1 % active)."""
    n = int(shape[0] * shape[1])
    keys = jax.random.split(key, n_kc)
    wiring = jax.vmap(lambda k: jax.random.choice(k, n, (pn_per_kc,), replace=False))(keys)
    return MushroomBody(wiring=wiring.astype(jnp.int32), kc_weights=jnp.ones(n_kc, jnp.float32), n_active=n_active)
