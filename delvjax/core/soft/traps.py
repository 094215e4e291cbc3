"""Trap points of a homing field (docs/differentiable.md "Trap points").

The soft homing vector H(x) (`soft.loss`) is continuous in the position x. Where the hard
method switches between two hypotheses whose vectors oppose, the softmin averages them and H
passes through zero: the hard field's sinks (false homes), saddles and sources are zeros of H.
They are found with optimistix's Newton root finder, vmapped over starts, and classified by the
Jacobian J = dH/dx at the zero: det J < 0 a saddle; det J > 0 and trace J < 0 a sink (the field
flows in), trace J > 0 a source. The solver is optimistix's Levenberg-Marquardt on H (a damped
Newton step): plain Newton overshoots where H is flat and left most starts on env1 at infinity.

H at x averages the soft vectors of unit moves ending at x along FIELD_HEADINGS headings (the
field of a rollout depends on the heading it arrives with; the average is the heading-free
field), with the vector map's noise streams of `key`.

Limit cycles: a rollout moves x -> S(x) = x + d H(x) / |H(x)|. Period-2 orbits of S (zeros of
S(S(x)) - x, `two_cycles`) are where timed-out rollouts step back and forth across a line where the
field flips.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import TWO_PI, rotate
from ..kernel import map_poses
from ..maps import stream_keys
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensor import Sensor
from .methods import soft_direction
from .sensing import soft_home, soft_observe

FIELD_HEADINGS = 8
KINDS = ("sink", "saddle", "source", "degenerate")


def solver() -> eqx.Module:
    """Damped Newton (Newton overshoots where the field is flat), optimistix's LevenbergMarquardt. Built at
    each trace: constructing one at import starts JAX's backend (which must wait for jax.distributed), and
    one instance shared by traces of other shapes made jit run a program compiled for another shape."""
    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    return optx.LevenbergMarquardt(rtol=1e-6, atol=1e-6)


def soft_vector(
    x: Array, env: Env, sensor: Sensor, method: HomingMethod, key: Array, tau: Array, sharpness: Array
) -> Array:
    """H(x): the mean soft homing vector (world frame) over FIELD_HEADINGS arrival headings, (2,)."""
    k_home, k_views, _ = stream_keys(key)
    home = soft_home(env, k_home, sensor, sharpness)
    visible = jnp.ones(env.landmarks.shape[0], bool)

    def one(heading):
        poses = map_poses(x, heading, k_views, 0, sensor)
        vec, _, valid = soft_direction(method, home, soft_observe(env, visible, poses, sensor, sharpness), tau)
        return valid * rotate(vec, poses.heading_end), valid  # validity in [0, 1] weighs each heading

    vecs, valid = jax.vmap(one)(TWO_PI * jnp.arange(FIELD_HEADINGS) / FIELD_HEADINGS)
    return jnp.sum(vecs, axis=0) / jnp.maximum(jnp.sum(valid), 1.0)


def classify(jac: Array) -> Array:
    """Index into KINDS of a zero from its 2 x 2 Jacobian."""
    det = jnp.linalg.det(jac)
    trace = jnp.trace(jac)
    return jnp.where(det < 0, 1, jnp.where((det > 0) & (trace < 0), 0, jnp.where((det > 0) & (trace > 0), 2, 3)))


@jax.jit
def field_zeros(
    env: Env, starts: Array, sensor: Sensor, method: HomingMethod, key: Array, tau: Array, sharpness: Array
) -> tuple[Array, Array, Array, Array, Array]:
    """Root finding from every start (damped Newton, Levenberg-Marquardt, on H): (points (S, 2),
    solver converged (S,), kind (S,) into KINDS, Jacobian (S, 2, 2), residual |H| at the point
    relative to the median |H| at the starts (S,)). A point with a residual that is not small is a
    minimum of |H| but no zero: a discontinuity of the field (e.g. a blob that appears)."""
    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    field = lambda x, _: soft_vector(x, env, sensor, method, key, tau, sharpness)  # noqa: E731

    def one(y0):
        sol = optx.root_find(field, solver(), y0, max_steps=64, throw=False)
        jac = jax.jacfwd(lambda x: field(x, None))(sol.value)
        return (
            sol.value,
            sol.result == optx.RESULTS.successful,
            classify(jac),
            jac,
            jnp.linalg.norm(field(sol.value, None)),
        )

    zeros, ok, kind, jac, residual = jax.vmap(one)(starts)
    scale = jnp.median(jax.vmap(lambda x: jnp.linalg.norm(field(x, None)))(starts))
    return zeros, ok, kind, jac, residual / jnp.maximum(scale, 1e-12)


@jax.jit
def two_cycles(
    env: Env, starts: Array, sensor: Sensor, method: HomingMethod, key: Array, tau: Array, sharpness: Array
) -> tuple[Array, Array, Array]:
    """Period-2 orbits of the rollout map x -> x + d H(x) / |H(x)| (a unit step along the soft field):
    zeros of S(S(x)) - x, root-found from every start. Returns (x (S, 2), its partner S(x) (S, 2),
    residual |S(S(x)) - x| in cm (S,)). An agent on such an orbit steps back and forth between x and
    S(x) across a line where the field flips: the limit cycles of the timed-out rollouts."""

    import optimistix as optx  # optimistix: loaded only when a solver runs (not by a vector map)

    def step(x):
        h = soft_vector(x, env, sensor, method, key, tau, sharpness)
        return x + sensor.d * h / jnp.maximum(jnp.linalg.norm(h), 1e-12)

    def one(y0):
        sol = optx.root_find(lambda x, _: step(step(x)) - x, solver(), y0, max_steps=64, throw=False)
        return sol.value, step(sol.value), jnp.linalg.norm(step(step(sol.value)) - sol.value)

    return jax.vmap(one)(starts)
