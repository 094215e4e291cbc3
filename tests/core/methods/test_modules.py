"""Methods as modules (docs/architecture.md): settings on the module, traced leaves reuse the compiled
program, programs switch by index, the two methods added as one file + one registry line agree with
their NumPy twins, and blob widths are the apparent sizes of the landmarks."""

from __future__ import annotations

import dataclasses
import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import DELV, Compass, DELVGap, Grid, Sensor
from delvjax.core import maps
from delvjax.core.errors import InputError
from delvjax.core.kernel import direction_from, map_poses
from delvjax.core.sensing import blob_runs, record_home, render, unit_move
from delvjax.options._registry import METHODS, configure, method_set
from delvjax.options._setup import make_setup
from tests.cases.compiled import call, compiled
from tests.twins.cc import cc_home_vector_ref

record_home, unit_move = compiled(record_home), compiled(unit_move)


@compiled
def blob_widths(env, pos, heading, sensor, max_blobs):
    """The blobs of the mask rendered from `pos` with every valid landmark."""
    mask, _ = render(env, env.valid, pos, heading, sensor)
    return blob_runs(mask, max_blobs)


@compiled
def blob_counts(env, points):
    """The number of blobs (at most 4) seen at each point, heading 0."""
    return jax.vmap(lambda p: jnp.sum(blob_runs(render(env, env.valid, p, jnp.float32(0.0), Sensor())[0], 4)[2]))(
        points
    )


def alv_direction(sigma, point, env):
    """ALV's direction at `point` (heading 0.4, fixed keys) as a function of the bearing-noise sigma."""
    visible = jnp.ones(env.landmarks.shape[0], bool)
    sensor = eqx.tree_at(lambda s: s.noise.bearing, Sensor(), sigma)
    home = record_home(env, jax.random.PRNGKey(0), sensor)
    poses = map_poses(point, jnp.float32(0.4), jax.random.PRNGKey(1), 3, sensor)
    return direction_from(env, visible, poses, home, METHODS["alv"], sensor)[0]


alv_direction_grad, alv_direction = compiled(jax.grad(alv_direction)), compiled(alv_direction)


def test_a_module_with_settings_gives_the_public_api_numbers_and_a_traced_setting_reuses_the_program():
    env = delvjax.load_env("env1")
    method = DELV(levels=3, heading=Compass())
    vm = maps.vector_map(env, method, Sensor(d=50.0), spacing=100.0)
    api = delvjax.vector_map(env, method="delv-compass", levels=3, grid=Grid(spacing=100.0))
    assert np.array_equal(np.asarray(vm.direction), np.asarray(api.direction), equal_nan=True)
    module_api = delvjax.vector_map(
        env, method=method, sensor=Sensor(d=50.0), grid=Grid(spacing=100.0)
    )  # a module, no name
    assert np.array_equal(np.asarray(module_api.direction), np.asarray(vm.direction), equal_nan=True)
    compiled = maps._vector_map._cache_size()
    finer = maps.vector_map(env, eqx.tree_at(lambda m: m.levels, method, 6), Sensor(d=50.0), spacing=100.0)
    assert maps._vector_map._cache_size() == compiled  # levels is a traced leaf: no new program
    assert not np.array_equal(np.asarray(finer.direction), np.asarray(vm.direction), equal_nan=True)


def test_a_sweep_over_a_sensor_leaf_equals_the_single_maps():
    env = delvjax.load_env("env2")
    values = jnp.array([30.0, 80.0])
    swept = maps.sweep(env, DELV(), Sensor(), "d", values, spacing=100.0)
    for i, d in enumerate((30.0, 80.0)):
        one = maps.vector_map(env, DELV(), Sensor(d=d), spacing=100.0)
        assert np.array_equal(np.asarray(swept.direction[i]), np.asarray(one.direction), equal_nan=True)


def test_a_program_switches_method_by_its_traced_index():
    """Every landmark method of the twin tests (test_vs_twins.py runs them as one `MethodSet`) gives its
    own program's numbers bit for bit from a `MethodSet`."""
    env = delvjax.load_env("env1").arrays()
    prog, names = method_set("alv", ["delv", "delv-compass", "alv", "acv", "delv-visual", "alv-visual", "acv-visual"])
    for i, name in enumerate(names):
        chosen = eqx.tree_at(lambda p: p.index, prog, jnp.int32(i))
        a = maps.vector_map(env, chosen, Sensor(), spacing=100.0)
        b = maps.vector_map(env, METHODS[name], Sensor(), spacing=100.0)
        assert np.array_equal(np.asarray(a.direction), np.asarray(b.direction), equal_nan=True), name


