"""Analytic cases (thesis §3.2-3.3): exact distances, exact position and heading, the ALV potential."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.core.estimation import current_vectors, end_distances, quantize, reference_vectors, start_distances
from delvjax.core.methods import DELV
from delvjax.core.methods.delv import delv_direction, match_arrangement
from delvjax.core.sensing import Snapshot, UnitMove
from delvjax.options._registry import METHODS
from tests.cases.compiled import call, compiled
from tests.conftest import random_landmarks

jax.config.update("jax_enable_x64", False)

current_vectors, end_distances, reference_vectors, start_distances = map(
    compiled, (current_vectors, end_distances, reference_vectors, start_distances)
)
delv_direction, match_arrangement = compiled(delv_direction), compiled(match_arrangement)


def exact_snapshot(points: np.ndarray, pos: np.ndarray, heading: float) -> Snapshot:
    """A snapshot whose blobs are the exact bearings of `points` (no pixels)."""
    rel = points - pos
    b = np.sort(np.mod(np.arctan2(rel[:, 1], rel[:, 0]) - heading, 2 * np.pi))
    return Snapshot(
        mask=jnp.zeros(360, bool),
        gray=jnp.zeros(360),
        bearing=jnp.asarray(b, jnp.float32),
        width=jnp.zeros(len(b), jnp.float32),
        valid=jnp.ones(len(b), bool),
    )


def exact_move(points, start, heading, d, psi=0.0, compass=0.0) -> UnitMove:
    end = start + d * np.array([np.cos(heading), np.sin(heading)])
    return UnitMove(
        start=exact_snapshot(points, start, heading),
        end=exact_snapshot(points, end, heading + psi),
        d_hat=jnp.float32(d),
        psi_hat=jnp.float32(psi),
        compass=jnp.float32(compass),
    )


@pytest.mark.parametrize("psi_deg", [0.0, 7.0, -12.0])
def test_distances_are_exact_with_exact_bearings(psi_deg):
    """Eqs 3.2 / 3.3 (typo corrected): R_C = |L - C|, R_P = |L - P| for any turn psi."""
    lms = np.array([[300.0, 700.0], [750.0, 650.0], [650.0, 250.0], [250.0, 350.0]])
    start, h, d = np.array([430.0, 520.0]), np.radians(33.0), 50.0
    move = exact_move(lms, start, h, d, psi=np.radians(psi_deg))
    cfg = DELV()
    end = start + d * np.array([np.cos(h), np.sin(h)])
    order_p = np.argsort(np.mod(np.arctan2(*(lms - start).T[::-1]) - h, 2 * np.pi))
    order_c = np.argsort(np.mod(np.arctan2(*(lms - end).T[::-1]) - h - np.radians(psi_deg), 2 * np.pi))
    np.testing.assert_allclose(
        np.asarray(start_distances(move, cfg)), np.linalg.norm(lms - start, axis=1)[order_p], rtol=2e-3
    )
    np.testing.assert_allclose(
        np.asarray(end_distances(move, cfg)), np.linalg.norm(lms - end, axis=1)[order_c], rtol=2e-3
    )


def test_undefined_distance_becomes_r_max():
    """A landmark straight ahead has no parallax: its distance is r_max (docs/model.md §3.1)."""
    lms = np.array([[800.0, 500.0], [500.0, 800.0]])
    move = exact_move(lms, np.array([500.0, 500.0]), 0.0, 50.0)
    r = np.asarray(start_distances(move, DELV()))
    assert r[0] == 2000.0 and abs(r[1] - 300.0) < 0.5


def test_quantization_eq_3_17():
    r = jnp.array([1.0, 400.0, 500.0, 501.0, 999.0, 5000.0])
    np.testing.assert_allclose(np.asarray(quantize(r, 1, 1000.0)), 1000.0)
    np.testing.assert_allclose(np.asarray(quantize(r, 2, 1000.0)), [500, 500, 500, 1000, 1000, 1000])
    np.testing.assert_allclose(np.asarray(quantize(r, 4, 1000.0)), [250, 500, 500, 750, 1000, 1000])
    assert quantize(r, None, 1000.0) is r


def separated_landmarks(seed: int) -> np.ndarray:
    """3-6 landmarks 180-350 cm from home, bearings >= 40 deg apart and >= 15 deg off the x axis:
    the geometry in which the nearest-bearing partner of docs/model.md §3.1 is the true one."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 7))
    base = np.radians(rng.uniform(15, 45)) + 2 * np.pi * np.arange(n) / n
    ang = base + np.radians(rng.uniform(-8, 8, size=n))
    ang = np.where(np.abs(np.sin(ang)) < np.sin(np.radians(15)), ang + np.radians(20), ang)
    dist = rng.uniform(180, 350, size=n)
    return 500.0 + dist[:, None] * np.stack([np.cos(ang), np.sin(ang)], axis=1)


