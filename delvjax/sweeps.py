"""Running a sweep: cells grouped by shape, one compiled program per shape, labelled results
(`xarray.Dataset`, netCDF and a tidy CSV); docs/sweeps.md."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Callable

import jax
import numpy as np

from . import api
from .core.batching import local_mesh, n_devices, over_devices
from .cell_store import cell_digest, code_digest, load_cells, save_cells
from .core import cells as core_cells
from .core.cells import CellMetrics, map_cells
from .core.errors import InputError
from .core.maps import grid_included, grid_points
from .io import output_set
from .presets import load_env
from .sweep_spec import SweepSpec

if TYPE_CHECKING:
    import xarray

SUMS = ("points", "invalid", "gt45", "gt90", "error_sum", "error_sq_sum")  # per cell, see core.cells.CellMetrics
CELL_CHUNK = 64  # cells per call of a group's program (the last chunk padded): bounds memory
FILES = ("sweep.nc", "sweep.csv", "sweep.toml")


def _cell_setups(spec: SweepSpec, max_points: int) -> list[dict]:
    """Every cell's validated setup (`api.map_request`), before any work; an error names the cell."""
    envs = {}
    for name in spec.axes["env"]:
        envs[name] = load_env(name)
    slots = max(int(e.landmarks.shape[0]) for e in envs.values())
    envs = {name: load_env(name, pad_to=slots) for name in envs}  # equal slots: one program for every env
    setups = []
    for cell in spec.cells():  # input preparation, one small pytree per cell
        options = {k: v for k, v in cell.items() if k not in ("env", "method", "spacing", "seed")}
        try:
            req = api.map_request(envs[cell["env"]], method=cell["method"], spacing=float(cell["spacing"]),
                                  seed=cell["seed"], max_points=max_points, **options)
        except InputError as exc:
            where = ", ".join(f"{k}={v}" for k, v in cell.items())
            raise InputError(f"cell ({where})", exc.value, f"{exc.field}: {exc.expected}") from None
        setups.append(req)
    return setups


def _group_key(req: dict) -> tuple:
    """Cells with equal keys stack into one program: pytree structure, leaf shapes, grid."""
    tree = (req["env"].arrays(), req["method"], req["sensor"])
    leaves, treedef = jax.tree.flatten(tree)
    shapes = tuple((np.shape(x), np.asarray(x).dtype.str) for x in leaves)
    return treedef, shapes, req["spacing"], tuple(np.asarray(req["env"].arena).tolist())


