"""What every kind of sweep is (`SweepKind`, docs/sweeps.md): one class per kind owns its name (what a sweep
file says; a kind is that string), metrics, shape (grid, rollouts, `distance_cm`), per-cell sums, the validated
setup of a cell (`request`), its program's inputs, the program and the metrics from the sums; and the one
validation of a cell that the kinds share (`validated`)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import ClassVar, Protocol, runtime_checkable

import numpy as np

from ...core import metrics as table
from ...options._registry import get_method


@runtime_checkable
class Sweep(Protocol):
    """What a kind reads of a sweep (`SweepSpec`, which is built from the kinds: a protocol, not an import)."""

    axes: dict
    distances: tuple
    trials: int


class SweepKind(str):
    """A kind of sweep, equal to its name (`KINDS[name]`); a subclass sets the class attributes and methods."""

    name: ClassVar[str]
    metrics: ClassVar[dict[str, str]]  # name -> description, from `core.metrics.METRICS`
    grid: ClassVar[bool]  # a grid of release points (a `spacing` axis)
    rollouts: ClassVar[bool]  # rollout axes (occlude, first_move, ...) and motion noise
    per_distance: ClassVar[bool]  # a `distance_cm` dimension (release distances and trials per distance)
    sums: ClassVar[type]  # the dataclass of the per-cell sums its program returns
    # A kind of other worlds and methods than the landmark kinds' (route-following) sets these:
    own_axes: ClassVar[dict[str, str] | None] = None  # its axes besides env, method and seed (None: `_spec.axes`)
    text_axes: ClassVar[tuple[str, ...]] = ()  # those of its axes whose values are names
    defaults: ClassVar[dict[str, list] | None] = None  # env, method, seed when a file leaves them out
    default_trials: ClassVar[int | None] = None  # trials per cell, `[sweep] trials` (None: no such field)
    units: ClassVar[dict[str, str]] = {}  # its axes' CF units
    own_cells: ClassVar[bool] = False  # True: its own `environments`, `traced`, `group_key` and `idle_padding`

    def __new__(cls) -> SweepKind:
        return super().__new__(cls, cls.name)

    def request(self, env, cell: dict, spec: Sweep, max_points: int, method_set: Sequence[str] | None = None) -> dict:
        """The validated setup of one cell (`validated`)."""
        raise NotImplementedError

    def inputs(self, setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
        """(shared, traced) arguments of the program for a chunk of setups and their stacked pytrees."""
        raise NotImplementedError

    def program(self, lanes: int, trials: int | None) -> Callable:
        """The per-chunk program, shared arguments first (max_steps comes traced, in `inputs`)."""
        raise NotImplementedError

    def metrics_of(self, sums: dict) -> dict:
        """Every metric of the kind from the per-cell sums (NumPy)."""
        raise NotImplementedError

    def environments(self, names: Sequence[str], environment: Callable[[str], object]) -> dict:
        """(own_cells) label -> the world of each `env` value; `environment(label)`: the landmark kinds' `Env`."""
        raise NotImplementedError

    def traced(self, req: dict, mask_rows: int = 1) -> tuple:
        """(own_cells) The pytree a cell's program takes (`cells.traced`)."""
        raise NotImplementedError

    def group_key(self, req: dict) -> tuple:
        """(own_cells) Cells with equal keys share a program (`cells.group_key`)."""
        raise NotImplementedError

    def idle_padding(self, stacked: tuple, real: int | None) -> tuple:
        """(own_cells) A chunk's rows from `real` on left idle (`cells.idle_padding`)."""
        raise NotImplementedError

    def cell_seconds(self, spec: Sweep) -> float:
        """Rough warm seconds of one cell on 2 CPU cores, for the time a sweep states before it starts."""
        raise NotImplementedError


def descriptions(rows: tuple) -> dict[str, str]:
    """name -> description of rows of the metrics table (`core.metrics`)."""
    return {m.name: m.description for m in rows}


MAP_METRICS = descriptions(table.MAP_METRICS)


def options(cell: dict) -> dict:
    """A cell's options (every axis but the scene's env, method and seed)."""
    return {k: v for k, v in cell.items() if k not in ("env", "method", "seed")}


def _landmarks_only(name: str) -> bool:
    """Whether a registered method reads landmark bearings alone: no ring image, no panorama."""
    m = get_method(name)
    return not m.reads_image() and not m.reads_panorama()


def shared_program(spec: Sweep, method) -> tuple[str, ...] | None:
    """The sweep's methods compiled into one `MethodSet` with `method` (docs/sweeps.md, "One program
    for the landmark methods"): every landmark method of the sweep's method axis, the same numbers
    bit for bit in less compile time; None for a method alone or one that reads images (an image
    method compiled in a `MethodSet` sums its errors in another order: last-bit changes). Looked up in
    the registry each time: a method registered at run time may change it."""
    names = spec.axes.get("method", ())
    if not isinstance(method, str) or not all(isinstance(n, str) for n in names) or not _landmarks_only(method):
        return None
    mine = tuple(n for n in names if _landmarks_only(n))
    return mine if len(mine) > 1 else None


def validated(request: Callable[..., dict], cell: dict, spec: Sweep, method_set=None, **kwargs) -> dict:
    """`request(method=..., **kwargs)`: the cell validated once, by its API's request; where the sweep has
    companions (or `method_set` names them), set up as one of their `MethodSet`, a setting of another method still
    an error (`make_setup`'s `own_only`)."""
    names = shared_program(spec, cell["method"]) if method_set is None else tuple(method_set)
    if names is None:
        return request(method=cell["method"], **kwargs)
    return request(method=cell["method"], method_set=names, own_only=True, **kwargs)


def pct(part: np.ndarray, whole: np.ndarray) -> np.ndarray:
    """100 part / whole, NaN where whole is 0."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(whole > 0, 100.0 * part / np.maximum(whole, 1), np.nan)
