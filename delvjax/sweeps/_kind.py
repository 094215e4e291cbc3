"""The kinds of sweep (docs/sweeps.md): each is one object that knows its name (what a sweep file
says; a `SweepKind` is that string), its metrics, whether it has a grid, rollout axes and a
`distance_cm` dimension, the per-cell sums its program returns, how a cell is validated, its
program, and its metrics from the sums. Nothing else compares a kind's name."""

from __future__ import annotations

from collections.abc import Callable

from ..core import metrics as table
from ..core.cells import CellMetrics
from ..core.rollouts.cells import CatchmentSums, SuccessSums
from ._kinds import (
    catchment_inputs,
    catchment_program,
    distance_inputs,
    grid_inputs,
    map_program,
    map_request,
    rollout_request,
    success_program,
)
from ._results import catchment_metrics, error_metrics, success_metrics


class SweepKind(str):
    """A kind of sweep: its name, and what it knows (see the module docstring)."""

    metrics: dict[str, str]
    grid: bool
    rollouts: bool
    per_distance: bool
    sums: type
    request: Callable  # (env, cell, spec, max_points) -> the validated setup of a cell
    inputs: Callable  # (setups, traced) -> (shared, traced) arguments of the program
    program: Callable  # (lanes, trials) -> the per-chunk program (max_steps comes traced, in `inputs`)
    metrics_of: Callable[[dict], dict]
    cell_seconds: Callable  # (spec) -> rough warm seconds of one cell on 2 CPU cores, for the stated estimate

    def __new__(cls, name: str, **known):
        self = super().__new__(cls, name)
        self.__dict__.update(known)
        return self


# name -> description of each kind's metrics, from the one metrics table (`core.metrics.METRICS`)
ERROR_METRICS = {m.name: m.description for m in table.MAP_METRICS}
CATCHMENT_METRICS = {m.name: m.description for m in table.CATCHMENT_METRICS}
SUCCESS_METRICS = {m.name: m.description for m in table.SUCCESS_METRICS}


VECTOR_MAP = SweepKind(
    "vector-map",
    metrics=ERROR_METRICS,
    grid=True,
    rollouts=False,
    per_distance=False,
    sums=CellMetrics,
    request=map_request,
    inputs=grid_inputs,
    program=map_program,
    metrics_of=lambda sums: error_metrics(sums, sums["points"]),
    cell_seconds=lambda spec: 0.02,  # README: 1000 env1 DELV vector maps (25 cm) in 20.5 s on 2 CPU cores
)
CATCHMENT = SweepKind(
    "catchment",
    metrics={
        **CATCHMENT_METRICS,
        **{k: v.replace("grid points", "first directions (points x masks)") for k, v in ERROR_METRICS.items()},
    },
    grid=True,
    rollouts=True,
    per_distance=False,
    sums=CatchmentSums,
    request=rollout_request,
    inputs=catchment_inputs,
    program=catchment_program,
    metrics_of=catchment_metrics,
    cell_seconds=lambda spec: 0.5,  # README: a DELV catchment cell (1559 rollouts) 0.2-0.7 s
)
SUCCESS_RATE = SweepKind(
    "success-rate",
    metrics=SUCCESS_METRICS,
    grid=False,
    rollouts=True,
    per_distance=True,
    sums=SuccessSums,
    request=rollout_request,
    inputs=distance_inputs,
    program=success_program,
    metrics_of=success_metrics,
    cell_seconds=lambda spec: len(spec.distances) * spec.trials * 1.5e-3,  # a rollout trial: at most 1.5 ms
)
KINDS = {k: k for k in (VECTOR_MAP, CATCHMENT, SUCCESS_RATE)}  # name -> kind
