"""What each kind of sweep computes per cell (docs/sweeps.md): the validated setup of a cell, the
key of the cells that share one compiled program, and a chunk of such cells as one call of it
(`core.cells.map_cells` for vector maps, `core.rollouts.cells` for catchments and success rates),
split over the local devices when there are several."""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from typing import TYPE_CHECKING

import jax
import numpy as np

from ..evaluate import _vector_map as api, _rollouts as api_rollouts
from ..core import cells as map_cells
from ..core.batching import over_devices, over_processes, pad_rows
from ..core.errors import InputError
from ..core.maps import grid_included, grid_points
from ..core.rollouts import DEFAULT_LANES, catchment_counted
from ..core.rollouts import cells as rollout_programs
from ..options._registry import get_method

if TYPE_CHECKING:  # types only: the kinds and the spec are built from this module
    from ._kind import SweepKind
    from ._spec import SweepSpec


def sum_names(kind: SweepKind) -> tuple[str, ...]:
    """The names of the per-cell sums a kind's program returns."""
    return tuple(f.name for f in dataclasses.fields(kind.sums))


def cell_setup(
    spec: SweepSpec, envs: dict, cell: dict, max_points: int, program: tuple[str, ...] | None = None
) -> dict:
    """One cell's setup, validated by the API call of its kind (`spec.kind.request`); an `InputError`
    names the cell. `program`: registry names compiled into one program with the cell's method, image methods
    too (`point_outcomes`); None: the sweep's landmark methods (`shared_program`)."""
    try:
        return spec.kind.request(envs[cell["env"]], cell, spec, max_points, program)
    except InputError as exc:
        where = ", ".join(f"{k}={v}" for k, v in cell.items())
        raise InputError(f"cell ({where})", exc.value, f"{exc.field}: {exc.expected}") from None


def _options(cell: dict) -> dict:
    return {k: v for k, v in cell.items() if k not in ("env", "method", "seed")}


def _landmarks_only(name: str) -> bool:
    """Whether a registered method reads landmark bearings alone: no ring image, no panorama."""
    m = get_method(name)
    return not m.reads_image() and not m.reads_panorama()


def shared_program(spec: SweepSpec, method) -> tuple[str, ...] | None:
    """The sweep's methods compiled into one `Program` with `method` (docs/sweeps.md, "One program
    for the landmark methods"): every landmark method of the sweep's method axis, the same numbers
    bit for bit in less compile time; None for a method alone or one that reads images (an image
    method compiled in a `Program` sums its errors in another order: last-bit changes). Looked up in
    the registry each time: a method registered at run time may change it."""
    names = spec.axes.get("method", ())
    if not isinstance(method, str) or not all(isinstance(n, str) for n in names) or not _landmarks_only(method):
        return None
    mine = tuple(n for n in names if _landmarks_only(n))
    return mine if len(mine) > 1 else None


def _with_program(request: Callable[..., dict], cell: dict, spec: SweepSpec, program=None, **kwargs) -> dict:
    """`request(method=..., **kwargs)` validated for the cell's method alone (a setting of another
    method stays an error), then, where the sweep has companions (or `program` names them), set up as one
    of their `Program`."""
    req = request(method=cell["method"], **kwargs)
    names = shared_program(spec, cell["method"]) if program is None else tuple(program)
    return req if names is None else request(method=cell["method"], program=names, **kwargs)


def map_request(env, cell: dict, spec: SweepSpec, max_points: int, program=None) -> dict:
    """A vector-map cell, validated as `delvjax.vector_map` validates its keywords."""
    return _with_program(
        functools.partial(api.map_request, env),
        cell,
        spec,
        program,
        seed=cell["seed"],
        max_points=max_points,
        **_options(cell),
    )


