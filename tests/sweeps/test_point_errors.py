"""Per-point errors of a vector-map sweep (`delvjax.sweeps.point_errors`) and the catchment restated under
the physical rules (`catchment_physical_pct`): the same numbers as the sums of `run_sweep`, and as a run
under collisions = "fail" (docs/sweeps.md)."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.core.errors import InputError
from delvjax.sweeps import point_errors, run_sweep
from delvjax.sweeps._spec import parse_sweep

MAPS = """
[sweep]
kind = "vector-map"
[axes]
env = [{ensemble = "env1", members = 2, seed = 3}, "env3"]
method = ["delv", "alv", "warping"]
spacing = [100]
seed = [5]
"""


def test_per_point_errors_are_the_errors_the_sweep_sums():
    spec = parse_sweep(MAPS)
    res = point_errors(spec)
    ds = run_sweep(spec)
    err = res["errors"]
    assert err.shape == (*spec.shape, len(res["points"]))
    inc = ~np.isnan(err)
    assert inc.sum(axis=-1).reshape(-1).tolist() == ds.points.values.reshape(-1).tolist()
    mean = np.nanmean(err, axis=-1).reshape(ds.mean_error_deg.shape)
    np.testing.assert_allclose(mean, ds.mean_error_deg.values, rtol=1e-5)
    gt45 = 100.0 * (err > 45).sum(axis=-1) / inc.sum(axis=-1)
    np.testing.assert_allclose(gt45.reshape(ds.gt45_pct.shape), ds.gt45_pct.values, atol=1e-9)
    assert set(res["homes"]) == set(spec.axes["env"])
    assert len({float(m) for m in mean.reshape(-1)}) > 3  # the cells differ: not one cell's errors repeated


def test_per_point_errors_need_a_vector_map_sweep_of_one_grid():
    with pytest.raises(InputError):
        point_errors(parse_sweep(MAPS.replace("spacing = [100]", "spacing = [100, 200]")))
    with pytest.raises(InputError):
        point_errors(parse_sweep(MAPS.replace('"vector-map"', '"catchment"')))


def test_the_restated_physical_catchment_is_the_catchment_under_collisions_fail():
    text = """
[sweep]
kind = "catchment"
metrics = ["catchment_pct", "catchment_physical_pct"]
[axes]
env = [{ensemble = "env1", members = 3, seed = 1}, "env2"]
method = ["delv", "alv"]
collisions = ["ignore", "fail"]
spacing = [100]
seed = [2]
"""
    ds = run_sweep(parse_sweep(text))
    ignore, fail = (ds.sel({"collisions": c}) for c in ("ignore", "fail"))
    np.testing.assert_array_equal(ignore.catchment_physical_pct.values, fail.catchment_pct.values)
    np.testing.assert_array_equal(fail.catchment_physical_pct.values, fail.catchment_pct.values)
    assert (ignore.catchment_physical_pct.values < ignore.catchment_pct.values).any()  # some trials touch a landmark
