"""Config objects (core/rollouts/config.py): `Grid`, `Rules`, `Sensor` and `Noise` describe a
run as objects and give the numbers of the keywords they stand for; a keyword beside its object is
refused, naming it."""

from __future__ import annotations

import inspect
import math
import warnings
from pathlib import Path

import equinox as eqx
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import DELV, Compass, Grid, InputError, Noise, Rules, Sensor

KW = dict(spacing=200.0, heading_deg=30.0, first_move="homing", max_steps=60, bearing_noise_deg=2.0, d=40.0)


def test_the_old_keywords_still_work_with_a_deprecation_warning_and_the_same_numbers():
    """The flat keywords of earlier releases build the same `Grid` and `Rules` (one release more), with a
    DeprecationWarning that names them and points at the caller's line (not at delvjax)."""
    method = DELV(heading=Compass())
    with pytest.deprecated_call() as record:
        by_keywords = delvjax.catchment("env1", method, seed=3, **KW)
    assert ["spacing, heading_deg" in str(w.message) for w in record] == [True, False]
    assert "max_steps, first_move" in str(record[1].message)
    assert {Path(w.filename).name for w in record} == {Path(__file__).name}
    by_objects = delvjax.catchment(
        "env1",
        method,
        sensor=Sensor(d=40.0),
        noise=Noise(bearing=math.radians(2.0)),
        grid=Grid(spacing=200.0, heading_deg=30.0),
        rules=Rules(first_move="homing", max_steps=60),
        seed=3,
    )
    assert np.array_equal(np.asarray(by_keywords.outcome), np.asarray(by_objects.outcome))
    assert np.array_equal(np.asarray(by_keywords.steps), np.asarray(by_objects.steps))
    assert by_keywords.grid == by_objects.grid == Grid(spacing=200.0, heading_deg=30.0)
    with pytest.deprecated_call(match="announce"):
        delvjax.catchment("env1", "alv", grid=Grid(spacing=400.0), announce=lambda: None)
    with pytest.deprecated_call(match="spacing, heading_deg"):
        vm_kw = delvjax.vector_map("env1", "alv", spacing=200.0, heading_deg=30.0)
    vm_obj = delvjax.vector_map("env1", "alv", grid=Grid(spacing=200.0, heading_deg=30.0))
    assert np.array_equal(np.asarray(vm_kw.error_deg), np.asarray(vm_obj.error_deg))


def test_the_objects_travel_unchanged_to_the_core(monkeypatch):
    """`catchment` hands the user's `Grid` and `Rules` themselves to `core.rollouts.catchment_area`
    (no unpacking into keywords on the way), and the result carries its grid."""
    seen = {}
    real = delvjax.evaluate._rollouts.catchment_area

    def spy(env, method, sensor, grid, rules, **kw):
        seen.update(grid=grid, rules=rules)
        return real(env, method, sensor, grid, rules, **kw)

    monkeypatch.setattr(delvjax.evaluate._rollouts, "catchment_area", spy)
    grid, rules = Grid(spacing=400.0, heading_deg=10.0), Rules(max_steps=5, lanes=16)
    result = delvjax.catchment("env1", "alv", grid=grid, rules=rules)
    assert seen["grid"] is grid and seen["rules"] is rules
    assert result.grid is grid


def test_wide_public_calls_are_keyword_only_and_narrow():
    """After the environment and the method every argument is named, and the catchment call takes at
    most 12 named parameters (issue 55: 19 plus **options before)."""
    for call in (delvjax.catchment, delvjax.success_rate, delvjax.trajectories, delvjax.vector_map):
        params = list(inspect.signature(call).parameters.values())
        assert [p.name for p in params[:2]] == ["env", "method"], call
        assert all(p.kind in (p.KEYWORD_ONLY, p.VAR_KEYWORD) for p in params[2:]), call
    assert len([p for p in inspect.signature(delvjax.catchment).parameters.values() if p.kind != p.VAR_KEYWORD]) <= 12
    with pytest.deprecated_call() as record:  # the old positional spacing: named for one release more
        result = delvjax.catchment("env1", "alv", 400.0)
    assert "spacing by position" in str(record[0].message) and result.grid == Grid(spacing=400.0)


