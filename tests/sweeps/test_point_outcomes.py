"""Per-point outcomes of a catchment sweep (`delvjax.sweeps.point_outcomes`): the trials `run_sweep` sums, point by
point (docs/sweeps.md "Per-point errors")."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.core.errors import InputError
from delvjax.evaluate._vector_map import MAX_POINTS
from delvjax.sweeps import point_outcomes, run_sweep
from delvjax.sweeps._run import _envs, _plan
from delvjax.sweeps._spec import parse_sweep

CATCHMENTS = """
[sweep]
kind = "catchment"
metrics = ["catchment_pct", "catchment_physical_pct", "catchment_points"]
[axes]
env = [{ensemble = "env1", members = 2, seed = 3}, "env3"]
method = ["delv", "alv"]
occlude = [0, 1]
spacing = [150]
seed = [4]
"""


def test_per_point_outcomes_are_the_trials_the_sweep_sums():
    spec = parse_sweep(CATCHMENTS)
    res = point_outcomes(spec)
    ds = run_sweep(spec)
    ok, counted, trials = res["successes"], res["counted"], res["trials"]
    assert ok.shape == counted.shape == trials.shape == (*spec.shape, len(res["points"]))
    assert (ok <= trials).all() and (res["untouched"] <= ok).all()
    shape = ds.catchment_pct.shape  # the Dataset drops the axes of one value
    np.testing.assert_array_equal(counted.sum(axis=-1).reshape(shape), ds.catchment_points.values)
    for name, var in (("successes", "catchment_pct"), ("untouched", "catchment_physical_pct")):
        pct = 100.0 * (res[name] * counted).sum(axis=-1) / (trials * counted).sum(axis=-1)
        np.testing.assert_allclose(pct.reshape(shape), ds[var].values, rtol=1e-6)
    assert len(set(ds.catchment_pct.values.reshape(-1).tolist())) > 2  # the cells differ
    per_point = ok[counted] / trials[counted]
    assert 0 < per_point.mean() < 1 and ((per_point == 0) | (per_point == 1)).mean() < 1  # not all one outcome
    assert set(res["landmarks"]) == set(spec.axes["env"])


def test_per_point_outcomes_need_a_catchment_sweep():
    maps = '[sweep]\nkind = "vector-map"\n[axes]\nenv = ["env1"]\nmethod = ["delv"]\nspacing = [150]\n'
    with pytest.raises(InputError):
        point_outcomes(parse_sweep(maps))
    with pytest.raises(InputError):
        point_outcomes(parse_sweep(CATCHMENTS.replace("spacing = [150]", "spacing = [150, 200]")))


def test_a_named_program_puts_image_and_landmark_methods_in_one_group():
    spec = parse_sweep(CATCHMENTS.replace('method = ["delv", "alv"]', 'method = ["delv", "warping"]'))
    envs = _envs(spec)
    alone, _, _ = _plan(spec, envs, MAX_POINTS, None)
    shared, _, _ = _plan(spec, envs, MAX_POINTS, None, ("delv", "warping"))
    assert len(alone) == 2 and len(shared) == 1  # an image method compiles alone unless a program names it
    assert sorted(shared[0]) == list(range(spec.n_cells))
