"""What every familiarity model is (docs/familiarity.md §2): an equinox module that owns its settings
and, once trained, its memory of a route; `train` returns the trained copy (pure), `unfamiliarity`
scores candidate views (lower is more familiar, as BoB's differences and InfoMax's decision), and
`choose` turns the scores of a scan into a heading."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..search import first_argmin


class Choice(eqx.Module):
    """turn: the chosen turn, rad; value: its unfamiliarity; snapshot: the best-matching route image
    (-1 where the model keeps no images); curve: (R,) the unfamiliarity of every candidate."""

    turn: Array
    value: Array
    snapshot: Array
    curve: Array


class FamiliarityModel(eqx.Module):
    """The familiarity-model protocol: `train(views, masks)` -> trained copy; `unfamiliarity(views,
    masks, active)` (R, H, W) -> (R,); `choose(views, turns, masks, active)` -> `Choice`. `active`: (S,)
    the route images a windowed memory may match (None: all)."""

    def train(self, views: ArrayLike, masks: ArrayLike | None = None) -> FamiliarityModel:
        raise NotImplementedError

    def unfamiliarity(self, views: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None) -> Array:
        raise NotImplementedError

    def choose(
        self, views: ArrayLike, turns: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None
    ) -> Choice:
        """The first least unfamiliar candidate (BoB's rotaters take the first minimum)."""
        curve = self.unfamiliarity(views, masks, active)
        i = first_argmin(curve)
        return Choice(turn=turns[i], value=curve[i], snapshot=jnp.int32(-1), curve=curve)

    def n_images(self) -> int:
        """Route images a windowed memory indexes (0: the model keeps none)."""
        return 0