@pytest.mark.parametrize("seed", range(6))
def test_exact_bearings_give_exact_position_and_heading(seed):
    """§3.3.1: with exact bearings the matching returns p = x - home and alpha = h - alpha_r."""
    rng = np.random.default_rng(seed)
    lms = separated_landmarks(seed)
    home = np.array([500.0, 500.0])
    cfg = DELV()
    ref_v, ref_ok = reference_vectors(exact_move(lms, home, 0.0, 50.0), cfg)
    done = 0
    while done < 4:
        h = np.radians(float(rng.integers(0, 360)))
        x = rng.uniform(350, 650, size=2)
        start = x - 50.0 * np.array([np.cos(h), np.sin(h)])
        rel = lms - start
        sin_b = np.sin(np.arctan2(rel[:, 1], rel[:, 0]) - h)
        if len(lms) < 2 or np.min(np.linalg.norm(lms - x, axis=1)) < 100 or np.min(np.abs(sin_b)) < 0.05:
            continue  # undefined parallax straight ahead/behind gives r_max, not an exact distance
        done += 1
        view = exact_move(lms, start, h, 50.0)
        cur_v, cur_ok = current_vectors(view, cfg)
        alphas = 2 * jnp.pi * jnp.arange(360) / 360
        p, alpha, var, n = match_arrangement(ref_v, ref_ok, cur_v, cur_ok, alphas)
        np.testing.assert_allclose(np.asarray(p), x - home, atol=0.5)
        assert abs(np.angle(np.exp(1j * (float(alpha) - h)))) < 1e-5
        assert float(var) < 1.0 and int(n) == len(lms)
        angle, valid = call(METHODS["delv"], exact_move(lms, home, 0.0, 50.0), view)
        to_home = np.arctan2(*(home - x)[::-1])
        assert bool(valid) and abs(np.angle(np.exp(1j * (h + float(angle) - to_home)))) < 1e-3


def alv_potential(x, lms, home):
    """Möller (2000) / thesis §3.3.2: U(x) = sum ||L_i - x|| - u_i(x_o) . (L_i - x)."""
    u_home = (lms - home) / jnp.linalg.norm(lms - home, axis=1, keepdims=True)
    return jnp.sum(jnp.linalg.norm(lms - x, axis=1) - jnp.sum(u_home * (lms - x), axis=1))


def test_alv_potential_argument():
    """H(x) = ALV(x) - ALV(x_o) = -grad U(x) (Eq 3.13); grad U(x_o) = 0, D(x_o) > 0, U_xx(x_o) > 0 (Eq 3.14)."""
    lms = jnp.asarray(random_landmarks(4)[:, :2])
    home = jnp.array([500.0, 500.0])

    def alv(x):
        v = lms - x
        return jnp.sum(v / jnp.linalg.norm(v, axis=1, keepdims=True), axis=0)

    for x in np.random.default_rng(0).uniform(100, 900, size=(10, 2)):
        x = jnp.asarray(x)
        np.testing.assert_allclose(
            np.asarray(alv(x) - alv(home)), -np.asarray(jax.grad(alv_potential)(x, lms, home)), atol=1e-5
        )
    np.testing.assert_allclose(np.asarray(jax.grad(alv_potential)(home, lms, home)), 0.0, atol=1e-5)
    hess = np.asarray(jax.hessian(alv_potential)(home, lms, home))
    rel = np.asarray(lms - home)
    norm3 = np.linalg.norm(rel, axis=1) ** 3
    d_eq314 = sum(
        (rel[i, 0] * rel[j, 1] - rel[j, 0] * rel[i, 1]) ** 2 / (norm3[i] * norm3[j])
        for i in range(len(rel))
        for j in range(i + 1, len(rel))
    )
    np.testing.assert_allclose(np.linalg.det(hess), d_eq314, rtol=1e-3)
    assert d_eq314 > 0 and hess[0, 0] > 0


def test_alv_method_follows_the_potential_gradient():
    """The ALV method on rendered images (exact compass) points along -grad U within 2 degrees
    (where every landmark is its own blob)."""
    env = delvjax.load_env("ring5")
    vm = delvjax.vector_map(env, method="alv", grid=Grid(spacing=50.0, heading_deg=30.0))
    lms, home = env.landmarks[:, :2], env.home
    # within 180 cm of home no two of the five landmarks merge into one blob
    inc = np.asarray(vm.included) & (np.linalg.norm(np.asarray(vm.points) - 500.0, axis=1) < 180.0)
    for x, direction, ok in zip(np.asarray(vm.points)[inc], np.asarray(vm.direction)[inc], np.asarray(vm.valid)[inc]):
        g = -np.asarray(jax.grad(alv_potential)(jnp.asarray(x), lms, home))
        if np.linalg.norm(g) < 0.05:
            continue
        assert ok and abs(np.angle(np.exp(1j * (direction - np.arctan2(g[1], g[0]))))) < np.radians(2.0)


