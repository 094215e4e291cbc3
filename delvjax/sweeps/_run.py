"""Running a sweep (docs/sweeps.md): every cell validated first, cells grouped by shape, one compiled
program per shape called on chunks of cells, split over the local devices and dealt over the
processes, finished chunks kept on disk; results as labelled data (`_results.py`)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import jax
import numpy as np

from ..core.batching import global_mesh, local_mesh, n_devices, process_rows
from ..core.deprecation import keywords_after, refuse_unknown, renamed_keyword
from ..core.rollouts import DEFAULT_LANES
from ..envs._presets import env_from_dict, load_env, random_env
from ..evaluate import _vector_map as api
from ..evaluate._progress import Progress, with_callbacks
from ..options._setup import METHOD_SET_WHY
from ._kinds import cell_setup, evaluate, group_key, mask_rows, programs_compiled, sum_names
from ._results import dataset, load_sweep, save_sweep, sweep_inputs
from ._spec import SweepSpec
from ._store import cell_digest, code_digest, load_cells, save_cells

__all__ = ["CELL_CHUNK", "load_sweep", "run_sweep", "save_sweep", "sweep_inputs"]

if TYPE_CHECKING:
    import xarray

CELL_CHUNK = 64  # cells per call of a group's program (the last chunk padded): bounds memory
KEEP_SETUPS = 1024  # a sweep of at most this many cells keeps the setups its validation made (`_plan`)


def _envs(spec: SweepSpec) -> dict:
    """The sweep's environments, padded to equal landmark slots (one program for every environment)."""

    def env(name: str, pad_to: int | None = None):
        if name in spec.random_envs:
            return random_env(*spec.random_envs[name], pad_to=pad_to)
        if name in spec.ensemble_envs:
            return env_from_dict(spec.ensemble_envs[name], pad_to=pad_to)
        return load_env(spec.env_files.get(name, name), pad_to=pad_to)

    if spec.kind.own_cells:  # the kind's own worlds (route following: colour worlds)
        return spec.kind.environments(spec.axes["env"], env)
    envs = {name: env(name) for name in spec.axes["env"]}
    slots = max(int(e.landmarks.shape[0]) for e in envs.values())
    return {name: env(name, pad_to=slots) for name in envs}


def _plan(
    spec: SweepSpec,
    envs: dict,
    max_points: int,
    code: str | None,
    method_set: tuple[str, ...] | None = None,
    kept: dict[int, dict] | None = None,
) -> tuple[list[list[int]], list[str], int]:
    """Validate every cell before any work; return the cells of each program (group), with `code`
    every cell's digest (`_store.py`), and the most visibility masks of any cell. With `kept` (a dict) and
    at most KEEP_SETUPS cells, each cell's setup is kept there (cell number -> setup) for the run to use rather
    than make again; a larger sweep's are not: memory does not grow with them. `method_set`: as `cell_setup`'s."""
    keep = kept is not None and spec.n_cells <= KEEP_SETUPS
    ids: dict[tuple, int] = {}
    groups: list[list[int]] = []
    digests: list[str] = []
    rows = 1
    for i, cell in enumerate(spec.cells()):  # input preparation, one small pytree per cell
        req = cell_setup(spec, envs, cell, max_points, method_set)
        rows = max(rows, mask_rows(req))
        gid = ids.setdefault(group_key(req, spec.kind), len(ids))
        if gid == len(groups):
            groups.append([])
        groups[gid].append(i)
        digests.append(cell_digest(req, code) if code is not None else "")
        if keep:
            kept[i] = req
    return groups, digests, rows


def _setups(spec: SweepSpec, envs: dict, rows: list[int], kept: dict[int, dict], max_points: int, method_set) -> list:
    """The setups of a chunk's rows: those `_plan` kept, the others made once each (padding repeats a cell)."""
    made: dict[int, dict] = {}
    for i in rows:
        if i not in made:
            made[i] = kept[i] if i in kept else cell_setup(spec, envs, spec.cell(i), max_points, method_set)
    return [made[i] for i in rows]


