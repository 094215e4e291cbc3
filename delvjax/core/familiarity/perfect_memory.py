"""Perfect memory (docs/familiarity.md §2.1; bob_robotics' PerfectMemory): every route image is kept;
a candidate view's unfamiliarity is its least difference from any (active) route image (`ridf.KINDS`).

The heading of a scan is that of the best-matching image (`select="best"`, BoB's
BestMatchingSnapshot), or the circular mean of the best turns for the `n_best` best-matching images,
weighted by 1 - difference / 255 (`select="weighted"`, BoB's WeightSnapshotsDynamic). A window
(`window_ahead`, `window_behind` images about the last best match, BoB's PerfectMemoryWindow::Fixed)
is carried by the route rollouts (`core/familiarity/following.py`).
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..search import first_argmin
from .base import Choice, FamiliarityModel
from .ridf import difference, unmasked_table

BYTE = 255.0  # BoB reports a best difference / 255 (its images are 8-bit)


class PerfectMemory(FamiliarityModel):
    """kind: "abs", "rms" or "corr" (`ridf.difference`); select: "best" or "weighted"; n_best: images
    averaged by "weighted"; window_ahead / window_behind: route images searched ahead of / behind the
    last best match in a rollout (0 ahead: the whole route). images: (S, H, W), masks: (S, H, W) or None (every pixel) once
    trained."""

    kind: str = eqx.field(static=True, default="abs")
    select: str = eqx.field(static=True, default="best")
    n_best: int = eqx.field(static=True, default=3)
    window_ahead: int = eqx.field(static=True, default=0)
    window_behind: int = eqx.field(static=True, default=0)
    images: Array | None = None
    masks: Array | None = None

    def train(self, views: ArrayLike, masks: ArrayLike | None = None) -> PerfectMemory:
        views = jnp.asarray(views, jnp.float32)
        masks = None if masks is None else jnp.broadcast_to(jnp.asarray(masks, bool), views.shape)
        return eqx.tree_at(lambda m: (m.images, m.masks), self, (views, masks), is_leaf=lambda x: x is None)

    def n_images(self) -> int:
        return 0 if self.images is None else self.images.shape[0]

    def table(self, views: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None) -> Array:
        """(S, R): the difference of every candidate view (R, H, W) from every route image; inactive
        images are +inf. Without masks on either side, `ridf.unmasked_table` (a flat pixel axis)."""
        views = jnp.asarray(views, jnp.float32)
        if masks is None and self.masks is None:
            t = unmasked_table(views, self.images, self.kind)
        else:
            keep = jnp.ones(views.shape, bool) if masks is None else jnp.asarray(masks, bool)
            mine = jnp.ones(self.images.shape, bool) if self.masks is None else self.masks

            def one(image: ArrayLike, mask: ArrayLike) -> Array:
                return difference(views, image[None], keep & mask[None], self.kind)

            t = jax.vmap(one)(self.images, mine)
        return t if active is None else jnp.where(active[:, None], t, jnp.inf)

    def unfamiliarity(self, views: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None) -> Array:
        t = self.table(views, masks, active)
        return jnp.min(jnp.where(jnp.isnan(t), jnp.inf, t), 0)

    def choose(
        self, views: ArrayLike, turns: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None
    ) -> Choice:
        t = self.table(views, masks, active)
        t = jnp.where(jnp.isnan(t), jnp.inf, t)
        best_col = first_argmin(t)  # (S,) each image's best candidate
        lowest = jnp.min(t, 1)  # (S,)
        curve = jnp.min(t, 0)
        s = first_argmin(lowest)
        if self.select == "best":
            return Choice(turn=turns[best_col[s]], value=lowest[s] / BYTE, snapshot=s.astype(jnp.int32), curve=curve)
        order = jnp.argsort(lowest, stable=True)[: self.n_best]  # ties: the earlier image first
        weight = 1.0 - lowest[order] / BYTE
        a = turns[best_col[order]]
        turn = jnp.arctan2(jnp.sum(weight * jnp.sin(a)), jnp.sum(weight * jnp.cos(a)))
        return Choice(turn=turn, value=lowest[s] / BYTE, snapshot=s.astype(jnp.int32), curve=curve)


def window(n_images: int, pointer: ArrayLike, ahead: int, behind: int) -> Array:
    """(S,) the route images a fixed window searches (BoB's clampWindow): end = min(pointer + ahead, S),
    start = max(end - ahead - behind, 0); pointer < 0 (unset) or ahead 0: every image."""
    end = jnp.minimum(pointer + ahead, n_images)
    start = jnp.maximum(end - ahead - behind, 0)
    i = jnp.arange(n_images)
    inside = (i >= start) & (i < end)
    return jnp.where((pointer < 0) | (ahead <= 0), jnp.ones(n_images, bool), inside)
