"""A sweep's results as labelled data (docs/sweeps.md "Results"): per-cell sums -> metrics (each kind's `metrics_of`), an
`xarray.Dataset` (one dimension per axis, plus `distance_cm` for success rates), netCDF and a
tidy CSV written as a unit, and `load_sweep`."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import jax
import numpy as np

from ..core.errors import InputError
from ..outputs._files import output_set
from ._store import STORE

if TYPE_CHECKING:  # types only: the kinds are built from this module
    from ._spec import SweepSpec

FILES = ("sweep.nc", "sweep.csv", "sweep.toml")

# The arguments of xarray's methods that take dimensions as keywords (sel, isel, interp, reindex, head, tail,
# thin, drop_sel, drop_isel, pad, shift, roll, expand_dims, assign_coords, swap_dims, rename, query): a dimension
# so named is swallowed by `ds.sel(method="delv")`, which then returns every method without a word (issue 53).
# An axis so named is a dimension under another name in the Dataset (`dim_name`); the sweep file and sweep.csv
# keep the axis's own name, and the Dataset's attribute `renamed_axes` records the mapping.
SELECTORS = ("sel", "isel", "interp", "reindex", "head", "tail", "thin", "drop_sel", "drop_isel", "pad", "shift")
SELECTORS += ("roll", "expand_dims", "assign_coords", "swap_dims", "rename", "query")
XARRAY_KEYWORDS = frozenset(
    "indexers method tolerance drop missing_dims coords assume_sorted kwargs method_non_numeric copy fill_value "
    "labels errors pad_width mode stat_length constant_values end_values reflect_type keep_attrs shifts "
    "roll_coords dim axis create_index_for_new_dim dims_dict name_dict names queries parser engine "
    "indexers_kwargs coords_kwargs labels_kwargs pad_width_kwargs shifts_kwargs dim_kwargs dims_kwargs "
    "queries_kwargs".split()
)
RENAMED = {"method": "homing_method"}  # the one axis so named today; any other gets the prefix `sweep_`


def dim_name(axis: str) -> str:
    """The Dataset's name of a sweep axis: `method` -> `homing_method`, another xarray keyword -> `sweep_<axis>`,
    every other axis its own name. A name already a dimension's is returned as it is."""
    return RENAMED.get(axis, f"sweep_{axis}" if axis in XARRAY_KEYWORDS else axis)


def axis_name(dim: str) -> str:
    """The sweep file's (and sweep.csv's) name of a Dataset dimension: `dim_name`'s inverse."""
    back = {v: k for k, v in RENAMED.items()}
    return back.get(dim, dim[len("sweep_") :] if dim.startswith("sweep_") and dim[6:] in XARRAY_KEYWORDS else dim)


def safe_names(ds):
    """`ds` with every dimension and coordinate named like an xarray keyword renamed (`dim_name`), the
    mapping in its attribute `renamed_axes` ("method -> homing_method", ...); a file written before the
    renaming reads as one written after."""
    names = {n: dim_name(n) for n in ds.variables if dim_name(n) != n}
    if not names:
        return ds
    done = [s.strip() for s in str(ds.attrs.get("renamed_axes", "")).split(";") if s.strip()]
    ds = ds.rename(names)
    ds.attrs["renamed_axes"] = "; ".join(done + [f"{k} -> {v}" for k, v in names.items()])
    return ds


