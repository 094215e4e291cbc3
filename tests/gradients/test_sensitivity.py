"""jax.grad through a homing method equals finite differences (the discrete choices held fixed)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax.core.maps import stream_keys
from delvjax.core.sensing import record_home, unit_move
from delvjax.core.sensitivity import _perturbed, bearing_jacobian, bearing_noise_gain
from delvjax.core.sensor import Sensor
from delvjax.options._registry import METHODS
from delvjax.studies.runs.sensitivity import GAIN_SET, gain_method
from tests.cases.compiled import call, compiled


@compiled
def _move(env, p, h, k, cfg):
    """The unit move ending at p (one compiled program per shape, shared by every method)."""
    return unit_move(env, p, h, k, cfg, end_at=p)


@compiled
def _around(method, home, view, e):
    """The method's direction at the current bearings + e, at them and - e."""
    return method(home, _perturbed(view, e))[0], method(home, view)[0], method(home, _perturbed(view, -e))[0]


@compiled
def _noisy_angles(method, home, view, noise):
    """The method's direction with every row of `noise` added to the current view's valid bearings."""
    return jax.vmap(lambda n: method(home, _perturbed(view, n * view.end.valid))[0])(noise)


@pytest.mark.parametrize("method", ["delv", "alv", "acv"])
def test_bearing_jacobian_matches_finite_differences(method):
    env = delvjax.load_env("env1").arrays()
    cfg = Sensor()
    key = jax.random.PRNGKey(5)
    pts = jnp.array([[300.0, 450.0], [600.0, 560.0], [150.0, 850.0], [820.0, 200.0]])
    hd = jnp.array([0.3, 2.0, -1.0, 4.0])
    jac, blob_ok, ok = bearing_jacobian(env, pts, hd, key, cfg, gain_method(method))  # as the study draws it
    k_home, k_views, _ = call(stream_keys, key)
    home = call(record_home, env, k_home, cfg)
    eps = 2e-4  # small enough that no discrete choice (heading grid, shift) flips
    checked = 0
    for i in range(4):
        view, _ = _move(env, pts[i], hd[i], jax.random.fold_in(k_views, i), cfg)
        for j in np.nonzero(np.asarray(blob_ok[i]))[0]:
            e = jnp.zeros_like(view.end.bearing).at[j].set(eps)
            plus, centre, minus = _around(METHODS[method], home, view, e)
            fwd = float(jnp.angle(jnp.exp(1j * (plus - centre)))) / eps
            bwd = float(jnp.angle(jnp.exp(1j * (centre - minus)))) / eps
            if abs(fwd - bwd) > 0.05 * max(1.0, abs(fwd)):
                continue  # a discrete choice (DELV's 1-degree heading grid) flipped: no derivative here
            assert abs(0.5 * (fwd + bwd) - float(jac[i, j])) < 0.05 * max(1.0, abs(fwd)), (i, j, fwd, float(jac[i, j]))
            checked += 1
    assert bool(ok.all()) and checked >= 8


def test_gain_maps_in_the_shared_program_equal_each_method_on_its_own():
    """The study's gain maps run DELV (with and without compass) and ALV in one compiled program; their
    Jacobians equal those of each method's own program bit for bit."""
    env = delvjax.load_env("env1").arrays()
    pts = jnp.array([[300.0, 450.0], [600.0, 560.0], [150.0, 850.0], [820.0, 200.0]])
    hd = jnp.array([0.3, 2.0, -1.0, 4.0])
    assert "alv" in GAIN_SET and type(gain_method("alv")).__name__ == "MethodSet"
    shared = bearing_jacobian(env, pts, hd, jax.random.PRNGKey(5), Sensor(), gain_method("alv"))
    own = bearing_jacobian(env, pts, hd, jax.random.PRNGKey(5), Sensor(), METHODS["alv"])
    for a, b in zip(shared, own):
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b))


def test_gain_predicts_small_noise_spread():
    """Monte Carlo over seeds with small bearing noise on the current view only ~ gain * sigma."""
    env = delvjax.load_env("ring5").arrays()
    pts = jnp.array([[420.0, 430.0]])
    hd = jnp.array([0.7])
    gain, ok = call(bearing_noise_gain, env, pts, hd, jax.random.PRNGKey(0), Sensor(), METHODS["alv"])
    sigma = np.radians(0.3)
    view, _ = _move(env, pts[0], hd[0], jax.random.PRNGKey(1), Sensor())
    home = call(record_home, env, jax.random.PRNGKey(2), Sensor())
    noise = sigma * jax.random.normal(jax.random.PRNGKey(3), (4000, view.end.bearing.shape[0]))
    angles = _noisy_angles(METHODS["alv"], home, view, noise)
    spread = float(jnp.std(jnp.angle(jnp.exp(1j * (angles - jnp.mean(angles))))))
    assert bool(ok[0]) and abs(spread / (float(gain[0]) * sigma) - 1.0) < 0.1
