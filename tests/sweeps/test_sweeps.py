"""Sweep files (docs/sweeps.md): validation before any work, one program per shape, cells equal to
`delvjax.vector_map`, the same numbers however cells are chunked, labelled results."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.sweeps import _run as sweeps
from delvjax.sweeps._examples import EXAMPLE
from delvjax.sweeps._kinds.base import shared_program
from delvjax.sweeps._spec import parse_sweep

SMALL = """
[sweep]
metrics = ["gt45_pct", "gt90_pct", "mean_error_deg", "mean_error_ci95_deg", "invalid_pct", "points"]
[axes]
method = ["delv", "alv"]
d = [30, 60]
bearing_noise_deg = [0.0, 3.0]
seed = {start = 0, stop = 1}
spacing = [90]
"""


@pytest.fixture(scope="module")
def small():
    return sweeps.run_sweep(parse_sweep(SMALL))


# DELV on env1 at 200 cm, two cells: the command-line, plotting and resuming tests run this shape (or
# chunks of it), so they share one compiled program (the suite is compile-bound: docs/reproduce.md)
TWO_CELLS = "[axes]\nd = [40, 80]\nseed = [3]\nspacing = [200]\n"


def cli_sweep(tmp_path, text: str) -> tuple[int, object, object]:
    """Write `text` as a sweep file and run `delvjax sweep` into tmp_path/out: (exit, file, out)."""
    path, out = tmp_path / "s.toml", tmp_path / "out"
    path.write_text(text)
    return main(["sweep", str(path), "--out", str(out)]), path, out


def test_the_example_file_is_valid_and_printed(capsys):
    spec = parse_sweep(EXAMPLE)
    assert spec.shape == (
        2,
        2,
        4,
        2,
        3,
        1,
    ) and list(spec.axes)[:3] == ["env", "method", "d"]
    assert spec.axes["d"] == [10, 40, 70, 100] and spec.axes["seed"] == [0, 1, 2]
    assert main(["sweep", "--example"]) == 0
    assert capsys.readouterr().out == EXAMPLE


def test_every_cell_equals_the_vector_map_of_its_settings(small):
    assert dict(small.sizes) == {"homing_method": 2, "d": 2, "bearing_noise_deg": 2, "seed": 2}
    # axes with one value are scalar coordinates, labelled with the environment's own name
    assert small["env"].item() == "env1" and small["env_name"].item() == "env1" and float(small["spacing"]) == 90.0
    # one program for both landmark methods (none if an earlier test compiled it)
    assert 0 <= small.attrs["programs_compiled"] <= 1
    for method in ("delv", "alv"):
        for seed in (0, 1):
            vm = delvjax.vector_map(
                "env1", method=method, d=60, bearing_noise_deg=3.0, seed=seed, grid=Grid(spacing=90.0)
            )
            s = delvjax.summarize_map(vm.error_deg, vm.valid, vm.included)
            cell = small.sel({"homing_method": method, "d": 60, "bearing_noise_deg": 3.0, "seed": seed}).squeeze()
            assert int(cell.points) == s["points"] and float(cell.invalid_pct) == 100 * s["invalid"] / s["points"]
            assert float(cell.gt45_pct) == s["gt45_pct"] and float(cell.gt90_pct) == s["gt90_pct"]
            assert float(cell.mean_error_deg) == pytest.approx(s["mean_error_deg"], rel=1e-6)
            assert 0 < float(cell.mean_error_ci95_deg) < 30
    noisy, exact = small.sel({"bearing_noise_deg": 3.0}), small.sel({"bearing_noise_deg": 0.0})
    assert float(noisy.mean_error_deg.mean()) > float(exact.mean_error_deg.mean())  # the axis reaches the cells


def test_the_numbers_do_not_depend_on_how_cells_are_chunked(small, monkeypatch):
    monkeypatch.setattr(sweeps, "CELL_CHUNK", 3)
    chunked = sweeps.run_sweep(parse_sweep(SMALL))
    for name in small.data_vars:
        assert np.array_equal(small[name].values, chunked[name].values, equal_nan=True), name


def test_landmark_methods_share_one_program_and_keep_their_numbers_bit_for_bit(small):
    assert shared_program(parse_sweep(SMALL), "alv") == ("delv", "alv")
    mixed = parse_sweep("[axes]\nmethod = ['delv', 'warping', 'alv', 'minwarping', 'cc']")
    assert [shared_program(mixed, m) for m in ("cc", "warping", "minwarping")] == [("delv", "alv", "cc"), None, None]
    assert shared_program(parse_sweep("[axes]\nmethod = ['alv']"), "alv") is None
    alone = sweeps.run_sweep(parse_sweep(SMALL.replace('["delv", "alv"]', '["alv"]')))  # ALV's own program
    for name in small.data_vars:
        assert np.array_equal(small[name].sel({"homing_method": "alv"}).values, alone[name].values, equal_nan=True), (
            name
        )


@pytest.mark.parametrize(
    "text, field",
    [
        ("[axes]\nd = []", "axes.d"),
        ("[axes]\nd = {start = 5, stop = 1}", "axes.d"),
        ("[axes]\nd = [1, 1]", "axes.d"),
        ("[axes]\nd = [50, 50.0]", "axes.d"),  # one value written twice
        ("[axes]\nd = [true, 2]", "axes.d"),
        ("[axes]\nd = {start = 10, stop = 100, step = 1e-300}", "axes.d"),  # too many values
        ("[axes]\nd = {start = 10, stop = 100, step = 1e-320}", "axes.d"),  # a subnormal step: not an OverflowError
        ("[sweep]\nmetrics = [['gt45_pct']]", "sweep.metrics[0]"),  # a nested list
        ("[axes]\nlevls = [1]", "axes.levls"),
        ("[axes]\nmotion_step_noise = [0.1]", "axes.motion_step_noise"),  # a rollout axis in a vector-map sweep
        ("[sweep]\nkind = 'success-rate'\n[axes]\nspacing = [10]", "axes.spacing"),
        ("[axes]\nmethod = [1]", "axes.method"),
        ("[axes]\nfirst_move = [1]", "axes.first_move"),
        ("[sweep]\nmetrics = ['catchment']", "sweep.metrics[0]"),
        ("[sweep]\nmetrics = ['catchment_pct']", "sweep.metrics[0]"),  # a catchment metric in a vector-map sweep
        ("[sweep]\nkind = 'catchment'\nmetrics = ['success_pct']", "sweep.metrics[0]"),
        ("[sweep]\nkind = 'catchments'", "sweep.kind"),
        ("[sweep]\ntrials = 5", "sweep.trials"),
        ("[sweep]\nkind = 'success-rate'\ntrials = 0", "sweep.trials"),
        ("[sweep]\nkind = 'success-rate'\ndistances = []", "sweep.distances"),
        ("[sweep]\nkind = 'success-rate'\ndistances = ['a']", "sweep.distances"),
        ("[sweep]\nmetric = ['gt45_pct']", "sweep.metric"),
        ("[axis]\nd = [1]", "axis"),
        ("d = [", "sweep"),
    ],
)
def test_a_bad_sweep_file_names_its_field(text, field):
    with pytest.raises(InputError) as exc:
        parse_sweep(text)
    assert exc.value.field == field


def test_an_incompatible_cell_is_refused_before_any_work(tmp_path, capsys):
    code, _, out = cli_sweep(tmp_path, "[axes]\nmethod = ['delv', 'alv']\nlevels = [2]\nspacing = [200]\n")
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "method=alv" in err[0] and "levels: is not a setting of the method alv" in err[0]
    assert not out.exists()


def test_the_cli_writes_netcdf_csv_and_the_file_and_load_sweep_reads_them(tmp_path, capsys):
    code, path, out = cli_sweep(tmp_path, TWO_CELLS)
    assert code == 0
    assert sorted(p.name for p in out.iterdir()) == [".cells", "sweep.csv", "sweep.nc", "sweep.toml"]
    ds = delvjax.load_sweep(out)
    assert dict(ds.sizes) == {"env": 1, "method": 1, "spacing": 1, "seed": 1, "d": 2} or ds.sizes["d"] == 2
    assert ds.attrs["sweep_toml"] == path.read_text() and "jax_version" in ds.attrs
    for name in [*ds.data_vars, *ds.coords]:  # self-describing: CF long_name on all, units on every number
        assert ds[name].attrs.get("long_name"), name
        assert ds[name].dtype.kind in "OUS" or ds[name].attrs.get("units"), name
    assert ds["gt45_pct"].attrs["units"] == "percent" and ds["d"].attrs == {
        "long_name": "unit-movement step",
        "units": "cm",
    }
    rows = (out / "sweep.csv").read_text().splitlines()
    assert len(rows) == 3 and rows[0].startswith("d,seed,spacing,env,env_name,method,gt45_pct")
    with pytest.raises(InputError, match="sweep.nc"):
        delvjax.load_sweep(tmp_path)


FOUR = """
import sys, numpy as np, jax
from delvjax.sweeps._spec import parse_sweep
from delvjax.sweeps import run_sweep
assert jax.local_device_count() == 4
results = {}
for i, text in enumerate(sys.argv[2:]):
    ds = run_sweep(parse_sweep(text))
    results.update({f"{i}/{k}": ds[k].values for k in ds.data_vars})
    results[f"{i}/programs"] = ds.attrs["programs_compiled"]