def dataset(spec: SweepSpec, sums: dict, programs: int, env_names: dict[str, str] | None = None, missing=None):
    """Per-cell sums -> the requested metrics, labelled by the axes (and `distance_cm`). An axis with one
    value is a scalar coordinate, not a dimension; `env_names` (label -> the environment's own `name`)
    become the coordinate `env_name` beside `env`; `missing` (cells,) bool: cells not computed (`run_sweep`'s
    `skip`), every metric NaN there."""
    import xarray as xr  # xarray: loaded only when results are labelled

    if missing is None or not np.any(missing):
        values = spec.kind.metrics_of(sums)
    else:  # the missing cells' sums are 0: their metrics are computed, then replaced
        with np.errstate(divide="ignore", invalid="ignore"):
            values = {k: np.asarray(v, float).copy() for k, v in spec.kind.metrics_of(sums).items()}
        for v in values.values():
            v[np.asarray(missing, bool)] = np.nan
    dims, shape = list(spec.axes), spec.shape
    coords = {name: np.asarray(v) for name, v in spec.axes.items()}
    if spec.kind.per_distance:
        dims, shape = dims + ["distance_cm"], shape + (len(spec.distances),)
        coords["distance_cm"] = np.asarray(spec.distances)
    ds = xr.Dataset({m: (dims, np.asarray(values[m]).reshape(shape)) for m in spec.metrics}, coords=coords)
    for name, attrs in spec.describe().items():  # CF-style long_name and units on every variable and coordinate
        ds[name].attrs.update(attrs)
    if env_names is not None and "env" in ds.coords:
        names = [env_names.get(e, e) for e in spec.axes["env"]]
        ds = ds.assign_coords(env_name=("env", np.asarray(names)))
        ds["env_name"].attrs["long_name"] = "the environment's name (its JSON `name`, a preset's name)"
    ds = ds.squeeze([d for d in ds.dims if ds.sizes[d] == 1])  # kept as scalar coordinates
    ds = safe_names(ds)
    ds.attrs.update(
        sweep_toml=spec.text,
        kind=str(spec.kind),
        programs_compiled=programs,
        cells=spec.n_cells,
        delvjax_version=_version("delvjax"),
        jax_version=jax.__version__,
        jaxlib_version=_version("jaxlib"),
    )
    if spec.kind.per_distance:
        ds.attrs["trials_per_distance"] = spec.trials
    return ds


def _version(package: str) -> str:
    from importlib.metadata import PackageNotFoundError, version  # only for the versions a result records

    try:
        return version(package)
    except PackageNotFoundError:
        return "unknown"


RUN_ATTRS = ("programs_compiled", "cells_reused")  # about the run, not the results: kept out of sweep.nc


def save_sweep(ds, out: str | Path) -> list[Path]:
    """sweep.nc (netCDF, every attribute but `RUN_ATTRS`, so that a resumed sweep writes the bytes of an
    uninterrupted one), sweep.csv (one row per cell) and sweep.toml, as a unit."""
    out = Path(out)
    paths = [out / f for f in FILES]
    table = table_of(ds)
    kept = ds.copy()
    kept.attrs = {k: v for k, v in ds.attrs.items() if k not in RUN_ATTRS}
    with output_set() as files:
        files.file(paths[0], lambda tmp: kept.to_netcdf(tmp, engine="scipy"), "--out")
        files.file(paths[1], lambda tmp: table.to_csv(tmp, index=False, float_format="%.6g"), "--out")
        files.file(paths[2], lambda tmp: Path(tmp).write_text(ds.attrs["sweep_toml"]), "--out")
    return paths


def table_of(ds):
    """The tidy table of a sweep: one row per cell (and distance), the axes first in the file's order
    (scalar coordinates too; `env_name` after `env`), then the metrics."""
    import pandas as pd  # pandas: an xarray dependency, loaded with the table

    if ds.dims:
        table = ds.to_dataframe().reset_index()
    else:  # every axis has one value: one row
        table = pd.DataFrame([{k: v.item() for k, v in {**ds.coords, **ds.data_vars}.items()}])
    table = table.rename(columns=axis_name)  # the sweep file's names: `method`, not `homing_method`
    first = [axis_name(c) for c in ds.coords if axis_name(c) in table.columns and c != "env_name"]
    if "env_name" in table.columns:
        first.insert(first.index("env") + 1, "env_name")
    return table[first + [c for c in table.columns if c not in first]]


def sweep_inputs(out: str | Path) -> list[Path]:
    """The files and folders of a sweep folder that `load_sweep` and a resumed sweep read."""
    return [Path(out) / f for f in FILES] + [Path(out) / STORE]


def load_sweep(out: str | Path):
    """The `xarray.Dataset` of a finished sweep folder (`delvjax sweep ... --out DIR`)."""
    import xarray as xr  # xarray: loaded only when results are labelled

    path = Path(out) / FILES[0]
    if not path.is_file():
        raise InputError("out", str(out), f"has no {FILES[0]} (not a finished sweep folder)")
    try:
        with xr.open_dataset(path, engine="scipy") as ds:
            return safe_names(ds.load())
    except Exception as exc:  # noqa: BLE001 - a damaged file raises whatever the reader meets first
        raise InputError(
            "out",
            str(out),
            f"has a {FILES[0]} that cannot be read ({type(exc).__name__}): rerun the sweep to rewrite it",
        ) from None
