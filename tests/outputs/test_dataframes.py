"""`delvjax.to_dataframe`: every result as a pandas DataFrame with the columns of its CSV file."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax.outputs._tables import catchment_columns, success_trial_columns, trajectory_columns, vector_map_columns


def test_every_result_becomes_the_table_of_its_csv():
    vm = delvjax.vector_map("env1", spacing=200.0)
    c = delvjax.catchment("env1", spacing=200.0, occlude=1)
    sr = delvjax.success_rate("env1", distances=[100.0], trials=4)
    tr = delvjax.trajectories("env1", starts=[(300.0, 300.0)], max_steps=10)
    for result, columns in [
        (vm, vector_map_columns(vm)),
        (c, catchment_columns(c, with_hidden=True)),
        (sr, success_trial_columns(sr, "delv")),
        (tr, trajectory_columns(tr, "delv")),
    ]:
        df = delvjax.to_dataframe(result, "delv")
        assert list(df.columns) == list(columns)
        first = next(iter(columns.values()))
        assert len(df) == len(first) and np.array_equal(df[next(iter(columns))].to_numpy(), np.asarray(first))
    assert set(delvjax.to_dataframe(c)["hidden"]) == {"0", "1", "2", "3"}  # one row per point and hidden landmark


def test_something_else_is_refused_by_name():
    with pytest.raises(delvjax.InputError, match="result"):
        delvjax.to_dataframe({"x": [1]})
