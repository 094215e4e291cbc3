"""Python API of the differentiable path (docs/differentiable.md): homing loss and its gradient
with respect to the world (landmarks, home), the agent (d, the quantization scale) and the noise.

    delvjax.homing_loss("env1", "delv", tau=0.01)            -> a JAX scalar (lower is better)
    value, grads = delvjax.homing_loss_grad("env1", "delv")   -> grads["landmarks"] (N, 3), ...

`homing_loss` is a JAX function: `jax.grad`, `jax.jit` and `jax.vmap` of it work with respect to
an Env's landmarks and home, d, scale and the noise options (docs/differentiable.md).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import NamedTuple

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..core.batching import traced_floats
from ..core.checks import is_traced, positive
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.grid import Grid
from ..core.maps import CLEARANCE, SPACING, grid_included, grid_points, random_headings, vector_map
from ..core.methods import HomingMethod
from ..core.scene import Env
from ..core.soft.loss import soft_included, soft_loss
from ..core.soft.methods import check_differentiable
from ..core.soft.sensing import EDGE_CM, VISIBILITY_WIDTH
from ..core.types import Real
from ..evaluate._vector_map import check_grid, scene_request
from ..options._limits import MAX_POINTS, check_size, grid_count
from ..options._setup import NOISE_FIELDS_DEG, NOISE_FIELDS_FRACTION

TAU = 0.01  # default softmin temperature (docs/differentiable.md)
NOISE_NAMES = {
    **{f: name for name, f in NOISE_FIELDS_DEG.items()},
    **{f: name for name, f in NOISE_FIELDS_FRACTION.items()},
}


def _setup(env, method, spacing, seed, clearance, heading_deg, max_points, options):
    env, module, sensor, heading, key, clearance = scene_request(env, method, clearance, heading_deg, seed, **options)
    for field, value in (("spacing", spacing), ("arena", env.arena)):
        if is_traced(value):  # the grid's size depends on them: a program cannot take them as data
            raise InputError(
                field,
                "a traced value",
                "must be concrete (it sets the grid's size); trace the landmarks, home, d, scale or noise instead",
            )
    spacing = positive(spacing, "spacing")
    traced = any(is_traced(x) for x in (env.landmarks, env.home, env.valid, clearance))
    if traced:  # which points are clear of the landmarks is computed in the program
        check_size(grid_count(env.arena, spacing), max_points, "spacing", spacing, "grid point")
    else:
        check_grid(env, Grid(spacing=spacing, clearance=clearance), max_points)
    points = grid_points(env.arena, spacing)
    included = grid_included(env, points, clearance)
    headings = (
        random_headings(key, points.shape[0]) if heading is None else np.full(points.shape[0], heading, np.float32)
    )
    # host arrays where they are known now; inside jax.jit even the key is traced
    included, headings = (x if is_traced(x) else np.asarray(x) for x in (included, headings))
    return env, module, sensor, key, points, included, headings


def _check_soft(tau, sharpness) -> tuple[float, float]:
    tau = positive(tau, "tau")
    sharpness = positive(sharpness, "sharpness")
    return tau, sharpness


@keywords_after(2, ("spacing", "seed", "soft", "tau", "sharpness", "heading_deg", "clearance", "max_points"))
def homing_loss(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    *,
    spacing: float = SPACING,
    seed: int = 0,
    soft: bool = True,
    tau: float = TAU,
    sharpness: float = VISIBILITY_WIDTH,
    heading_deg: float | None = None,
    clearance: Real = CLEARANCE,
    max_points: int = MAX_POINTS,
    **options,
) -> jax.Array:
    """Mean of 1 - cos(angular error) over the docs/model.md §5 grid (0 perfect, 2 = every direction
    reversed; a point without a direction counts 2), as a JAX scalar. soft=True: the analytic views
    and softmin matching of docs/differentiable.md with temperature `tau` and visibility width
    `sharpness` (rad); soft=False: the ordinary (pixel) vector map. `options` as in
    `delvjax.vector_map`.

    A JAX function: under `jax.grad`, `jax.jit` or `jax.vmap`, an Env's landmarks and home, `d`,
    `scale`, the noise options, `tau` and `sharpness` may be traced (a traced value is checked at run
    time, `equinox.error_if`, with the message a concrete one gets at once); the arena, spacing and
    seed stay concrete (they set the grid). soft=False is not differentiable and takes no traced value."""
    if soft:
        tau, sharpness = _check_soft(tau, sharpness)
    env, module, sensor, key, points, included, headings = _setup(
        env, method, spacing, seed, clearance, heading_deg, max_points, options
    )
    if not soft:
        leaves = jax.tree.leaves((env, module, sensor, clearance))
        if any(is_traced(x) for x in leaves):
            raise InputError(
                "soft", soft, "must be True under jax.grad, jax.jit or jax.vmap (the pixel map is not differentiable)"
            )

        vm = vector_map(
            env=env,
            method=module,
            sensor=sensor,
            spacing=spacing,
            key=key,
            clearance=clearance,
            heading=None if heading_deg is None else math.radians(heading_deg),
        )
        err = np.radians(np.asarray(vm.error_deg))[np.asarray(vm.included)]
        return jnp.asarray(np.mean(1.0 - np.cos(err)))
    check_differentiable(module)
    weights = soft_included(env, points, clearance)  # the grid rule with soft edges (docs/differentiable.md)
    return _loss(env, points, weights, headings, key, sensor, module, jnp.float32(tau), jnp.float32(sharpness))


_loss = jax.jit(soft_loss)


class LossProblem(NamedTuple):
    """A soft homing-loss evaluation ready to run: the differentiable parameters (`params`:
    landmarks (L, 3), home (2,), d, noise (a `Noise`), scale for DELV) and everything held fixed
    (`included`: the hard grid rule at the given landmarks; the loss weighs points by
    `soft_included` of the landmarks it is given)."""

    params: dict
    env: Env
    points: np.ndarray
    included: np.ndarray
    headings: np.ndarray
    key: jax.Array
    sensor: object
    method: HomingMethod
    tau: jax.Array
    sharpness: jax.Array
    n_landmarks: int
    clearance: jax.Array
    edge: jax.Array  # cm: the soft edge of the grid rule (`soft_included`)


def loss_problem(
    env: str | Path | Env,
    method: str | HomingMethod = "delv",
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    sharpness: float = VISIBILITY_WIDTH,
    heading_deg: float | None = None,
    clearance: Real = CLEARANCE,
    max_points: int = MAX_POINTS,
    **options,
) -> LossProblem:
    """Validate the options of `homing_loss_grad` (before any work) and set the problem up."""
    tau, sharpness = _check_soft(tau, sharpness)
    env, module, sensor, key, points, included, headings = _setup(
        env, method, spacing, seed, clearance, heading_deg, max_points, options
    )
    check_differentiable(module)
    sensor, module = traced_floats(sensor), traced_floats(module)  # python floats are not differentiable leaves
    arrays = env
    params = {
        "landmarks": jnp.asarray(arrays.landmarks, jnp.float32),
        "home": jnp.asarray(arrays.home, jnp.float32),
        "d": sensor.d,
        "noise": sensor.noise,
    }
    if hasattr(module, "scale"):
        params["scale"] = module.scale
    return LossProblem(
        params,
        arrays,
        points,
        included,
        headings,
        key,
        sensor,
        module,
        jnp.float32(tau),
        jnp.float32(sharpness),
        env.n_landmarks,
        jnp.asarray(clearance, jnp.float32),
        jnp.float32(EDGE_CM),
    )


def problem_loss(params: dict, problem: LossProblem, visible: jax.Array | None = None) -> jax.Array:
    """The soft loss of `problem` with `params` in place of its own (a pure, differentiable function);
    `visible` (L,): the landmarks the current views see (occlusion; None: all)."""
    e = eqx.tree_at(lambda x: (x.landmarks, x.home), problem.env, (params["landmarks"], params["home"]))
    s = eqx.tree_at(lambda x: (x.d, x.noise), problem.sensor, (params["d"], params["noise"]))
    m = eqx.tree_at(lambda x: x.scale, problem.method, params["scale"]) if "scale" in params else problem.method
    weights = soft_included(e, problem.points, problem.clearance, problem.edge)
    return soft_loss(
        e, problem.points, weights, problem.headings, problem.key, s, m, problem.tau, problem.sharpness, visible
    )


@jax.jit
def problem_value_and_grad(problem: LossProblem) -> tuple[jax.Array, dict]:
    """Quality and its gradient with respect to every parameter, reverse mode, one program."""
    return jax.value_and_grad(problem_loss)(problem.params, problem)


def readable_grads(grads: dict, n_landmarks: int) -> dict:
    """Gradients by public name: landmarks (N, 3), home, d, scale, and the noise options (per degree)."""
    out = {
        "landmarks": np.asarray(grads["landmarks"])[:n_landmarks],
        "home": np.asarray(grads["home"]),
        "d": float(grads["d"]),
    }
    if "scale" in grads:
        out["scale"] = float(grads["scale"])
    for field, name in NOISE_NAMES.items():
        g = float(getattr(grads["noise"], field))
        out[name] = g * math.pi / 180.0 if name.endswith("_deg") else g
    return out
