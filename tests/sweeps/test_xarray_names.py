"""A sweep's Dataset has no dimension or coordinate named like an argument of xarray's selection methods
(issue 53 point 5): `ds.sel(method="delv")` returned both methods without a word, since `method` is `sel`'s own
keyword; the axis `method` is the dimension `homing_method`, the sweep file and sweep.csv keep `method`."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest
import xarray as xr

from delvjax.core.maps import VectorMap, map_dataset
from delvjax.sweeps import load_sweep, run_sweep, save_sweep
from delvjax.sweeps._kinds import KINDS, sum_names
from delvjax.sweeps._results import SELECTORS, XARRAY_KEYWORDS, dataset, safe_names
from delvjax.sweeps._spec import SweepSpec, axes, name_axes, parse_sweep

SWEEP = '[sweep]\nkind = "vector-map"\n[axes]\nmethod = ["delv", "alv"]\nspacing = [200]\nseed = [0, 1]\n'


def test_the_keywords_are_every_argument_of_xarrays_selectors():
    """The installed xarray's selection methods take no argument the list lacks (a new one would be missed)."""
    found = set()
    for name in SELECTORS:
        found |= set(inspect.signature(getattr(xr.Dataset, name)).parameters) - {"self"}
    assert found <= XARRAY_KEYWORDS, found - XARRAY_KEYWORDS
    assert {"method", "tolerance", "drop", "indexers"} <= XARRAY_KEYWORDS


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep")
    ds = run_sweep(parse_sweep(SWEEP))
    save_sweep(ds, out)
    return ds, out


def test_a_user_selects_one_method_by_keyword(swept):
    ds, out = swept
    for data in (ds, load_sweep(out)):
        one = data.sel(homing_method="delv")  # the keyword form a user types
        assert "homing_method" not in one.dims and one.homing_method.item() == "delv"
        assert np.array_equal(one.mean_error_deg.values, data.mean_error_deg.isel(homing_method=0).values)
        assert "method" not in data.variables and data.attrs["renamed_axes"] == "method -> homing_method"
    table = pd.read_csv(out / "sweep.csv")  # the table keeps the sweep file's name
    assert list(table.columns[:3]) == ["method", "spacing", "seed"] and set(table.method) == {"delv", "alv"}
    assert "method = " in (out / "sweep.toml").read_text()


def test_a_file_written_before_the_renaming_reads_renamed(swept, tmp_path):
    ds, _ = swept
    old = ds.rename(homing_method="method")
    old.attrs = {k: v for k, v in ds.attrs.items() if k not in ("renamed_axes", "programs_compiled", "cells_reused")}
    (tmp_path / "old").mkdir()
    old.to_netcdf(tmp_path / "old" / "sweep.nc", engine="scipy")
    back = load_sweep(tmp_path / "old")
    assert "homing_method" in back.dims and "method" not in back.variables
    assert back.attrs["renamed_axes"] == "method -> homing_method"


def _fake(spec: SweepSpec):
    n = spec.n_cells
    extra = (len(spec.distances),) if spec.kind.per_distance else ()
    return dataset(spec, {k: np.ones((n,) + extra) for k in sum_names(spec.kind)}, 0)


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_no_axis_of_any_kind_is_an_xarray_keyword(kind):
    """Every axis a kind accepts (two values each, a dimension) and the scalar ones: none named like a keyword."""
    names = set(name_axes())
    for axis in axes(KINDS[kind]):
        values = ["a", "b"] if axis in names else [1, 2]
        for shown in (values, values[:1]):  # a dimension, and a scalar coordinate
            spec = SweepSpec(kind, {axis: shown}, list(KINDS[kind].metrics), "")
            ds = _fake(spec)
            assert not set(map(str, ds.variables)) & XARRAY_KEYWORDS, (kind, axis)


def test_a_vector_maps_dataset_has_no_keyword_dimension():
    """`VectorMap.to_xarray` on a grid (y, x) and on scattered points (`point`)."""
    grid = np.stack(np.meshgrid([0.0, 1.0], [0.0, 1.0, 2.0]), -1).reshape(-1, 2)
    for pts in (grid, np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 1.0]])):
        zero, true = np.zeros(len(pts), np.float32), np.ones(len(pts), bool)
        vm = VectorMap(pts.astype(np.float32), true, zero, zero, true, zero)
        ds = map_dataset(vm)
        assert ("point" in ds.dims) != ("y" in ds.dims)
        assert not set(map(str, ds.variables)) & XARRAY_KEYWORDS


def test_safe_names_keeps_a_dataset_without_keywords():
    ds = xr.Dataset({"a": (("d",), [1.0, 2.0])}, coords={"d": [1, 2]})
    assert safe_names(ds) is ds and "renamed_axes" not in ds.attrs
    named = safe_names(ds.assign_coords(tolerance=3.0))
    assert "sweep_tolerance" in named.coords and named.attrs["renamed_axes"] == "tolerance -> sweep_tolerance"