def test_options_set_only_the_fields_a_method_has_and_name_the_bad_one():
    method, sensor = make_setup("delv-compass", levels=4, d=30.0, bearing_noise_deg=2.0)
    assert method.levels == 4 and sensor.d == 30.0 and math.isclose(sensor.noise.bearing, math.radians(2.0))
    warping, _ = make_setup("warping", n_alpha=36)
    assert warping.n_alpha == 36
    shared, _ = make_setup("alv", method_set=["delv-compass", "alv"], levels=4)  # DELV in the program takes it
    assert shared.methods[0].levels == 4 and configure(METHODS["alv"], levels=3) is METHODS["alv"]
    for method_name, bad in (
        ("delv", dict(levels=0)),
        ("delv", dict(d=-1.0)),
        ("warping", dict(n_psi=7)),
        ("delv", dict(unknown_option=1.0)),
        ("alv", dict(levels=3)),
        ("delv", dict(n_alpha=36)),
        ("warping", dict(blur_deg=2.0)),
    ):
        with pytest.raises(InputError) as err:
            make_setup(method_name, **bad)
        assert next(iter(bad)) in str(err.value)
    module, _ = make_setup(DELV(levels=2), sensor=Sensor(d=20.0))
    assert module.levels == 2
    with pytest.raises(InputError, match="d"):
        make_setup(DELV(), sensor=Sensor(), d=20.0)


def test_blob_widths_are_the_apparent_sizes_of_the_cylinders():
    """One cylinder of radius r at distance D subtends 2 asin(r / D); the run of mask pixels
    covers it to within two pixels."""
    sensor = Sensor()
    for x, r in ((200.0, 30.0), (350.0, 60.0), (800.0, 20.0)):
        env = delvjax.make_env([[x, 300.0, r]])
        _, width, valid = blob_widths(env.arrays(), jnp.array([100.0, 300.0]), jnp.float32(0.3), sensor, 1)
        true = 2.0 * math.asin(r / (x - 100.0))
        assert bool(valid[0]) and abs(float(width[0]) - true) <= 2 * 2 * math.pi / sensor.n_pix


def test_cartwright_collett_on_rendered_views_equals_its_twin():
    env = delvjax.load_env("env1").arrays()
    sensor = Sensor()
    home = record_home(env, jax.random.PRNGKey(0), sensor)
    rng = np.random.default_rng(3)
    for point in rng.uniform(150.0, 850.0, size=(12, 2)):
        view, _ = unit_move(
            env,
            jnp.asarray(point, jnp.float32),
            jnp.float32(rng.uniform(0, 2 * np.pi)),
            jax.random.PRNGKey(1),
            sensor,
            end_at=jnp.asarray(point, jnp.float32),
        )
        angle, valid = call(METHODS["cc"], home, view)
        c = float(view.compass)
        h, ok = cc_home_vector_ref(
            np.asarray(home.start.bearing),
            np.asarray(home.start.width),
            np.asarray(home.start.valid),
            np.asarray(view.end.bearing) + c,
            np.asarray(view.end.width),
            np.asarray(view.end.valid),
        )
        assert bool(valid) == ok
        if ok:
            expected = math.atan2(h[1], h[0]) - c
            assert abs(math.remainder(float(angle) - expected, 2 * math.pi)) < 1e-4


def test_gap_aware_delv_equals_delv_where_the_counts_agree_and_helps_with_a_landmark_hidden():
    """Where the current view shows as many blobs as the home view there is one subset: the same
    pairing as linear matching, bitwise. With a landmark hidden it skips the gap."""
    env = delvjax.load_env("env1")
    kw = dict(grid=Grid(spacing=100.0), seed=4)
    ref = delvjax.vector_map(env, method="delv-compass", **kw)
    blobs = blob_counts(env.arrays(), ref.points)
    same = np.asarray(blobs) == env.n_landmarks
    assert same.sum() > 50
    for linear, gapped in (("delv-compass", "delv-gap-compass"), ("delv", "delv-gap")):
        a, b = delvjax.vector_map(env, method=linear, **kw), delvjax.vector_map(env, method=gapped, **kw)
        assert np.array_equal(np.asarray(a.direction)[same], np.asarray(b.direction)[same], equal_nan=True)
    inc = np.asarray(ref.included)
    errors = {
        m: float(np.asarray(delvjax.vector_map(env, method=m, hidden=[1], **kw).error_deg)[inc].mean())
        for m in ("delv-compass", "delv-gap-compass")
    }
    assert errors["delv-gap-compass"] < 0.6 * errors["delv-compass"], errors


def test_the_gap_aware_module_is_delv_with_another_search():
    assert isinstance(DELVGap(), DELV)
    fields = {f.name for f in dataclasses.fields(DELVGap)}
    assert fields == {f.name for f in dataclasses.fields(DELV)}


def test_a_sensor_field_is_differentiable_through_the_kernel():
    """`eqx.tree_at` on a sensor leaf and `jax.grad` through the per-point kernel: the derivative of
    ALV's direction with respect to the bearing-noise sigma (pathwise, fixed keys) matches central
    finite differences."""
    env = delvjax.load_env("env1").arrays()

    checked = 0
    for point in (jnp.array([250.0, 700.0]), jnp.array([800.0, 300.0]), jnp.array([600.0, 850.0])):
        sigma, h = jnp.float32(0.02), 1e-3
        grad = float(alv_direction_grad(sigma, point, env))
        fd = (float(alv_direction(sigma + h, point, env)) - float(alv_direction(sigma - h, point, env))) / (2 * h)
        assert math.isfinite(grad)
        assert abs(grad - fd) <= 0.05 * abs(fd) + 1e-3, (point, grad, fd)
        checked += abs(fd) > 1e-2
    assert checked >= 1  # the derivative is not trivially zero everywhere
