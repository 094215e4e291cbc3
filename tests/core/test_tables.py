"""`delvjax.to_dataframe` and the `.to_dataframe()` of every result: a pandas DataFrame with the
columns of its CSV file; `VectorMap.to_xarray()`: the map as labelled data."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core.tables import catchment_columns, success_trial_columns, trajectory_columns, vector_map_columns


def test_every_result_becomes_the_table_of_its_csv():
    vm = delvjax.vector_map("env1", grid=Grid(spacing=200.0))
    c = delvjax.catchment("env1", occlude=1, grid=Grid(spacing=200.0))
    sr = delvjax.success_rate("env1", distances=[100.0], trials=4)
    tr = delvjax.trajectories("env1", starts=[(300.0, 300.0)], rules=Rules(max_steps=10))
    for result, columns in [
        (vm, vector_map_columns(vm)),
        (c, catchment_columns(c, with_hidden=True)),
        (sr, success_trial_columns(sr, "delv")),
        (tr, trajectory_columns(tr, "delv")),
    ]:
        df = delvjax.to_dataframe(result, "delv")
        assert list(df.columns) == list(columns)
        own = result.to_dataframe() if result is vm else result.to_dataframe("delv")  # the method, the same table
        assert own.equals(df)
        first = next(iter(columns.values()))
        assert len(df) == len(first) and np.array_equal(df[next(iter(columns))].to_numpy(), np.asarray(first))
    assert set(delvjax.to_dataframe(c)["hidden"]) == {"0", "1", "2", "3"}  # one row per point and hidden landmark


def test_something_else_is_refused_by_name():
    with pytest.raises(delvjax.InputError, match="result"):
        delvjax.to_dataframe({"x": [1]})


def test_a_vector_map_as_xarray_is_its_grid_in_centimetres():
    vm = delvjax.vector_map("env1", seed=3, grid=Grid(spacing=100.0))
    ds = vm.to_xarray()
    assert dict(ds.sizes) == {"y": 10, "x": 10} and ds.x.values.tolist() == [50.0 + 100 * i for i in range(10)]
    pts = np.asarray(vm.points)
    k = 37  # a cell: row 3, column 7
    cell = ds.sel(x=pts[k, 0], y=pts[k, 1])
    assert float(cell.error_deg) == float(np.asarray(vm.error_deg)[k])
    assert bool(cell.included) == bool(np.asarray(vm.included)[k])
    assert ds.error_deg.attrs["units"] == "degree" and ds.x.attrs["units"] == "cm"
    invalid = ~ds.valid.values
    assert np.isnan(ds.direction_deg.values[invalid]).all()  # undefined directions stay NaN, marked invalid
    assert delvjax.to_xarray(vm).identical(ds)


def test_scattered_points_become_a_point_dimension():
    vm = delvjax.vector_map("env1", grid=Grid(spacing=100.0))
    scattered = type(vm)(
        points=vm.points[::-1], included=vm.included, heading=vm.heading, direction=vm.direction,
        valid=vm.valid, error_deg=vm.error_deg,
    )  # fmt: skip
    ds = scattered.to_xarray()
    assert dict(ds.sizes) == {"point": 100} and np.array_equal(ds.x.values, np.asarray(vm.points)[::-1, 0])