@keywords_after(1, ("max_points", "progress", "announce", "out", "phase", "lanes", "skip", "program", "mask_rows"))
def run_sweep(
    spec: SweepSpec,
    *,
    max_points: int = api.MAX_POINTS,
    progress: Progress | Callable[[int, int], None] | None = None,
    out: str | Path | None = None,
    lanes: int = DEFAULT_LANES,
    skip: Callable[[dict], bool] | None = None,
    method_set: tuple[str, ...] | None = None,
    mask_rows: int = 1,
    **legacy,
) -> xarray.Dataset:
    """Every cell of `spec`: metrics as an `xarray.Dataset` (one dimension per axis of more than one
    value). Every cell is validated before any work; then `progress` (a `Progress`, evaluate/_progress.py,
    or a plain `f(done, total)`) hears `start(n)`, `phase(text)` where what runs changes ("compiling
    program 2 of 3") and `(done, n)` after each chunk. The separate `announce=` and `phase=` callbacks of
    earlier releases still work for one release, with a DeprecationWarning.
    With `out`, finished chunks are kept in out/.cells and cells found there are not computed again
    (`_store.py`: a killed or changed sweep resumes). `lanes`: rollout trials advanced side by side
    (`rollouts.run_trials`; no number depends on it): fewer waste less on cells of few trials.
    `skip(cell)` True: the cell (its axis values, as `spec.cells()` gives them) is not computed and its
    metrics are NaN (a study that needs only some cells of a product; the others' numbers are the same).
    `method_set` (registry names compiled into one program with every cell's method, as `point_outcomes`') and
    `mask_rows` (visibility masks padded to at least this many rows) let sweeps of other methods or occlusions
    share one compiled program (the same numbers: a cell's trials do not depend on its companions)."""
    report = with_callbacks(progress, legacy, "run_sweep")
    method_set = renamed_keyword(legacy, "program", "method_set", method_set, METHOD_SET_WHY)
    refuse_unknown(legacy, "run_sweep")
    envs = _envs(spec)
    kept: dict[int, dict] = {}
    groups, digests, rows = _plan(spec, envs, max_points, code_digest() if out is not None else None, method_set, kept)
    rows = max(rows, mask_rows)
    n = spec.n_cells
    names = sum_names(spec.kind)
    extra = (len(spec.distances),) if spec.kind.per_distance else ()
    sums = {k: np.zeros((n,) + extra) for k in names}
    todo = np.ones(n, bool)
    if out is not None:
        done = load_cells(Path(out))
        for i, digest in enumerate(digests):
            if digest in done:
                todo[i] = False
                for k in names:
                    sums[k][i] = done[digest][k]
    skipped = np.zeros(n, bool)
    if skip is not None:  # cells nobody reads: never computed, their metrics NaN (`dataset`)
        skipped = np.array([bool(skip(cell)) for cell in spec.cells()], bool) & todo
        todo &= ~skipped
    processes = jax.process_count()
    if processes > 1:  # a cell is computed again unless every process found it (--out need not be shared)
        from jax.experimental import multihost_utils  # only with several processes (jax.distributed)

        todo = multihost_utils.process_allgather(todo).any(axis=0)
    report.start(n)
    if not todo.all():
        report(int((~todo).sum()), n)
    compiled = programs_compiled()
    mesh = local_mesh() if processes == 1 else global_mesh()  # one mesh over every device of every process
    per_call = n_devices(mesh)
    width = -(-CELL_CHUNK // per_call) * per_call  # cells per call, a multiple of the devices
    live = [cells for cells in ([i for i in g if todo[i]] for g in groups) if cells]  # one program each
    jobs = []  # (cells, padded size, the program's number on its first chunk else False); chunks padded to `width`
    idle = spec.kind.rollouts  # a rollout chunk's padding runs no trials: every chunk `width` cells,
    for number, cells in enumerate(live, 1):  # one program shape for sweeps of any size (`idle_padding`)
        size = width if idle or len(cells) > width else -(-len(cells) // per_call) * per_call
        jobs += [(cells[start : start + width], size, start == 0 and number) for start in range(0, len(cells), width)]
    mine: list[int] = []  # the cells this process computed
    for chunk, size, first in jobs:
        if first:  # the program's first call compiles it (or loads it from the cache)
            report.phase(f"compiling program {first} of {len(live)}")
        padded = chunk + [chunk[0]] * (size - len(chunk))
        start, stop = (0, size) if processes == 1 else process_rows(mesh, size)  # this process's rows
        setups = _setups(spec, envs, padded[start:stop], kept, max_points, method_set)
        own = chunk[start:stop]  # this process's real cells (the rest of its rows are padding: no trials)
        res = evaluate(spec.kind, setups, mesh, rows, None if processes == 1 else size, lanes, real=len(own))
        for k in names:
            sums[k][own] = res[k][: len(own)]
        mine += own
        if out is not None and own:
            save_cells(Path(out), [digests[i] for i in own], {k: sums[k][own] for k in names})
        report(len(chunk), n)
    if processes > 1:
        sums = _merge(sums, mine)
    ds = dataset(spec, sums, programs_compiled() - compiled, {k: e.name for k, e in envs.items()}, skipped)
    ds.attrs["cells_reused"] = int((~todo & ~skipped).sum())
    ds.attrs["cells_skipped"] = int(skipped.sum())
    return ds


def _merge(sums: dict, mine: list[int]) -> dict:
    """Every process's cells (`jax.distributed`): gathered, each cell from the process that computed it."""
    from jax.experimental import multihost_utils  # only with several processes (jax.distributed)

    n = len(next(iter(sums.values())))
    owned = np.zeros(n, bool)
    owned[mine] = True
    table = np.concatenate([v.reshape(n, -1) for v in sums.values()], axis=1)  # (cells, columns)
    tables = multihost_utils.process_allgather(table)  # (P, cells, columns)
    owners = multihost_utils.process_allgather(owned)  # (P, cells)
    merged = table.copy()
    for p in range(tables.shape[0]):  # a few processes
        merged[owners[p]] = tables[p][owners[p]]
    out, col = {}, 0
    for k, v in sums.items():
        width = int(np.prod(v.shape[1:], dtype=int))
        out[k] = merged[:, col : col + width].reshape(v.shape)
        col += width
    return out