def run_sweep(spec: SweepSpec, max_points: int = api.MAX_POINTS, progress: Callable[[int, int], None] | None = None,
              announce: Callable[[], None] | None = None, out: str | Path | None = None) -> xarray.Dataset:
    """Every cell of `spec`: metrics as an `xarray.Dataset` (one dimension per axis). Every cell is
    validated before any work; `announce()` is called then; `progress(done, total)` after each chunk.
    With `out`, finished chunks are kept in out/.cells and cells found there are not computed again
    (`cell_store`: a killed or changed sweep resumes)."""
    import xarray as xr

    setups = _cell_setups(spec, max_points)
    n = len(setups)
    sums = {k: np.zeros(n) for k in SUMS}
    digests, todo = [""] * n, list(range(n))
    if out is not None:
        code = code_digest()
        digests = [cell_digest(req, code) for req in setups]
        done = load_cells(Path(out))
        todo = [i for i in range(n) if digests[i] not in done]
        for i in set(range(n)) - set(todo):
            for k in SUMS:
                sums[k][i] = done[digests[i]][k]
    if announce is not None:
        announce()
    if progress is not None and len(todo) < n:
        progress(n - len(todo), n)
    groups: dict[tuple, list[int]] = {}
    for i in todo:
        groups.setdefault(_group_key(setups[i]), []).append(i)
    compiled = _programs()
    mesh = local_mesh()
    width = -(-CELL_CHUNK // n_devices(mesh)) * n_devices(mesh)  # cells per call, a multiple of the devices
    jobs = [(cells[start:start + width], width if len(cells) > width else
             -(-len(cells[start:start + width]) // n_devices(mesh)) * n_devices(mesh))
            for cells in groups.values() for start in range(0, len(cells), width)]
    mine = jobs[jax.process_index()::jax.process_count()]  # several processes: every P-th chunk is ours
    for chunk, size in mine:
        res = _evaluate(setups, chunk + [chunk[0]] * (size - len(chunk)), mesh)
        for k in sums:
            sums[k][chunk] = np.asarray(getattr(res, k))[:len(chunk)]
        if out is not None:
            save_cells(Path(out), [digests[i] for i in chunk], {k: sums[k][chunk] for k in SUMS})
        if progress is not None:
            progress(len(chunk) * jax.process_count(), n)
    if jax.process_count() > 1:
        sums = _merge(sums, [i for chunk, _ in mine for i in chunk])
    ds = _dataset(spec, sums, _programs() - compiled, xr)
    ds.attrs["cells_reused"] = n - len(todo)
    return ds


def _evaluate(setups: list[dict], rows: list[int], mesh) -> CellMetrics:
    """The cells `rows` (one shape) as one call of their program, split over `mesh`'s devices if any."""
    points = grid_points(setups[rows[0]]["env"].arena, setups[rows[0]]["spacing"])
    stack = lambda *xs: np.stack([np.asarray(x) for x in xs])  # noqa: E731
    envs = jax.tree.map(stack, *[setups[i]["env"].arrays() for i in rows])
    included = np.stack([np.asarray(grid_included(setups[i]["env"].arrays(), points, setups[i]["clearance"]))
                         for i in rows])
    methods = jax.tree.map(stack, *[setups[i]["method"] for i in rows])
    sensors = jax.tree.map(stack, *[setups[i]["sensor"] for i in rows])
    keys = stack(*[setups[i]["key"] for i in rows])
    if mesh is None:
        return map_cells(envs, points, included, methods, sensors, keys)
    # each device evaluates its own cells, with the one-device per-cell program
    return over_devices(_cells_on_device, mesh, 1, points, envs, included, methods, sensors, keys)


def _merge(sums: dict, mine: list[int]) -> dict:
    """Every process's cells (`jax.distributed`): gathered, each cell from the process that computed it."""
    from jax.experimental import multihost_utils

    owned = np.zeros(len(sums["points"]), bool)
    owned[mine] = True
    table = np.stack([sums[k] for k in SUMS])
    tables = multihost_utils.process_allgather(table)  # (P, metrics, cells)
    owners = multihost_utils.process_allgather(owned)  # (P, cells)
    merged = table.copy()
    for p in range(tables.shape[0]):  # a few processes
        merged[:, owners[p]] = tables[p][:, owners[p]]
    return {k: merged[i] for i, k in enumerate(SUMS)}


def _cells_on_device(points, envs, included, methods, sensors, keys):
    """`map_cells` with the shared grid first (`batching.over_devices` replicates the first argument)."""
    return map_cells(envs, points, included, methods, sensors, keys)


def _programs() -> int:
    """Programs compiled so far for cells (one device, or split over the local devices)."""
    return core_cells.map_cells._cache_size() + over_devices._cache_size()


def _dataset(spec: SweepSpec, sums: dict, programs: int, xr):
    """Per-cell sums -> the requested metrics, labelled by the axes."""
    pts = np.maximum(sums["points"], 1)
    mean = sums["error_sum"] / pts
    var = np.maximum(sums["error_sq_sum"] - pts * mean ** 2, 0.0) / np.maximum(pts - 1, 1)
    half = _t(pts) * np.sqrt(var / pts)
    values = {"gt45_pct": 100 * sums["gt45"] / pts, "gt90_pct": 100 * sums["gt90"] / pts, "mean_error_deg": mean,
              "mean_error_ci95_deg": np.where(sums["points"] >= 2, half, np.nan),
              "invalid_pct": 100 * sums["invalid"] / pts, "points": sums["points"].astype(np.int64)}
    dims = list(spec.axes)
    coords = {name: np.asarray(v) for name, v in spec.axes.items()}
    ds = xr.Dataset({m: (dims, np.asarray(values[m]).reshape(spec.shape)) for m in spec.metrics}, coords=coords)
    ds.attrs.update(sweep_toml=spec.text, kind=spec.kind, programs_compiled=programs, cells=int(np.prod(spec.shape)),
                    delvjax_version=_version("delvjax"), jax_version=jax.__version__, jaxlib_version=_version("jaxlib"))
    return ds


def _t(n: np.ndarray) -> np.ndarray:
    """Student-t 97.5 % quantile with n - 1 degrees of freedom (NaN for n < 2), as `metrics.t_interval`."""
    from scipy import stats

    return np.where(n >= 2, stats.t.ppf(0.975, np.maximum(n - 1, 1)), np.nan)


def _version(package: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(package)
    except PackageNotFoundError:
        return "unknown"


def save_sweep(ds, out: str | Path) -> list[Path]:
    """sweep.nc (netCDF, every attribute), sweep.csv (one row per cell) and sweep.toml, as a unit."""
    out = Path(out)
    paths = [out / f for f in FILES]
    table = ds.to_dataframe().reset_index()
    with output_set() as files:
        files.file(paths[0], lambda tmp: ds.to_netcdf(tmp, engine="scipy"), "--out")
        files.file(paths[1], lambda tmp: table.to_csv(tmp, index=False, float_format="%.6g"), "--out")
        files.file(paths[2], lambda tmp: Path(tmp).write_text(ds.attrs["sweep_toml"]), "--out")
    return paths


def load_sweep(out: str | Path):
    """The `xarray.Dataset` of a finished sweep folder (`delvjax sweep ... --out DIR`)."""
    import xarray as xr

    path = Path(out) / FILES[0]
    if not path.is_file():
        raise InputError("out", str(out), f"has no {FILES[0]} (not a finished sweep folder)")
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()
