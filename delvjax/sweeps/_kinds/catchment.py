"""The catchment kind of sweep (docs/sweeps.md "Rollout sweeps"): a rollout from every grid point of each cell,
under every visibility mask (`core.rollouts.cells.catchment_cells`); its metrics are the catchment's and the
vector map's over the first directions. Also the rollout request the success-rate kind shares."""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence

import numpy as np

from ...core import metrics as table
from ...core.rollouts import catchment_counted
from ...core.rollouts import cells as rollout_programs
from ...evaluate import _rollouts as api_rollouts
from .base import MAP_METRICS, Sweep, SweepKind, descriptions, options, pct, validated
from .vector_map import error_metrics, grid_inputs


def rollout_request(kind: str, env, cell: dict, spec: Sweep, max_points: int, method_set=None) -> dict:
    """A catchment or success-rate cell, validated as `delvjax.catchment` / `success_rate` validate theirs."""
    request = functools.partial(api_rollouts.rollout_request, env)
    common = dict(seed=cell["seed"], distances=spec.distances, trials=spec.trials, max_points=max_points)
    return validated(request, cell, spec, method_set, kind=kind, **common, **options(cell))


def catchment_metrics(sums: dict) -> dict:
    """Catchment % (mean, worst and best mask), failure rates and mean moves of the successes."""
    trials, points, counted = sums["trials"], sums["counted_points"], sums["counted"]
    with np.errstate(invalid="ignore", divide="ignore"):
        steps = np.where(sums["successes"] > 0, sums["steps_success"] / np.maximum(sums["successes"], 1), np.nan)
    # the vector map's rates over every released trial; the catchment over the counted ones (docs/model.md §5)
    return {
        **error_metrics(sums, trials),
        "catchment_pct": pct(sums["successes"], counted),
        "catchment_physical_pct": pct(sums["successes_untouched"], counted),
        "catchment_min_pct": pct(sums["success_min"], points),
        "catchment_max_pct": pct(sums["success_max"], points),
        "timeout_pct": pct(sums["timeout"], counted),
        "landmark_pct": pct(sums["landmark"], counted),
        "arena_pct": pct(sums["arena"], counted),
        "mean_steps_success": steps,
        "catchment_points": sums["counted_points"].astype(np.int64),
    }


def catchment_inputs(setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
    """(shared, traced) of a catchment chunk: the grid's and max_steps (a traced number: one program for
    every value), and the points each cell counts."""
    shared, traced = grid_inputs(setups, traced)
    points, included = shared[0], traced[-1]
    counted = np.stack(
        [
            catchment_counted(req["env"].arena, points, inc, req["first_move"], req["sensor"].d)
            for req, inc in zip(setups, included)
        ]
    )
    return (points, np.int32(setups[0]["max_steps"])), traced + (counted,)


# the vector map's metrics, counted over a catchment's first directions
_FIRST_DIRECTIONS = {k: v.replace("grid points", "first directions (points x masks)") for k, v in MAP_METRICS.items()}


class Catchment(SweepKind):
    """A catchment area per cell (Tables 5.3/5.4)."""

    name = "catchment"
    metrics = {**descriptions(table.CATCHMENT_METRICS), **_FIRST_DIRECTIONS}
    grid, rollouts, per_distance = True, True, False
    sums = rollout_programs.CatchmentSums

    def request(self, env, cell: dict, spec: Sweep, max_points: int, method_set: Sequence[str] | None = None) -> dict:
        return rollout_request(self.name, env, cell, spec, max_points, method_set)

    def inputs(self, setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
        return catchment_inputs(setups, traced)

    def program(self, lanes: int, trials: int | None) -> Callable:
        return lambda points, max_steps, cells, included, counted: rollout_programs.catchment_cells(
            cells, points, included, counted, max_steps, lanes=lanes
        )

    def metrics_of(self, sums: dict) -> dict:
        return catchment_metrics(sums)

    def cell_seconds(self, spec: Sweep) -> float:
        return 0.5  # README: a DELV catchment cell (1559 rollouts) 0.2-0.7 s


CATCHMENT = Catchment()
