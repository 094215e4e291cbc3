"""Analytic homing fields and their equilibria (thesis §3.3.2), found with optimistix.

With exact landmark positions the ALV homing vector is the smooth field
H(x) = sum_i u(L_i - x) - sum_i u(L_i - x_o) (Eqs 3.9-3.12) = -grad U(x) (Eq 3.13), and
the DELV vector with continuous distances is H(x) = sum_i [(L_i - x) - (L_i - x_o)] =
N (x_o - x) (Eqs 3.15-3.16). Their zeros are the points an agent following them would
settle at; the convergence argument says home is the minimum of U. `equilibria` runs
optimistix's Newton root finder from many starts at once (vmapped) to check that.
"""

from __future__ import annotations

from collections.abc import Callable

import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from .scene import Env


def alv_field(x: Array, env: Env) -> Array:
    """Eq 3.12 with exact geometry: sum u(L_i - x) - sum u(L_i - x_o), (2,)."""

    def unit_sum(p):
        v = env.landmarks[:, :2] - p
        u = v / jnp.linalg.norm(v, axis=-1, keepdims=True)
        return jnp.sum(jnp.where(env.valid[:, None], u, 0.0), axis=0)

    return unit_sum(x) - unit_sum(env.home)


def delv_field(x: Array, env: Env) -> Array:
    """Eq 3.15 with exact distances: sum (L_i - x) - sum (L_i - x_o) = N (x_o - x), (2,)."""
    v = (env.landmarks[:, :2] - x) - (env.landmarks[:, :2] - env.home)
    return jnp.sum(jnp.where(env.valid[:, None], v, 0.0), axis=0)


FIELDS: dict[str, Callable[[Array, Env], Array]] = {"alv": alv_field, "delv": delv_field}


def equilibria(
    env: Env, starts: ArrayLike, field: str = "alv", rtol: float = 1e-6, atol: float = 1e-4, max_steps: int = 64
) -> tuple[Array, Array]:
    """Zeros of a homing field from every start (vmapped optimistix Newton): (points (S, 2), converged (S,))."""
    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    fn = FIELDS[field]
    solver = optx.Newton(rtol=rtol, atol=atol)

    def one(y0):
        sol = optx.root_find(lambda x, e: fn(x, e), solver, y0, args=env, max_steps=max_steps, throw=False)
        return sol.value, sol.result == optx.RESULTS.successful

    return jax.jit(jax.vmap(one))(jnp.asarray(starts, jnp.float32))
