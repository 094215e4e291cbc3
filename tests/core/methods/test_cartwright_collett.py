"""Cartwright & Collett snapshot model: JAX `cc_home_vector` against the per-landmark NumPy twin
(tests/twins/cc.py), and analytic cases on a small explicit scene of cylinders (x, y, r)."""

from __future__ import annotations

import functools
import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.methods.cartwright_collett import cc_home_vector
from tests.cases.compiled import compiled
from tests.twins.cc import cc_home_vector_ref, wrap

TWO_PI = 2.0 * math.pi
B = 6
cc_compiled, cc_vmapped = compiled(cc_home_vector), jax.jit(jax.vmap(cc_home_vector))


# home at the origin; cylinders (x, y, r) in cm, all on one side as in a bee's landmark array
SCENE = np.array([[300.0, 50.0, 30.0], [120.0, 260.0, 25.0], [-60.0, 220.0, 40.0], [250.0, -150.0, 20.0]])


def view(landmarks: np.ndarray, p) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Blob arrays (bearing in [0, 2pi) sorted, width 2 asin(r/d), valid) seen from p, padded to B."""
    blobs = []
    for x, y, r in landmarks:
        dx, dy = x - p[0], y - p[1]
        blobs.append((math.atan2(dy, dx) % TWO_PI, 2.0 * math.asin(r / math.hypot(dx, dy))))
    blobs.sort()
    bearing, width, valid = np.zeros(B), np.zeros(B), np.zeros(B, bool)
    for k, (b, w) in enumerate(blobs):
        bearing[k], width[k], valid[k] = b, w, True
    return bearing, width, valid


def run_both(ref, cur, **kw):
    h, ok = cc_compiled(*map(jnp.asarray, ref), *map(jnp.asarray, cur), **kw)
    h_ref, ok_ref = cc_home_vector_ref(*ref, *cur, **kw)
    return np.asarray(h), bool(ok), h_ref, ok_ref


def random_sets(n: int = 200, seed: int = 0) -> list[np.ndarray]:
    """n padded blob sets (1-6 valid blobs per side) as 6 float32/bool arrays of shape (n, B).
    Every 8th current view equals its snapshot (invalid); the other 4th ones are perturbed copies
    with some bearings and widths left exactly equal (zero tangential / radial vectors)."""
    rng = np.random.default_rng(seed)
    arrs = [np.zeros((n, B), np.float32) if k % 3 != 2 else np.zeros((n, B), bool) for k in range(6)]
    for i in range(n):
        n_ref, n_cur = (int(v) for v in rng.integers(1, B + 1, size=2))
        rb, rw = np.sort(rng.uniform(0, TWO_PI, n_ref)), rng.uniform(0.05, 0.8, n_ref)
        if i % 8 == 0:  # identical view: invalid
            n_cur, cb, cw = n_ref, rb.copy(), rw.copy()
        elif i % 4 == 0:
            n_cur = n_ref
            cb = (rb + np.where(rng.random(n_ref) < 0.3, 0.0, rng.normal(0, 0.05, n_ref))) % TWO_PI
            cw = np.where(rng.random(n_ref) < 0.5, rw, rw * rng.uniform(0.7, 1.3, n_ref))
            order = np.argsort(cb)
            cb, cw = cb[order], cw[order]
        else:
            cb, cw = np.sort(rng.uniform(0, TWO_PI, n_cur)), rng.uniform(0.05, 0.8, n_cur)
        for k, (vals, m) in enumerate(
            ((rb, n_ref), (rw, n_ref), (None, n_ref), (cb, n_cur), (cw, n_cur), (None, n_cur))
        ):
            if vals is None:
                arrs[k][i, :m] = True
            else:
                arrs[k][i, :m] = vals
    return arrs


def twin_batch(arrs, **kw):
    out = [
        cc_home_vector_ref(*(np.asarray(a[i], np.float64) if a.dtype != bool else a[i] for a in arrs), **kw)
        for i in range(arrs[0].shape[0])
    ]
    return np.array([h for h, _ in out]), np.array([ok for _, ok in out])


def assert_same(h, ok, h_ref, ok_ref):
    np.testing.assert_array_equal(ok, ok_ref)
    assert ok_ref.any() and not ok_ref.all()  # both branches exercised
    np.testing.assert_allclose(h, h_ref, atol=1e-5)
    d_angle = [abs(wrap(math.atan2(a[1], a[0]) - math.atan2(b[1], b[0]))) for a, b in zip(h[ok], h_ref[ok])]
    assert max(d_angle) < 1e-4


# ----------------------------------------------------------------------------- (a) random vs twin
def test_random_sets_vmapped_match_twin():
    arrs = random_sets()
    h, ok = cc_vmapped(*map(jnp.asarray, arrs))
    assert_same(np.asarray(h), np.asarray(ok), *twin_batch(arrs))


# ----------------------------------------------------------------------------- (b) analytic cases
def test_identical_view_is_invalid():
    snap = view(SCENE, (0.0, 0.0))
    h, ok, h_ref, ok_ref = run_both(snap, snap)
    assert not ok and not ok_ref
    assert np.all(h == 0) and np.all(h_ref == 0)


@pytest.mark.parametrize("k", range(len(SCENE)))
@pytest.mark.parametrize("factor, toward", [(0.8, True), (1.25, False)])
def test_one_landmark_smaller_points_at_it(k, factor, toward):
    snap = view(SCENE, (0.0, 0.0))
    cur = (snap[0], snap[1].copy(), snap[2])
    cur[1][k] *= factor  # looks smaller (too far) -> go toward it; larger -> away from it
    h, ok, h_ref, ok_ref = run_both(snap, cur)
    assert ok and ok_ref
    expected = snap[0][k] if toward else snap[0][k] + math.pi
    assert abs(wrap(math.atan2(h[1], h[0]) - expected)) < 1e-6
    np.testing.assert_allclose(h, h_ref, atol=1e-6)
    assert np.linalg.norm(h) == pytest.approx(1.0, abs=1e-6)  # one radial unit vector, no tangential


def _rotated(eps):
    """Snapshot at home; current view = every bearing turned by eps, same widths.  It is the view
    from home of the scene rotated by eps about home (the 'implied' landmark positions)."""
    snap = view(SCENE, (0.0, 0.0))
    c, s = math.cos(eps), math.sin(eps)
    rotated = np.column_stack([c * SCENE[:, 0] - s * SCENE[:, 1], s * SCENE[:, 0] + c * SCENE[:, 1], SCENE[:, 2]])
    cur = view(rotated, (0.0, 0.0))
    np.testing.assert_allclose(cur[0][cur[2]], snap[0][snap[2]] + eps, atol=1e-12)
    np.testing.assert_allclose(cur[1], snap[1], atol=1e-12)
    return snap, (cur[0], snap[1], cur[2]), rotated  # widths copied: exactly equal


def _bearing_errors(landmarks, p, snap):
    return np.abs([wrap(a - b) for a, b in zip(view(landmarks, p)[0], snap[0])])[: len(landmarks)]


@pytest.mark.parametrize("eps", [0.02, -0.02])
def test_rotated_view_is_tangential_and_reduces_bearing_error(eps):
    snap, cur, rotated = _rotated(eps)
    h, ok, h_ref, ok_ref = run_both(snap, cur)
    assert ok and ok_ref
    # tangential only: with c_i = theta_i + eps, T_i = sign(eps) u(c_i + pi/2); widths equal -> R_i = 0
    c = cur[0][cur[2]]
    tangential = np.sign(eps) * np.column_stack([np.cos(c + math.pi / 2), np.sin(c + math.pi / 2)])
    np.testing.assert_allclose(h, tangential.sum(axis=0), atol=1e-5)
    np.testing.assert_allclose(h_ref, tangential.sum(axis=0), atol=1e-12)
    np.testing.assert_allclose(
        np.asarray(cc_compiled(*map(jnp.asarray, snap), *map(jnp.asarray, cur), radial_weight=7.0)[0]), h, atol=1e-6
    )
    # each landmark alone: a small step along its own vector shrinks its own bearing error
    # (this checks the tangential sign geometrically, on the JAX function itself)
    step = 2.0  # cm; landmarks are ~250 cm away
    for k in range(len(SCENE)):
        only = np.arange(B) == k
        h_k, ok_k = cc_compiled(*map(jnp.asarray, (snap[0], snap[1], only)), *map(jnp.asarray, (cur[0], cur[1], only)))
        assert bool(ok_k)
        p = step * np.asarray(h_k) / np.linalg.norm(h_k)
        before, after = _bearing_errors(rotated, (0.0, 0.0), snap)[k], _bearing_errors(rotated, p, snap)[k]
        assert after < before
    # all landmarks: a small step along H shrinks the summed bearing error
    p = step * h / np.linalg.norm(h)
    assert _bearing_errors(rotated, p, snap).sum() < _bearing_errors(rotated, (0.0, 0.0), snap).sum()


@pytest.mark.parametrize("direction", np.arange(8) * math.pi / 4)
def test_small_displacement_points_roughly_home(direction):
    """Seen from 10 cm off home, H is within 90 degrees of the true home direction."""
    p = 10.0 * np.array([math.cos(direction), math.sin(direction)])
    h, ok, h_ref, ok_ref = run_both(view(SCENE, (0.0, 0.0)), view(SCENE, p))
    assert ok and ok_ref
    np.testing.assert_allclose(h, h_ref, atol=1e-5)
    assert np.dot(h, -p) > 0


# ----------------------------------------------------------------------------- (c) jit / vmap / grad
def test_jit_and_vmap_match_twin():
    arrs = random_sets(n=64, seed=1)
    for w in (1.0, 3.0):
        fn = jax.jit(jax.vmap(functools.partial(cc_home_vector, radial_weight=w)))
        h, ok = fn(*map(jnp.asarray, arrs))
        assert_same(np.asarray(h), np.asarray(ok), *twin_batch(arrs, radial_weight=w))
    single = jax.jit(cc_home_vector)
    for i in range(4):
        h, ok = single(*(jnp.asarray(a[i]) for a in arrs))
        h_ref, ok_ref = cc_home_vector_ref(*(np.asarray(a[i], np.float64) if a.dtype != bool else a[i] for a in arrs))
        assert bool(ok) == ok_ref
        np.testing.assert_allclose(np.asarray(h), h_ref, atol=1e-5)


def test_gradient_is_finite():
    snap = view(SCENE, (0.0, 0.0))
    cur = view(SCENE, (10.0, -5.0))
    args = [jnp.asarray(a, jnp.float32) if a.dtype != bool else jnp.asarray(a) for a in (*snap, *cur)]

    def angle(cur_bearing):
        h, _ = cc_home_vector(*args[:3], cur_bearing, *args[4:])
        return jnp.arctan2(h[1], h[0])

    g = jax.jit(jax.grad(angle))(args[3])
    assert np.all(np.isfinite(np.asarray(g))) and np.any(np.asarray(g) != 0)
