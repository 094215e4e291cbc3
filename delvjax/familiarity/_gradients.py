"""Gradients of a view's unfamiliarity (docs/familiarity.md §2.4): with respect to the view and to the
model's memory or weights, by `jax.grad` of the model's own `unfamiliarity` (one program)."""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..core.familiarity.base import FamiliarityModel
from ._models import checked_images


def unfamiliarity_grad(model: FamiliarityModel, view) -> tuple[float, np.ndarray, FamiliarityModel]:
    """(unfamiliarity, d/d view (H, W), d/d model: a model-shaped pytree of gradients, None where a field
    is not a float array) of one view (H, W, 8-bit scale) under a trained `model`. The mushroom body's
    code is piecewise constant in the view: its view gradient is zero (docs/familiarity.md §2.3)."""
    v = jnp.asarray(checked_images([view], "view")[0])

    @eqx.filter_jit
    @eqx.filter_value_and_grad
    def value(pair):
        m, x = pair
        return m.unfamiliarity(x[None])[0]

    out, (d_model, d_view) = value((model, v))
    return float(out), np.asarray(d_view), jax.tree.map(np.asarray, d_model)