def rollout_request(env, cell: dict, spec: SweepSpec, max_points: int, program=None) -> dict:
    """A catchment or success-rate cell, validated as `delvjax.catchment` / `success_rate` validate theirs."""
    return _with_program(
        functools.partial(api_rollouts.rollout_request, env),
        cell,
        spec,
        program,
        kind=str(spec.kind),
        seed=cell["seed"],
        distances=spec.distances,
        trials=spec.trials,
        max_points=max_points,
        **_options(cell),
    )


def _traced(req: dict, mask_rows: int = 1) -> tuple:
    """The pytree a cell's program takes (stacked over the cells of a chunk); a rollout cell's masks
    padded to `mask_rows` rows (the most of any cell of the sweep: one program for every occlusion)."""
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


def group_key(req: dict) -> tuple:
    """Cells with equal keys stack into one program: pytree structure, leaf shapes (the number of
    masks aside), and the settings one call shares (grid, clearance, max_steps: a traced number, so its
    values share the program but not a call)."""
    leaves, treedef = jax.tree.flatten(_traced(dict(req, masks=req["masks"][:1]) if "masks" in req else req))
    shapes = tuple((np.shape(x), np.asarray(x).dtype.str) for x in leaves)
    return (
        treedef,
        shapes,
        req["spacing"],
        req["clearance"],
        req.get("max_steps"),
        tuple(np.asarray(req["env"].arena).tolist()),
    )


def idle_padding(traced: tuple, real: int | None) -> tuple:
    """A chunk's stacked traced inputs with its rows from `real` on (copies that pad the chunk to its
    program's size, results thrown away) left idle: a rollout cell with no masks runs no trials, and a
    vector-map row gets a False flag (appended: one per row, `map_cells`' `live`) and evaluates no grid point.
    So a padded row costs nearly nothing (the cells run one after the other, `lax.map`) and the real rows'
    numbers are unchanged (a cell's numbers do not depend on its chunk)."""
    cell = traced[0]
    if not isinstance(cell, rollout_programs.RolloutCell):
        rows = len(np.asarray(traced[3]))
        return (*traced, np.arange(rows) < (rows if real is None else real))
    if real is None or real >= len(cell.n_masks):
        return traced
    n_masks = np.array(cell.n_masks, np.int32)
    n_masks[real:] = 0
    return (dataclasses.replace(cell, n_masks=n_masks), *traced[1:])


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
    traced = idle_padding(jax.tree.map(stack, *[_traced(req, rows) for req in setups]), real)
    shared, traced = kind.inputs(setups, traced)
    program = _program(kind, lanes, first.get("trials"))
    if total is not None:
        res = over_processes(program, mesh, len(shared), total, *shared, *traced)
    elif mesh is None:
        res = program(*shared, *traced)
    else:
        res = over_devices(program, mesh, len(shared), *shared, *traced)
    return {name: np.asarray(getattr(res, name)) for name in sum_names(kind)}


def grid_inputs(setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
    """(shared, traced) of a vector-map chunk: the grid points shared, each cell's included points."""
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


def distance_inputs(setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
    """(shared, traced) of a success-rate chunk: the release distances, clearance and max_steps shared."""
    first = setups[0]
    shared = (np.asarray(first["distances"], np.float32), np.float32(first["clearance"]), np.int32(first["max_steps"]))
    return shared, traced


def map_program(lanes: int, trials: int | None):
    return lambda points, envs, methods, sensors, keys, live, included: map_cells.map_cells(
        envs, points, included, methods, sensors, keys, live
    )


def catchment_program(lanes: int, trials: int | None):
    return lambda points, max_steps, cells, included, counted: rollout_programs.catchment_cells(
        cells, points, included, counted, max_steps, lanes=lanes
    )


def success_program(lanes: int, trials: int | None):
    return lambda distances, clearance, max_steps, cells: rollout_programs.success_cells(
        cells, distances, clearance, trials=trials, max_steps=max_steps, lanes=lanes
    )


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
        + over_devices._cache_size()
    )