def test_delv_potential_points_home():
    """Eq 3.16: U_i = 1/2 ||L_i - x||^2 - (L_i - x_o).(L_i - x) has -grad U = N (x_o - x): straight home."""
    lms = jnp.asarray(random_landmarks(2)[:, :2])
    home = jnp.array([500.0, 500.0])
    u = lambda x: jnp.sum(0.5 * jnp.sum((lms - x) ** 2, axis=1) - jnp.sum((lms - home) * (lms - x), axis=1))  # noqa: E731
    x = jnp.array([123.0, 777.0])
    np.testing.assert_allclose(np.asarray(-jax.grad(u)(x)), len(lms) * np.asarray(home - x), rtol=1e-5)
    assert np.linalg.det(np.asarray(jax.hessian(u)(home))) > 0


def test_home_is_the_equilibrium_of_the_homing_fields():
    """§3.3.2 by root finding (optimistix Newton, vmapped over starts): the ALV field of env1 and
    of ring5, and the DELV field (Eq 3.15), vanish at home and nowhere else near it."""
    from delvjax.core.analysis import alv_field, equilibria

    starts = np.random.default_rng(0).uniform(380, 620, size=(40, 2))
    for name in ("env1", "ring5"):
        env = delvjax.load_env(name)
        roots, ok = equilibria(env, starts, "alv")
        assert bool(np.all(np.asarray(ok)))
        np.testing.assert_allclose(np.asarray(roots), 500.0, atol=0.05)
        np.testing.assert_allclose(np.asarray(alv_field(env.home, env)), 0.0, atol=1e-6)
    roots, ok = equilibria(delvjax.load_env("env3"), starts, "delv")
    assert bool(np.all(np.asarray(ok)))
    np.testing.assert_allclose(np.asarray(roots), 500.0, atol=1e-3)


def test_one_pair_with_a_heading_takes_the_first_shift():
    """docs/model.md §3.4: with n = 1 every shift has var = 0; the first k wins (current 0 pairs reference 0)."""
    ref_v = jnp.array([[100.0, 50.0], [-80.0, 120.0], [-30.0, -200.0]])
    cur_v = jnp.array([[40.0, -60.0], [0.0, 0.0], [0.0, 0.0]])
    alpha = jnp.array([0.7])
    rot = np.array([[np.cos(0.7), -np.sin(0.7)], [np.sin(0.7), np.cos(0.7)]])
    for ref_ok, cur_ok, expect in [
        (
            jnp.array([True, True, True]),
            jnp.array([True, False, False]),
            np.asarray(ref_v[0]) - rot @ np.asarray(cur_v[0]),
        ),
        (
            jnp.array([True, False, False]),
            jnp.array([True, True, False]),
            np.asarray(ref_v[0]) - rot @ np.asarray(cur_v[0]),
        ),
    ]:
        p, a, var, n = match_arrangement(ref_v, ref_ok, cur_v, cur_ok, alpha)
        assert int(n) == 1 and float(var) == 0.0 and float(a) == pytest.approx(0.7)
        np.testing.assert_allclose(np.asarray(p), expect, atol=1e-4)


def test_delv_with_compass_homes_on_one_landmark():
    """docs/model.md §3.4: with a compass one landmark (n = 1) fixes p = V^R - Rot(alpha) V; with exact
    bearings and heading it is x - home exactly, so the direction is exact. Without a compass
    one pair fits every heading: invalid (NaN)."""
    lm = np.array([[640.0, 730.0]])
    home = np.array([500.0, 500.0])
    record = exact_move(lm, home, 0.0, 50.0)
    rng = np.random.default_rng(5)
    done = 0
    while done < 8:
        h = float(rng.uniform(0.0, 2 * np.pi))
        x = rng.uniform(150.0, 850.0, size=2)
        start = x - 50.0 * np.array([np.cos(h), np.sin(h)])
        rel = lm[0] - start
        if (
            np.linalg.norm(lm[0] - x) < 100
            or np.linalg.norm(x - home) < 100
            or abs(np.sin(np.arctan2(rel[1], rel[0]) - h)) < 0.05
        ):
            continue  # no parallax straight ahead/behind (R = r_max), and a tiny p near home
        done += 1
        view = exact_move(lm, start, h, 50.0, compass=h)
        to_home = np.arctan2(*(home - x)[::-1])
        angle, valid = call(METHODS["delv-compass"], record, view)
        assert bool(valid) and abs(np.angle(np.exp(1j * (h + float(angle) - to_home)))) < 2e-3
        # the heading estimate the visual compass passes in takes the same path
        angle_v, valid_v = delv_direction(record, view, DELV(), jnp.reshape(jnp.float32(h), (1,)), min_pairs=1)
        assert bool(valid_v) and float(angle_v) == pytest.approx(float(angle), abs=1e-6)
        angle, valid = call(METHODS["delv"], record, view)
        assert not bool(valid) and np.isnan(float(angle))
