"""Config objects at the edge (evaluate/_config.py): `Grid`, `Rules`, `Sensor` and `Noise` describe a
run as objects and give the numbers of the keywords they stand for; a keyword beside its object is
refused, naming it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import delvjax
from delvjax import DELV, Compass, Grid, InputError, Noise, Rules, Sensor

KW = dict(spacing=200.0, heading_deg=30.0, first_move="homing", max_steps=60, bearing_noise_deg=2.0, d=40.0)


def test_objects_give_the_numbers_of_their_keywords():
    method = DELV(heading=Compass())
    by_keywords = delvjax.catchment("env1", method, seed=3, **KW)
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
    vm_kw = delvjax.vector_map("env1", "alv", spacing=200.0, heading_deg=30.0)
    vm_obj = delvjax.vector_map("env1", "alv", grid=Grid(spacing=200.0, heading_deg=30.0))
    assert np.array_equal(np.asarray(vm_kw.error_deg), np.asarray(vm_obj.error_deg))


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: delvjax.vector_map("env1", grid=Grid(spacing=200.0), spacing=100.0), "spacing"),
        (lambda: delvjax.catchment("env1", rules=Rules(max_steps=10), max_steps=20, spacing=200.0), "max_steps"),
        (lambda: delvjax.vector_map("env1", noise=Noise(), bearing_noise_deg=1.0, spacing=200.0), "bearing_noise_deg"),
        (lambda: delvjax.vector_map("env1", grid={"spacing": 100}), "grid"),
        (lambda: delvjax.vector_map("env1", noise=0.1), "noise"),
        (lambda: delvjax.catchment("env1", rules=Rules(first_move="later"), spacing=200.0), "first_move"),
    ],
)
def test_a_keyword_beside_its_object_or_a_bad_object_is_refused(call, field, untyped):
    with pytest.raises(InputError) as info:
        call()
    assert info.value.field == field
