"""`delvjax.homing_loss` is a JAX function (docs/differentiable.md): `jax.grad`, `jax.jit` and
`jax.vmap` of it work with respect to landmarks, home, d and the noise sigmas, agree with
`homing_loss_grad` and the eager value, and a traced bad value is refused with the same words."""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax.core.errors import InputError

ENV = delvjax.load_env("env1")
OPTS = dict(method="alv", spacing=200, tau=0.05)  # 25 points: one small program per transform
SIGMA = 2.0  # compass noise, deg: a noise sigma ALV reads


def loss(landmarks, home, d, sigma):
    env = eqx.tree_at(lambda e: (e.landmarks, e.home), ENV, (landmarks, home))
    return delvjax.homing_loss(env, d=d, compass_noise_deg=sigma, **OPTS)


ARGS = (ENV.landmarks, ENV.home, 50.0, SIGMA)


@pytest.fixture(scope="module")
def reference():
    return delvjax.homing_loss_grad(ENV, compass_noise_deg=SIGMA, smoothing_cm=None, **OPTS)  # the point gradient


def test_the_value_is_a_jax_scalar_equal_to_the_gradient_functions(reference):
    q = delvjax.homing_loss(ENV, compass_noise_deg=SIGMA, **OPTS)
    assert isinstance(q, jax.Array) and q.shape == ()
    assert float(q) == pytest.approx(reference[0], rel=1e-6)  # two programs: the value alone, value and grad


def test_grad_with_respect_to_landmarks_home_d_and_noise_matches_homing_loss_grad(reference):
    _, grads = reference
    g_lm, g_home, g_d, g_noise = jax.grad(loss, argnums=(0, 1, 2, 3))(*ARGS)
    n = ENV.n_landmarks
    np.testing.assert_allclose(np.asarray(g_lm)[:n], grads["landmarks"], rtol=1e-5, atol=1e-9)
    assert np.abs(np.asarray(g_lm)[:n]).max() > 1e-5  # not trivially zero
    np.testing.assert_allclose(np.asarray(g_home), grads["home"], rtol=1e-5, atol=1e-9)
    assert float(g_d) == pytest.approx(grads["d"], rel=1e-5, abs=1e-12)
    # the noise sigma in degrees: the gradient per degree, as homing_loss_grad reports it
    assert float(g_noise) == pytest.approx(grads["compass_noise_deg"], rel=1e-4)
    assert abs(float(g_noise)) > 1e-5


def test_jit_and_vmap_give_the_eager_values():
    eager = float(loss(*ARGS))
    assert float(jax.jit(loss)(*ARGS)) == pytest.approx(eager, rel=1e-6)
    moved = ENV.landmarks.at[0, 0].add(40.0)
    batch = jax.vmap(loss, in_axes=(0, None, None, None))(jnp.stack([ENV.landmarks, moved]), *ARGS[1:])
    np.testing.assert_allclose(np.asarray(batch), [eager, float(loss(moved, *ARGS[1:]))], rtol=1e-5)
    assert float(batch[0]) != float(batch[1])


def test_a_traced_bad_value_is_refused_with_the_concrete_message():
    with pytest.raises(InputError, match="d: must be > 0"):
        delvjax.homing_loss(ENV, d=-1.0, **OPTS)
    with pytest.raises(Exception, match="d: must be > 0"):
        jax.block_until_ready(jax.jit(lambda d: delvjax.homing_loss(ENV, d=d, **OPTS))(-1.0))


def test_what_sets_the_grid_must_stay_concrete():
    with pytest.raises(InputError, match="arena: must be concrete"):
        jax.jit(lambda e: delvjax.homing_loss(e, **OPTS))(ENV.arrays())
    with pytest.raises(InputError, match="soft: must be True"):
        jax.grad(lambda d: delvjax.homing_loss(ENV, "alv", spacing=200, soft=False, d=d))(50.0)
