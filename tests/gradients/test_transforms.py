"""`delvjax.homing_quality` is a JAX function (docs/differentiable.md): `jax.grad`, `jax.jit` and
`jax.vmap` of it work with respect to landmarks, home, d and the noise sigmas, agree with
`homing_quality_grad` and the eager value, and a traced bad value is refused with the same words."""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax.core.errors import InputError

ENV = delvjax.load_env("env1")
OPTS = dict(method="delv-compass", spacing=100, tau=0.05)


def quality_of_landmarks(landmarks):
    return delvjax.homing_quality(eqx.tree_at(lambda e: e.landmarks, ENV, landmarks), **OPTS)


@pytest.fixture(scope="module")
def reference():
    return delvjax.homing_quality_grad(ENV, **OPTS)


def test_the_value_is_a_jax_scalar_equal_to_the_gradient_functions(reference):
    q = delvjax.homing_quality(ENV, **OPTS)
    assert isinstance(q, jax.Array) and q.shape == ()
    assert float(q) == pytest.approx(reference[0], rel=1e-6)  # two programs: the value alone, value and grad


def test_grad_with_respect_to_landmarks_home_d_and_noise_matches_homing_quality_grad(reference):
    value, grads = reference
    g = jax.grad(quality_of_landmarks)(ENV.landmarks)
    np.testing.assert_allclose(np.asarray(g)[: ENV.n_landmarks], grads["landmarks"], rtol=1e-5, atol=1e-9)
    assert np.abs(np.asarray(g)[: ENV.n_landmarks]).max() > 1e-4  # not trivially zero
    g_home = jax.grad(lambda h: delvjax.homing_quality(eqx.tree_at(lambda e: e.home, ENV, h), **OPTS))(ENV.home)
    np.testing.assert_allclose(np.asarray(g_home), grads["home"], rtol=1e-5, atol=1e-9)
    g_d = jax.grad(lambda d: delvjax.homing_quality(ENV, d=d, **OPTS))(50.0)
    assert float(g_d) == pytest.approx(grads["d"], rel=1e-5)
    # a noise sigma in degrees: the gradient per degree, as homing_quality_grad reports it
    sigma = 2.0
    g_noise = jax.grad(lambda s: delvjax.homing_quality(ENV, bearing_noise_deg=s, **OPTS))(sigma)
    _, at_sigma = delvjax.homing_quality_grad(ENV, bearing_noise_deg=sigma, **OPTS)
    assert float(g_noise) == pytest.approx(at_sigma["bearing_noise_deg"], rel=1e-4)
    assert abs(float(g_noise)) > 1e-4


def test_jit_and_vmap_give_the_eager_values():
    eager = float(quality_of_landmarks(ENV.landmarks))
    assert float(jax.jit(quality_of_landmarks)(ENV.landmarks)) == pytest.approx(eager, rel=1e-6)
    moved = ENV.landmarks.at[0, 0].add(40.0)
    batch = jax.vmap(quality_of_landmarks)(jnp.stack([ENV.landmarks, moved]))
    np.testing.assert_allclose(np.asarray(batch), [eager, float(quality_of_landmarks(moved))], rtol=1e-5)
    assert float(batch[0]) != float(batch[1])


def test_a_traced_bad_value_is_refused_with_the_concrete_message():
    with pytest.raises(InputError, match="d: must be > 0"):
        delvjax.homing_quality(ENV, d=-1.0, **OPTS)
    with pytest.raises(Exception, match="d: must be > 0"):
        jax.block_until_ready(jax.jit(lambda d: delvjax.homing_quality(ENV, d=d, **OPTS))(-1.0))


def test_what_sets_the_grid_must_stay_concrete():
    with pytest.raises(InputError, match="arena: must be concrete"):
        jax.jit(lambda e: delvjax.homing_quality(e, **OPTS))(ENV.arrays())
    with pytest.raises(InputError, match="soft: must be True"):
        jax.grad(lambda d: delvjax.homing_quality(ENV, "delv-compass", spacing=100, soft=False, d=d))(50.0)
