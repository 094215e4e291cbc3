"""What a sweep does with its cells, whatever their kind (docs/sweeps.md): the validated setup of a cell (its
kind's `request`, once), the key of the cells that share one compiled program, and a chunk of such cells as one
call of it (the kind's `inputs` and `program`), split over the local devices when there are several."""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Sequence

import jax
import numpy as np

from ...core import cells as map_cells
from ...core.batching import over_devices, over_processes, pad_rows
from ...core.errors import InputError
from ...core.familiarity.cells import following_cells
from ...core.rollouts import DEFAULT_LANES
from ...core.rollouts import cells as rollout_programs
from .base import Sweep, SweepKind


def sum_names(kind: SweepKind) -> tuple[str, ...]:
    """The names of the per-cell sums a kind's program returns."""
    return tuple(f.name for f in dataclasses.fields(kind.sums))


def cell_setup(spec: Sweep, envs: dict, cell: dict, max_points: int, method_set: Sequence[str] | None = None) -> dict:
    """One cell's setup, validated (once) by the API call of its kind (`spec.kind.request`); an `InputError`
    names the cell. `method_set`: registry names compiled into one program with the cell's method, image methods
    too (`point_outcomes`); None: the sweep's landmark methods (`base.shared_program`)."""
    try:
        return spec.kind.request(envs[cell["env"]], cell, spec, max_points, method_set)
    except InputError as exc:
        where = ", ".join(f"{k}={v}" for k, v in cell.items())
        raise InputError(f"cell ({where})", exc.value, f"{exc.field}: {exc.expected}") from None


def traced(req: dict, mask_rows: int = 1, kind: SweepKind | None = None) -> tuple:
    """The pytree a cell's program takes (stacked over the cells of a chunk); a rollout cell's masks
    padded to `mask_rows` rows (the most of any cell of the sweep: one program for every occlusion); a kind
    with `own_cells` says its own."""
    if kind is not None and kind.own_cells:
        return kind.traced(req, mask_rows)
    if req.get("kind") is None:
        return req["env"], req["method"], req["sensor"], req["key"]
    masks = np.asarray(req["masks"], bool)
    padded = pad_rows(masks, mask_rows)
    return (
        rollout_programs.RolloutCell(
            env=req["env"],
            method=req["method"],
            sensor=req["sensor"],
            key=req["key"],
            masks=padded,
            n_masks=np.int32(len(masks)),
            radius=np.float32(req["home_radius"]),
            homing_first=np.bool_(req["first_move"] == "homing"),  # docs/model.md §5
            collide=np.bool_(req["collisions"] == "fail"),
        ),
    )


def mask_rows(req: dict) -> int:
    """Visibility masks of a rollout cell (0 for a vector map)."""
    return len(req["masks"]) if "masks" in req else 0


def group_key(req: dict, kind: SweepKind | None = None) -> tuple:
    """Cells with equal keys stack into one program: pytree structure, leaf shapes (the number of
    masks aside), and the settings one call shares (grid, clearance, max_steps: a traced number, so its
    values share the program but not a call); a kind with `own_cells` says its own."""
    if kind is not None and kind.own_cells:
        return kind.group_key(req)
    leaves, treedef = jax.tree.flatten(traced(dict(req, masks=req["masks"][:1]) if "masks" in req else req))
    shapes = tuple((np.shape(x), np.asarray(x).dtype.str) for x in leaves)
    return (
        treedef,
        shapes,
        req["spacing"],
        req["clearance"],
        req.get("max_steps"),
        tuple(np.asarray(req["env"].arena).tolist()),
    )


def idle_padding(stacked: tuple, real: int | None, kind: SweepKind | None = None) -> tuple:
    """A chunk's stacked traced inputs with its rows from `real` on (copies that pad the chunk to its
    program's size, results thrown away) left idle: a rollout cell with no masks runs no trials, and a
    vector-map row gets a False flag (appended: one per row, `map_cells`' `live`) and evaluates no grid point.
    So a padded row costs nearly nothing (the cells run one after the other, `lax.map`) and the real rows'
    numbers are unchanged (a cell's numbers do not depend on its chunk). A kind with `own_cells` says its own."""
    if kind is not None and kind.own_cells:
        return kind.idle_padding(stacked, real)
    cell = stacked[0]
    if not isinstance(cell, rollout_programs.RolloutCell):
        rows = len(np.asarray(stacked[3]))
        return (*stacked, np.arange(rows) < (rows if real is None else real))
    if real is None or real >= len(cell.n_masks):
        return stacked
    n_masks = np.array(cell.n_masks, np.int32)
    n_masks[real:] = 0
    return (dataclasses.replace(cell, n_masks=n_masks), *stacked[1:])


def evaluate(
    kind: SweepKind,
    setups: list[dict],
    mesh,
    rows: int = 1,
    total: int | None = None,
    lanes: int = DEFAULT_LANES,
    real: int | None = None,
) -> dict[str, np.ndarray]:
    """The cells `setups` (one group) as one call of their program, split over `mesh`'s devices if
    any (every device runs whole cells with the one-device program); rollout masks padded to `rows`.
    With `total`, `mesh` spans every process and `setups` are this process's rows of a chunk of
    `total` cells (`batching.over_processes`). `real`: the rows before it are cells, those from it on
    padding (`idle_padding`: no trials). Returns the sums (of `setups`) by name."""
    first = setups[0]
    stack = lambda *xs: np.stack([np.asarray(x) for x in xs])  # noqa: E731
    stacked = idle_padding(jax.tree.map(stack, *[traced(req, rows, kind) for req in setups]), real, kind)
    shared, stacked = kind.inputs(setups, stacked)
    compiled = _program(kind, lanes, first.get("trials"))
    if total is not None:
        res = over_processes(compiled, mesh, len(shared), total, *shared, *stacked)
    elif mesh is None:
        res = compiled(*shared, *stacked)
    else:
        res = over_devices(compiled, mesh, len(shared), *shared, *stacked)
    return {name: np.asarray(getattr(res, name)) for name in sum_names(kind)}


@functools.lru_cache(maxsize=None)
def _program(kind: SweepKind, lanes: int, trials: int | None):
    """The per-chunk program of a kind (`kind.program`), shared arguments first (`over_devices`
    replicates them); one per kind and setting."""
    return kind.program(lanes, trials)


def programs_compiled() -> int:
    """Programs compiled so far for sweep cells (one device, or split over the local devices)."""
    return (
        map_cells.map_cells._cache_size()
        + rollout_programs.catchment_cells._cache_size()
        + rollout_programs.success_cells._cache_size()
        + following_cells._cache_size()
        + over_devices._cache_size()
    )
