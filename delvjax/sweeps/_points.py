"""Per-point errors of a vector-map sweep (docs/sweeps.md "Per-point errors"): every cell's angular error at
every grid point, for numbers a sum cannot give (error curves by distance from home, error rates inside and
outside a region such as the landmarks' hull). The same cells, validation, padding and grouping as
`run_sweep`; each group's cells in chunks of one compiled program (`core.cells.map_cells_errors`)."""

from __future__ import annotations

import jax
import numpy as np

from ..core.cells import map_cells_errors
from ..core.errors import InputError
from ..evaluate import _vector_map as api
from ._kinds import _traced, cell_setup, grid_inputs
from ._run import CELL_CHUNK, _envs, _plan
from ._spec import SweepSpec

QUANTUM = 8  # cells: a group smaller than a chunk is padded to a multiple of this


def point_errors(spec: SweepSpec, max_points: int = api.MAX_POINTS) -> dict:
    """The per-point errors of every cell of a vector-map sweep of one grid (one spacing, one arena):
    {"errors": (*spec.shape, P) degrees (invalid = 180, NaN where a point is not included), "points": (P, 2)
    cm, "homes": {env label: (2,) cm}, "landmarks": {env label: (L, 3) x, y, r cm}}. Chunks of CELL_CHUNK cells, the last padded to CELL_CHUNK, a group of
    fewer cells to a multiple of QUANTUM (sweeps whose counts differ by a few cells share their programs)."""
    if spec.kind != "vector-map":
        raise InputError("sweep.kind", str(spec.kind), 'must be "vector-map" for per-point errors')
    envs = _envs(spec)
    groups, _, _ = _plan(spec, envs, max_points, None)
    grids = {(float(c["spacing"]), tuple(np.asarray(envs[c["env"]].arena).tolist())) for c in spec.cells()}
    if len(grids) > 1:
        raise InputError("axes", sorted(grids), "per-point errors need one grid: one spacing and one arena")
    out, points = None, None
    stack = lambda *xs: np.stack([np.asarray(x) for x in xs])  # noqa: E731
    for cells in groups:  # one program per group, a few chunks each
        for start in range(0, len(cells), CELL_CHUNK):
            chunk = cells[start : start + CELL_CHUNK]
            size = CELL_CHUNK if len(cells) > CELL_CHUNK else -(-len(chunk) // QUANTUM) * QUANTUM
            padded = chunk + [chunk[0]] * (size - len(chunk))
            setups = [cell_setup(spec, envs, spec.cell(i), max_points) for i in padded]
            traced = jax.tree.map(stack, *[_traced(req) for req in setups])
            (points,), traced = grid_inputs(setups, traced)
            errors = np.asarray(map_cells_errors(traced[0], points, traced[4], *traced[1:4]))
            if out is None:
                out = np.full((spec.n_cells, len(points)), np.nan, np.float32)
            out[chunk] = errors[: len(chunk)]
    homes = {label: np.asarray(e.home, float) for label, e in envs.items()}
    landmarks = {label: np.asarray(e.landmarks, float)[np.asarray(e.valid)] for label, e in envs.items()}
    return {
        "errors": out.reshape(*spec.shape, -1),
        "points": np.asarray(points, float),
        "homes": homes,
        "landmarks": landmarks,
    }
