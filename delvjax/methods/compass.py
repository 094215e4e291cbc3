"""Heading sources: the (noisy) compass and the visual compass (Labrosse 2006, Zeil 2003; docs/model.md §4.4)."""

from __future__ import annotations

from typing import Callable

import jax
import jax.numpy as jnp
from jax import lax
from jax import Array

from ..config import Config
from ..search import first_argmin
from ..geometry import TWO_PI, wrap
from ..sensing import UnitMove


def visual_compass(home_gray: Array, view_gray: Array) -> Array:
    """Estimate h - alpha_r from two gray ring images (docs/model.md §4.4).

    The pixel shift k minimising sum_j |C[j + k] - S[j]| (first minimum) gives -2 pi k / n.
    """
    n = home_gray.shape[-1]
    doubled = jnp.concatenate([view_gray, view_gray])

    def cost(k: Array) -> Array:
        return jnp.sum(jnp.abs(lax.dynamic_slice(doubled, (k,), (n,)) - home_gray))

    # A scan over the n shifts (each step vectorised over whatever is vmapped outside)
    # is 5x faster on CPU than materialising the (n, n) circulant by a gather.
    costs = lax.map(cost, jnp.arange(n))
    return wrap(-TWO_PI * first_argmin(costs) / n)


def heading_estimate(home: UnitMove, view: UnitMove, source: str) -> Array:
    """The agent's estimate of h - alpha_r at the end of `view`: compass reading or visual compass."""
    if source == "compass":
        return view.compass
    if source == "visual":
        return visual_compass(home.start.gray, view.end.gray)
    raise ValueError(f"heading source must be 'compass' or 'visual', got {source!r}")


def with_heading_source(fn: Callable, source: str) -> Callable:
    """Turn `fn(home, view, config, heading)` into a method `direction(home, view, config)`."""

    def direction(home: UnitMove, view: UnitMove, config: Config) -> tuple[Array, Array]:
        return fn(home, view, config, heading_estimate(home, view, source))

    direction.__name__ = f"{fn.__module__.rsplit('.', 1)[-1]}_{source}"
    direction.__doc__ = f"{fn.__doc__}\n\nHeading source: {source}."
    return direction


def visual_compass_errors(env, points: Array, headings: Array, config: Config) -> Array:
    """Heading error of the visual compass at each point (docs/model.md §4.4; thesis §5.3.2), (P,) rad.

    The home image is taken at home with heading alpha_r, the current one at `points` with
    `headings`; error = wrap(estimate - (h - alpha_r)). Rendering is noise-free.
    """
    return _visual_compass_errors(env.arrays(), jnp.asarray(points, jnp.float32), jnp.asarray(headings, jnp.float32),
                                  config)


@jax.jit
def _visual_compass_errors(env, points: Array, headings: Array, config: Config) -> Array:
    from ..sensing import render  # sensing imports this module's users: imported late

    visible = jnp.ones(env.landmarks.shape[0], bool)
    _, home_gray = render(env, visible, env.home, jnp.asarray(config.alpha_r, jnp.float32), config)

    def one(point, heading):
        _, gray = render(env, visible, point, heading, config)
        return wrap(visual_compass(home_gray, gray) - (heading - config.alpha_r))

    return jax.vmap(one)(points, headings)
