"""InfoMax (Baddeley et al. 2012; docs/familiarity.md §2.2; bob_robotics' InfoMax): a square-ish
network W (M x N, N pixels) trained once over the route, one image a step, by the natural-gradient
infomax rule

    u = W x,  y = tanh(u),  W <- W + lambda (I - (y + u) u^T) W,

with lambda = eta / (N M) (BoB since 2023; `rate_divisor="hidden"`: eta / M, the rule BoB's stored test
data were made with). The unfamiliarity of a view is sum_j |u_j| (BoB's decision function; lower is more
familiar). Inputs are the pixels / 255 in row-major order (`normalise="none"`) or their z-scores.
Training is one `lax.scan` over the route.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from .base import FamiliarityModel

BYTE = 255.0


def initial_weights(key: ArrayLike, n_inputs: int, n_hidden: int) -> Array:
    """(M, N) standard normal weights, every input's column centred and scaled to RMS 1 over the hidden
    units (as BoB's `generateInitialWeights`; its own generator is libstdc++'s, ours `jax.random`)."""
    w = jax.random.normal(key, (n_hidden, n_inputs), dtype=jnp.float32)
    w = w - jnp.mean(w, 0, keepdims=True)
    return w / jnp.sqrt(jnp.mean(w * w, 0, keepdims=True))


class InfoMax(FamiliarityModel):
    """learning_rate: eta (BoB's default 0.97 with lambda = eta / (N M)); rate_divisor: "inputs_hidden"
    (N M) or "hidden" (M); normalise: "none" (pixels / 255) or "zscore"; weights: (M, N), from
    `initial_weights` before training."""

    weights: Array
    learning_rate: Array | float = 0.97
    rate_divisor: str = eqx.field(static=True, default="inputs_hidden")
    normalise: str = eqx.field(static=True, default="none")

    def inputs(self, views: ArrayLike) -> Array:
        """(..., N) the network's input of images (..., H, W)."""
        x = jnp.asarray(views, jnp.float32).reshape(*views.shape[:-2], -1)
        if self.normalise == "zscore":
            m = jnp.mean(x, -1, keepdims=True)
            return (x - m) / jnp.sqrt(jnp.mean((x - m) ** 2, -1, keepdims=True))
        return x / BYTE

    def rate(self) -> Array:
        m, n = self.weights.shape
        return jnp.asarray(self.learning_rate, jnp.float32) / (m * n if self.rate_divisor == "inputs_hidden" else m)

    def train(self, views: ArrayLike, masks: ArrayLike | None = None) -> InfoMax:
        """One infomax step per route image, in order (masks are ignored, as BoB does)."""
        lam = self.rate()

        def step(w: ArrayLike, x: ArrayLike) -> tuple[Array, None]:
            u = w @ x
            y = jnp.tanh(u)
            return w + lam * (w - jnp.outer(y + u, u @ w)), None  # (I - (y + u) u^T) W

        w, _ = jax.lax.scan(step, self.weights, self.inputs(views))
        return eqx.tree_at(lambda m: m.weights, self, w)

    def unfamiliarity(self, views: ArrayLike, masks: ArrayLike | None = None, active: ArrayLike | None = None) -> Array:
        return jnp.sum(jnp.abs(self.inputs(views) @ self.weights.T), -1)


def infomax(shape: tuple[int, int], key: ArrayLike, n_hidden: int | None = None, **settings) -> InfoMax:
    """An untrained `InfoMax` for images of `shape` (H, W): N = H W inputs, `n_hidden` (default N) units."""
    n = int(shape[0] * shape[1])
    return InfoMax(weights=initial_weights(key, n, n if n_hidden is None else int(n_hidden)), **settings)
