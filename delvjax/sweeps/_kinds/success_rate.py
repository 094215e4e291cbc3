"""The success-rate kind of sweep (docs/sweeps.md "Rollout sweeps"): trials released at each distance from home
(`core.rollouts.cells.success_cells`); its metrics are the success rate per distance with its Wilson interval
(a `distance_cm` dimension)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ...core import metrics as table
from ...core.rollouts import cells as rollout_programs
from ...core.rollouts.success import wilson_pct
from .base import Sweep, SweepKind, descriptions, pct
from .catchment import rollout_request


def success_metrics(sums: dict) -> dict:
    """Success % per distance with its Wilson interval, and the trials placed."""
    lo, hi = wilson_pct(sums["successes"], sums["placed"])
    return {
        "success_pct": pct(sums["successes"], sums["placed"]),
        "success_ci95_lo_pct": lo,
        "success_ci95_hi_pct": hi,
        "placed": sums["placed"].astype(np.int64),
    }


class SuccessRate(SweepKind):
    """Success rate per release distance (Figs 4.10b, 5.7b)."""

    name = "success-rate"
    metrics = descriptions(table.SUCCESS_METRICS)
    grid, rollouts, per_distance = False, True, True
    sums = rollout_programs.SuccessSums

    def request(self, env, cell: dict, spec: Sweep, max_points: int, method_set: Sequence[str] | None = None) -> dict:
        return rollout_request(self.name, env, cell, spec, max_points, method_set)

    def inputs(self, setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
        """The release distances, clearance and max_steps shared."""
        first = setups[0]
        distances = np.asarray(first["distances"], np.float32)
        return (distances, np.float32(first["clearance"]), np.int32(first["max_steps"])), traced

    def program(self, lanes: int, trials: int | None) -> Callable:
        return lambda distances, clearance, max_steps, cells: rollout_programs.success_cells(
            cells, distances, clearance, trials=trials, max_steps=max_steps, lanes=lanes
        )

    def metrics_of(self, sums: dict) -> dict:
        return success_metrics(sums)

    def cell_seconds(self, spec: Sweep) -> float:
        return len(spec.distances) * spec.trials * 1.5e-3  # a rollout trial: at most 1.5 ms


SUCCESS_RATE = SuccessRate()