@pytest.mark.parametrize("call, obj, keyword", [(delvjax.vector_map, Grid(spacing=200.0), "grid"),
                                                (delvjax.catchment, Rules(max_steps=5), "rules")])  # fmt: skip
def test_a_settings_object_by_position_names_its_keyword(call, obj, keyword):
    """A Grid where the old positional spacing was once read as spacing=Grid(...), with advice to pass
    grid=Grid(spacing=Grid(...)); now one TypeError names the keyword, before any deprecation warning."""
    kind = type(obj).__name__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(TypeError, match=rf"takes a {kind} by name only: {keyword}={kind}\(\.\.\.\)"):
            call("env1", "delv", obj)


@pytest.mark.parametrize(
    "build, field",
    [
        (lambda: Grid(spacing=0.0), "spacing"),
        (lambda: Grid(clearance=-1.0), "clearance"),
        (lambda: Grid(heading_deg=float("inf")), "heading_deg"),
        (lambda: Rules(max_steps=2.5), "max_steps"),
        (lambda: Rules(home_radius=-5.0), "home_radius"),
        (lambda: Rules(first_move="walk"), "first_move"),
        (lambda: Rules(collisions=None), "collisions"),
        (lambda: Rules(lanes=0), "lanes"),
    ],
)
def test_a_config_object_checks_its_fields_when_built(build, field):
    with pytest.raises(InputError) as info:
        build()
    assert info.value.field == field


def test_config_objects_are_equinox_modules_that_compare_and_hash_by_value():
    assert isinstance(Grid(), eqx.Module) and isinstance(Rules(), eqx.Module)
    assert Grid(spacing=50) == Grid(spacing=50.0) and hash(Grid(spacing=50)) == hash(Grid(spacing=50.0))
    assert Rules(max_steps=7) != Rules() and Rules().recorded == {"first_move": "release", "collisions": "ignore"}
    assert Grid(heading_deg=390.0).heading_deg == 30.0  # reduced in float64, as the keyword was


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: delvjax.vector_map("env1", grid=Grid(spacing=200.0), spacing=100.0), "spacing"),
        (
            lambda: delvjax.catchment("env1", rules=Rules(max_steps=10), max_steps=20, grid=Grid(spacing=200.0)),
            "max_steps",
        ),
        (
            lambda: delvjax.vector_map("env1", noise=Noise(), bearing_noise_deg=1.0, grid=Grid(spacing=200.0)),
            "bearing_noise_deg",
        ),
        (lambda: delvjax.vector_map("env1", grid={"spacing": 100}), "grid"),
        (lambda: delvjax.vector_map("env1", noise=0.1), "noise"),
        (lambda: delvjax.catchment("env1", rules=Rules(first_move="later"), grid=Grid(spacing=200.0)), "first_move"),
    ],
)
def test_a_keyword_beside_its_object_or_a_bad_object_is_refused(call, field, untyped):
    with pytest.raises(InputError) as info:
        call()
    assert info.value.field == field


def test_results_carry_the_grid_they_were_computed_on():
    """Issue 55: a `VectorMap` carries its `Grid` (as a `Catchment` does), so a figure needs no spacing=."""
    from delvjax.core import maps
    from delvjax.plots import vector_map_figure

    grid = Grid(spacing=250, heading_deg=30)
    vm = delvjax.vector_map("env1", "alv", grid=grid)
    assert vm.grid is grid and vm.spacing == 250.0
    assert delvjax.vector_map("env1", "alv", grid=Grid(spacing=500)).grid == Grid(spacing=500)
    c = delvjax.catchment("env1", "alv", grid=Grid(spacing=500))
    assert c.grid == Grid(spacing=500)
    env = delvjax.load_env("env1")
    swept = maps.sweep(
        env, delvjax.options.get_method("delv"), Sensor(), "levels", jnp.asarray([2.0, 3.0]), spacing=500.0
    )
    assert swept.grid == Grid(spacing=500.0)  # heading None: random per point, as given
    fixed = maps.vector_map(env, delvjax.options.get_method("alv"), Sensor(), spacing=500.0, heading=math.radians(90.0))
    assert fixed.grid.heading_deg == pytest.approx(90.0)
    vector_map_figure(env, vm).clf()  # the arrows' length from the map's own grid
    with pytest.raises(InputError, match="not used by a vector map"):  # says why, not just "unknown"
        delvjax.vector_map("env1", "alv", rules=Rules())