np.savez(sys.argv[1], **results)
"""
TINY = "[axes]\nd = [40, 80]\nseed = [0, 1, 2]\nbearing_noise_deg = [2.0]\nspacing = [200]\n"  # TWO_CELLS' shape
TINY_CATCHMENT = (
    "[sweep]\nkind = 'catchment'\n[axes]\nocclude = [0, 1]\nseed = [0, 1, 2]\nmax_steps = [10, 50]\n"
    "bearing_noise_deg = [4.0]\nmethod = ['alv']\nspacing = [150]\n"
)


def test_cells_split_over_four_devices_give_the_one_device_numbers(tmp_path, monkeypatch):
    """6 cells over 4 forced host devices (padded to 8, two a device): every metric bitwise equal,
    for a vector-map and a catchment sweep (two values of max_steps, a traced number: one program).
    On one device the vector-map cells run in chunks of 2 (TWO_CELLS' program, compiled once for the file;
    the numbers do not depend on the chunks: `test_the_numbers_do_not_depend_on_how_cells_are_chunked`)."""
    import os
    import subprocess
    import sys

    out = tmp_path / "four.npz"
    env = dict(os.environ, XLA_FLAGS="--xla_force_host_platform_device_count=4", JAX_PLATFORMS="cpu")
    run = subprocess.run(
        [sys.executable, "-c", FOUR, str(out), TINY, TINY_CATCHMENT], env=env, capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr[-2000:]
    four = np.load(out)
    default = sweeps.CELL_CHUNK
    for i, text in enumerate((TINY, TINY_CATCHMENT)):
        monkeypatch.setattr(sweeps, "CELL_CHUNK", 2 if i == 0 else default)
        one = sweeps.run_sweep(parse_sweep(text))
        for name in one.data_vars:
            assert np.array_equal(one[name].values, four[f"{i}/{name}"], equal_nan=True), name
        assert i == 0 or 0 < float(one.catchment_pct.min()) < 100  # a catchment that can differ
    assert int(four["1/programs"]) == 1  # max_steps 10 and 50: one program split over the devices


def test_a_killed_sweep_resumes_and_a_changed_file_computes_only_its_new_cells(tmp_path, monkeypatch):
    text = TWO_CELLS.replace("[3]", "[0, 1]")  # 4 cells in chunks of 2: the program of TWO_CELLS
    monkeypatch.setattr(sweeps, "CELL_CHUNK", 2)
    real, calls = sweeps.evaluate, []

    def counted(kind, setups, *args, **kwargs):
        calls.append(len(setups))
        if len(calls) == 2 and kill:
            raise KeyboardInterrupt  # killed after the first chunk
        return real(kind, setups, *args, **kwargs)

    monkeypatch.setattr(sweeps, "evaluate", counted)
    kill, out = True, tmp_path / "out"
    with pytest.raises(KeyboardInterrupt):
        sweeps.run_sweep(parse_sweep(text), out=out)
    assert len(list((out / ".cells").glob("*.npz"))) == 1  # the finished chunk, nothing partial
    kill, calls[:] = False, []
    resumed = sweeps.run_sweep(parse_sweep(text), out=out)
    assert calls == [2] and resumed.attrs["cells_reused"] == 2
    fresh = sweeps.run_sweep(parse_sweep(text))
    for name in fresh.data_vars:
        assert np.array_equal(fresh[name].values, resumed[name].values, equal_nan=True), name
    calls[:] = []
    changed = sweeps.run_sweep(parse_sweep(text.replace("[40, 80]", "[40, 80, 120]")), out=out)
    assert calls == [2] and changed.attrs["cells_reused"] == 4  # only d = 120 (two seeds) is new


def test_skipped_cells_are_not_computed_and_the_others_keep_their_numbers(monkeypatch):
    text = TWO_CELLS.replace("[3]", "[0, 1]")  # 4 cells in chunks of 2: the program of TWO_CELLS
    monkeypatch.setattr(sweeps, "CELL_CHUNK", 2)
    real, calls = sweeps.evaluate, []
    monkeypatch.setattr(
        sweeps, "evaluate", lambda kind, setups, *a, **k: calls.append(len(setups)) or real(kind, setups, *a, **k)
    )
    full = sweeps.run_sweep(parse_sweep(text))
    calls[:] = []
    part = sweeps.run_sweep(parse_sweep(text), skip=lambda cell: cell["seed"] == 1 and cell["d"] == 80)
    assert calls == [2, 2] and part.attrs["cells_skipped"] == 1 and part.attrs["cells_reused"] == 0
    for name in full.data_vars:
        kept = part[name].sel({"d": 40})
        assert np.array_equal(kept.values, full[name].sel({"d": 40}).values, equal_nan=True), name
        assert np.array_equal(part[name].sel({"d": 80, "seed": 0}), full[name].sel({"d": 80, "seed": 0})), name
        assert np.isnan(part[name].sel({"d": 80, "seed": 1}).values), name


def test_sweep_figures_heat_maps_and_lines_with_intervals_over_seeds(small, tmp_path):
    from delvjax.plots._sweep import check_plot, sweep_figure

    fig, rows = sweep_figure(small, "d", "bearing_noise_deg", "gt45_pct")  # one panel per method
    assert len([a for a in fig.axes if a.get_visible() and a.get_title()]) == 2 and len(rows) == 2 * 2 * 2
    cell = small.gt45_pct.sel({"homing_method": "alv", "d": 60, "bearing_noise_deg": 3.0}).values.mean()
    assert [
        r["gt45_pct"] for r in rows if r["panel"] == "method=alv" and r["d"] == 60 and r["bearing_noise_deg"] == 3.0
    ] == [pytest.approx(cell)]
    images = [a.images[0] for a in fig.axes if a.images]  # one colour scale: the same colour is the same number
    values = [r["gt45_pct"] for r in rows]
    assert len(images) == 2 and {im.get_clim() for im in images} == {(min(values), max(values))}
    _, lines = sweep_figure(small, "d", None, "mean_error_deg")  # two seeds: a finite 95 % interval
    assert len(lines) == 2 * 2 * 2 and all(r["ci95_lo"] < r["mean_error_deg"] < r["ci95_hi"] for r in lines)
    for args, flag in [
        (("dd", None, "gt45_pct"), "--x"),
        (("d", "d", "gt45_pct"), "--y"),
        (("d", None, "x"), "--metric"),
    ]:
        with pytest.raises(InputError) as exc:
            check_plot(small, *args)
        assert exc.value.field == flag


def test_plot_sweep_writes_the_figure_and_its_numbers(tmp_path, capsys):
    code, _, out = cli_sweep(tmp_path, TWO_CELLS)
    assert code == 0
    assert main(["plot-sweep", str(out), "--x", "d", "--metric", "gt45_pct"]) == 0
    assert (out / "gt45_pct.png").stat().st_size > 1000 and len((out / "gt45_pct.csv").read_text().splitlines()) == 3
    assert main(["plot-sweep", str(out), "--x", "levels"]) == 2
    assert "--x: is not an axis" in capsys.readouterr().err


@pytest.mark.parametrize(
    "command",
    [None, "envs", "vector-map", "catchment", "success-rate", "trajectories", "reproduce", "sweep", "plot-sweep"],
)
def test_every_help_text_prints(command, capsys):
    """argparse %-formats help strings: a bare "95 %" once broke `delvjax --help`."""
    with pytest.raises(SystemExit) as exc:
        main([command, "--help"] if command else ["--help"])
    assert exc.value.code == 0 and "usage: delvjax" in capsys.readouterr().out


def test_a_damaged_sweep_file_is_one_line_not_a_plot(tmp_path, capsys):
    from tests.cases.faults import fake_sweep

    folder = fake_sweep(tmp_path / "s")
    data = (folder / "sweep.nc").read_bytes()
    (folder / "sweep.nc").write_bytes(data[: len(data) - 20])  # a copy cut short
    assert main(["plot-sweep", str(folder), "--x", "d"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "sweep.nc that cannot be read" in err[0]
    assert sorted(p.name for p in folder.iterdir()) == ["sweep.csv", "sweep.nc", "sweep.toml"]


@pytest.mark.parametrize("y", [None, "bearing_noise_deg"])
def test_sweep_figures_of_many_values_stay_readable(y):
    """40 values of d and 30 of the noise: tick labels thinned, no text over another (`figure_defects`)."""
    import xarray as xr

    from delvjax.plots._sweep import sweep_figure
    from tests.cases.figures import figure_defects

    d, noise = np.linspace(10.0, 400.0, 40), np.linspace(0.0, 14.5, 30)
    values = np.random.default_rng(0).uniform(0, 90, (2, 40, 30, 2))
    ds = xr.Dataset(
        {"mean_error_deg": (("homing_method", "d", "bearing_noise_deg", "seed"), values, {"units": "degree"})},
        coords={
            "homing_method": ["delv", "alv"],
            "d": ("d", d, {"units": "cm"}),
            "bearing_noise_deg": noise,
            "seed": [0, 1],
        },
    )
    if y is None:
        ds = ds.isel(bearing_noise_deg=0)
    fig, rows = sweep_figure(ds, "d", y, "mean_error_deg")
    assert figure_defects(fig) == [] and len(rows) == (2 * 40 if y is None else 2 * 40 * 30)


def test_a_vector_map_chunks_padding_evaluates_no_point_and_each_cell_is_set_up_once(monkeypatch):
    """Issue 54: a row that pads a chunk (`evaluate`'s `real`) evaluates no grid point (`map_cells`' `live`: all
    its points invalid) and leaves the real rows' numbers as they were; a sweep validates and sets up each cell
    once (`_plan` keeps the setups; before, every chunk set its cells and padding up again)."""
    from delvjax.sweeps._kinds import cell_setup, evaluate

    spec = parse_sweep(TWO_CELLS)
    envs = sweeps._envs(spec)
    setups = [cell_setup(spec, envs, spec.cell(i), 10_000) for i in range(2)]
    idle, running = (evaluate(spec.kind, setups, None, real=real) for real in (1, None))
    assert idle["invalid"][1] == idle["points"][1] > 0 and running["invalid"][1] < running["points"][1]
    for name, values in idle.items():
        np.testing.assert_array_equal(values[0], running[name][0])
    calls = []
    monkeypatch.setattr(sweeps, "cell_setup", lambda *a, **k: calls.append(1) or cell_setup(*a, **k))
    sweeps.run_sweep(spec)
    assert len(calls) == 2
