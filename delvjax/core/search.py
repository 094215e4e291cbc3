"""Exhaustive-search helpers with the model's tie rule: the first minimum wins (docs/model.md §3.4)."""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array


def first_argmin(x: Array, axis: int = -1) -> Array:
    """Index of the first minimum along `axis` (NaN counts as +inf), like `jnp.argmin`.

    Written as min, compare, min: XLA's CPU argmin is a variadic reduction that does not
    vectorise and is ~2.5x slower on the DELV hypothesis grid.
    """
    x = jnp.where(jnp.isnan(x), jnp.inf, x)
    m = jnp.min(x, axis=axis, keepdims=True)
    idx = jnp.arange(x.shape[axis]).reshape([-1 if a == axis % x.ndim else 1 for a in range(x.ndim)])
    first = jnp.min(jnp.where(x <= m, idx, x.shape[axis]), axis=axis)
    return jnp.minimum(first, x.shape[axis] - 1)
