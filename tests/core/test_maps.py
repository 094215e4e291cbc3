"""Vector maps: jit/vmap consistency, determinism, chunk invariance, invalid points, metrics (docs/model.md §5)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.core.maps import homing_directions, stream_keys
from delvjax.core.metrics import angular_error_deg, error_class, error_curve, error_point_rates, t_interval
from delvjax.core.sensing import record_home, unit_move
from delvjax.core.sensor import Sensor
from delvjax.options._registry import METHODS


@pytest.mark.parametrize("method", ["delv", "acv"])
def test_vmapped_map_equals_single_point_calls(method):
    env = delvjax.load_env("env1")
    vm = delvjax.vector_map(env, method=method, seed=3, grid=Grid(spacing=100.0))
    cfg = Sensor()
    key = jax.random.PRNGKey(3)
    k_home, k_views, _ = stream_keys(key)

    @jax.jit
    def single(point, heading, index):
        home = record_home(env, k_home, cfg)
        view, heading_end = unit_move(env, point, heading, jax.random.fold_in(k_views, index), cfg, end_at=point)
        angle, valid = METHODS[method](home, view)
        return heading_end + angle, valid

    for i in range(0, 100, 9):
        d, ok = single(vm.points[i], vm.heading[i], i)
        assert bool(ok) == bool(vm.valid[i])
        if ok:
            assert abs(float(jnp.angle(jnp.exp(1j * (d - vm.direction[i]))))) < 1e-5


def test_same_seed_same_numbers_however_chunked():
    kw = dict(
        method="delv", grid=Grid(spacing=50.0), seed=11, bearing_noise_deg=1.0, step_noise=0.05, turn_noise_deg=2.0
    )
    a = delvjax.vector_map("env2", batch_size=2048, **kw)
    b = delvjax.vector_map("env2", batch_size=37, **kw)
    c = delvjax.vector_map("env2", method="delv", seed=12, bearing_noise_deg=1.0, grid=Grid(spacing=50.0))
    for f in ("heading", "direction", "valid", "error_deg"):
        np.testing.assert_array_equal(np.asarray(getattr(a, f)), np.asarray(getattr(b, f)), err_msg=f)
    assert not np.array_equal(np.asarray(a.heading), np.asarray(c.heading))


def test_zero_noise_is_noise_free_and_noise_changes_results():
    plain = delvjax.vector_map("env1", grid=Grid(spacing=100.0, heading_deg=45.0))
    zero = delvjax.vector_map(
        "env1", bearing_noise_deg=0.0, compass_noise_deg=0.0, grid=Grid(spacing=100.0, heading_deg=45.0)
    )
    noisy = delvjax.vector_map("env1", bearing_noise_deg=3.0, grid=Grid(spacing=100.0, heading_deg=45.0))
    np.testing.assert_array_equal(np.asarray(plain.direction), np.asarray(zero.direction))
    assert not np.allclose(np.asarray(plain.direction), np.asarray(noisy.direction), equal_nan=True)
    np.testing.assert_allclose(np.degrees(np.asarray(plain.heading)), 45.0, atol=1e-4)


def test_rotating_the_world_rotates_the_map():
    """DELV without compass: rotate landmarks, points, headings and alpha_r by 90 deg about home."""
    env = delvjax.load_env("env1")
    lms = np.asarray(env.landmarks)
    rot = np.column_stack([1000.0 - lms[:, 1], lms[:, 0], lms[:, 2]])  # 90 deg CCW about (500, 500)
    env_r = delvjax.make_env(rot)
    cfg, cfg_r = Sensor(background="none"), Sensor(background="none", alpha_r=float(np.pi / 2))
    pts = jnp.asarray(np.random.default_rng(0).uniform(100, 900, size=(60, 2)), jnp.float32)
    pts_r = jnp.stack([1000.0 - pts[:, 1], pts[:, 0]], axis=1)
    h = jnp.full(60, 0.3, jnp.float32)
    key = jax.random.PRNGKey(0)
    d, ok = homing_directions(env, pts, h, key, cfg, METHODS["delv"])
    d_r, ok_r = homing_directions(env_r, pts_r, h + np.pi / 2, key, cfg_r, METHODS["delv"])
    same = np.abs(np.angle(np.exp(1j * (np.asarray(d_r) - np.asarray(d) - np.pi / 2)))) < 1e-3
    assert np.mean(same[np.asarray(ok)]) >= 0.95 and np.array_equal(np.asarray(ok), np.asarray(ok_r))


def test_undefined_directions_are_invalid_not_nan_errors():
    """DELV without a compass needs >= 2 landmark pairs: a one-landmark world gives only invalid
    points (error 180). With a compass (true or visual) one pair suffices (docs/model.md §3.4): every
    point is valid and, the one pairing being right, the errors are small."""
    env = delvjax.make_env([[700.0, 600.0, 30.0]], pad_to=4)  # env1's four slots: its programs serve both
    vm = delvjax.vector_map(env, method="delv", grid=Grid(spacing=100.0))
    assert not np.asarray(vm.valid).any()
    assert np.isnan(np.asarray(vm.direction)).all()
    np.testing.assert_array_equal(np.asarray(vm.error_deg), 180.0)
    alv = delvjax.vector_map(env, method="alv", grid=Grid(spacing=100.0))
    assert np.asarray(alv.valid)[np.asarray(alv.included)].mean() > 0.9
    for method in ("delv-compass", "delv-visual"):
        one = delvjax.vector_map(env, method=method, grid=Grid(spacing=50.0))
        inc = np.asarray(one.included)
        assert np.asarray(one.valid)[inc].all(), method
        assert np.median(np.asarray(one.error_deg)[inc]) < 5.0, method


def test_a_grid_point_at_home_is_left_out_and_a_grid_of_only_home_is_refused():
    """A grid whose only point is home (spacing 1000 cm in a 1000 cm arena) has nothing to evaluate: the
    spacing is refused, naming home, before any work (docs/model.md §5 "Grid"). The same landmarks with
    home elsewhere evaluate that point, whichever of the two was asked first (the answer is cached)."""
    env1 = delvjax.load_env("env1")
    away = delvjax.make_env(np.asarray(env1.landmarks), home=(400.0, 400.0))
    vm = delvjax.vector_map(away, method="alv", grid=Grid(spacing=1000.0))
    assert np.asarray(vm.included).sum() == 1 and np.asarray(vm.valid).all()
    for call in (delvjax.vector_map, delvjax.catchment):
        with pytest.raises(delvjax.InputError) as exc:
            call(env1, method="alv", grid=Grid(spacing=1000.0))
        assert exc.value.field == "spacing" and "but home" in str(exc.value)


def test_one_visible_landmark_needs_a_compass():
    """Occlusion down to one visible landmark (`hidden`): delv-compass stays defined, delv does not."""
    hidden = [1, 2, 3]
    with_compass = delvjax.vector_map("env1", method="delv-compass", hidden=hidden, grid=Grid(spacing=100.0))
    assert np.asarray(with_compass.valid)[np.asarray(with_compass.included)].all()
    without = delvjax.vector_map("env1", method="delv", hidden=hidden, grid=Grid(spacing=100.0))
    assert not np.asarray(without.valid).any()


def test_metrics():
    pts = jnp.array([[600.0, 500.0], [500.0, 600.0], [400.0, 500.0], [500.0, 400.0]])
    home = jnp.array([500.0, 500.0])
    direction = jnp.array([np.pi, -np.pi / 2 + 0.5, 0.0, 0.0])
    valid = jnp.array([True, True, True, False])
    err = np.asarray(angular_error_deg(direction, valid, pts, home))
    np.testing.assert_allclose(err, [0.0, np.degrees(0.5), 0.0, 180.0], atol=1e-4)
    np.testing.assert_array_equal(np.asarray(error_class(jnp.array([10.0, 45.0, 60.0, 90.0, 91.0]))), [0, 0, 1, 1, 2])
    rates = error_point_rates(jnp.array([10.0, 50.0, 100.0, 180.0]), jnp.array([True, True, True, False]))
    assert rates == {"gt45_pct": pytest.approx(200 / 3), "gt90_pct": pytest.approx(100 / 3)}
    mean, half, n = t_interval(np.array([1.0, 2.0, 3.0, 4.0]))
    assert (mean, n) == (2.5, 4) and half == pytest.approx(3.182446 * np.std([1, 2, 3, 4], ddof=1) / 2, rel=1e-5)
    rows = error_curve(
        jnp.array([10.0, 20.0, 30.0, 90.0]),
        jnp.array([[510.0, 500.0], [530.0, 500.0], [560.0, 500.0], [500.0, 580.0]]),
        home,
        jnp.array([True, True, True, True]),
    )
    assert [r["n"] for r in rows] == [2, 2] and rows[0]["mean_deg"] == 15.0
