"""The vector-map kind of sweep (docs/sweeps.md): each cell a vector map over a grid, summed per cell
(`core.cells.map_cells`); its metrics are the error point rates, the mean error and the invalid rate."""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence

import numpy as np

from ...core import cells as map_cells
from ...core.maps import grid_included, grid_points
from ...core.metrics import t_quantile
from ...evaluate import _vector_map as api
from .base import MAP_METRICS, Sweep, SweepKind, options, pct, validated


def error_metrics(sums: dict, n: np.ndarray) -> dict:
    """Error point rates, mean error with its Student-t 95 % half-width, invalid rate over `n` directions."""
    pts = np.maximum(n, 1)
    mean = sums["error_sum"] / pts
    var = np.maximum(sums["error_sq_sum"] - pts * mean**2, 0.0) / np.maximum(pts - 1, 1)
    half = t_quantile(n) * np.sqrt(var / pts)
    return {
        "gt45_pct": pct(sums["gt45"], n),
        "gt90_pct": pct(sums["gt90"], n),
        "mean_error_deg": np.where(n > 0, mean, np.nan),
        "mean_error_ci95_deg": np.where(n >= 2, half, np.nan),
        "invalid_pct": pct(sums["invalid"], n),
        "points": sums["points"].astype(np.int64),
    }


def grid_inputs(setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
    """(shared, traced) of a chunk over a grid: the grid points shared, each cell's included points."""
    first = setups[0]
    points = grid_points(first["env"].arena, first["spacing"])
    included = np.stack(_masks(setups, points))
    return (points,), traced + (included,)


def _masks(setups: list[dict], points) -> list[np.ndarray]:
    """Each cell's grid mask (`grid_included`), computed once for the cells of one world and clearance."""
    known: dict[tuple, np.ndarray] = {}
    for req in setups:
        key = (id(req["env"]), float(req["clearance"]))  # the setups live through the call: ids are unique
        if key not in known:
            known[key] = np.asarray(grid_included(req["env"], points, req["clearance"]))
    return [known[(id(req["env"]), float(req["clearance"]))] for req in setups]


class VectorMap(SweepKind):
    """A vector map per cell, validated as `delvjax.vector_map` validates its keywords."""

    name = "vector-map"
    metrics = MAP_METRICS
    grid, rollouts, per_distance = True, False, False
    sums = map_cells.CellMetrics

    def request(self, env, cell: dict, spec: Sweep, max_points: int, method_set: Sequence[str] | None = None) -> dict:
        request = functools.partial(api.map_request, env)
        return validated(request, cell, spec, method_set, seed=cell["seed"], max_points=max_points, **options(cell))

    def inputs(self, setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
        return grid_inputs(setups, traced)

    def program(self, lanes: int, trials: int | None) -> Callable:
        return lambda points, envs, methods, sensors, keys, live, included: map_cells.map_cells(
            envs, points, included, methods, sensors, keys, live
        )

    def metrics_of(self, sums: dict) -> dict:
        return error_metrics(sums, sums["points"])

    def cell_seconds(self, spec: Sweep) -> float:
        return 0.02  # README: 1000 env1 DELV vector maps (25 cm) in 20.5 s on 2 CPU cores


VECTOR_MAP = VectorMap()
