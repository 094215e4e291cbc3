"""One table schema per result type (docs/model.md §7), used by the CLI and the studies alike: each
result type owns its columns (`columns()`, `to_dataframe()`; defined beside the type), gathered here
with the pandas / xarray views of any result (`delvjax.to_dataframe`, `delvjax.to_xarray`).
"""

from __future__ import annotations

import numpy as np

from .errors import InputError
from .maps import VectorMap, vector_map_columns
from .rollouts.catchment import Catchment, catchment_columns
from .rollouts.rules import OUTCOME_NAMES, outcome_names, rule_columns
from .rollouts.success import SuccessRate, success_rows, success_trial_columns
from .rollouts.trajectories import Trajectories, trajectory_columns

__all__ = [
    "OUTCOME_NAMES",
    "catchment_columns",
    "concat_columns",
    "outcome_names",
    "rule_columns",
    "success_rows",
    "success_trial_columns",
    "to_dataframe",
    "to_xarray",
    "trajectory_columns",
    "vector_map_columns",
]
RESULTS = (VectorMap, Catchment, SuccessRate, Trajectories)  # the result types with a table


def concat_columns(tables: list[dict]) -> dict[str, list]:
    """Columns of several tables of one schema, one after the other."""
    return {k: [v for c in tables for v in np.asarray(c[k], dtype=object).tolist()] for k in tables[0]}


def to_dataframe(result, method: str = ""):
    """A result as a pandas DataFrame with the columns of its CSV file: a `VectorMap` per grid point, a
    `Catchment` per grid point and mask (with the hidden landmarks), a `SuccessRate` per trial,
    `Trajectories` per visited position (`result.to_dataframe(method)`). `method` fills the method
    column where there is one."""
    if not isinstance(result, RESULTS):
        raise InputError("result", type(result).__name__, f"must be a {' or '.join(t.__name__ for t in RESULTS)}")
    return result.to_dataframe(method)


def to_xarray(result: VectorMap):
    """A `VectorMap` as an `xarray.Dataset` over (y, x) in cm (`VectorMap.to_xarray`)."""
    if not isinstance(result, VectorMap):
        raise InputError("result", type(result).__name__, "must be a VectorMap (rollout results: to_dataframe)")
    return result.to_xarray()
