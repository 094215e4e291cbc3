"""Issue 55 point 1: one `Progress` object, the CLI's vector map through the API, a map that carries its grid."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import delvjax
from delvjax import Grid, Rules
from delvjax.cli import _main
from delvjax.core import maps
from delvjax.core.errors import InputError
from delvjax.evaluate import Progress
from delvjax.plots import vector_map_figure

SPACING = 50.0  # env1: a 20 x 20 grid, in chunks of 128 points (`batching.bucket` pads to 128)


class Recorder(Progress):
    """A `Progress` that writes down every call."""

    def __init__(self):
        self.calls: list[tuple] = []

    def start(self, total, phase=None):
        self.calls.append(("start", total))

    def __call__(self, done, total):
        self.calls.append(("done", done, total))


@pytest.fixture(scope="module")
def chunked():
    """(map, recorder): the 400-point grid in chunks of 128 points."""
    report = Recorder()
    return delvjax.vector_map("env1", batch_size=128, progress=report, grid=Grid(spacing=SPACING)), report


def test_a_vector_map_starts_its_progress_once_with_the_grid_then_reports_each_chunk(chunked):
    # before: `vector_map` took no progress (the keyword was refused as an unknown setting)
    vm, report = chunked
    n = vm.points.shape[0]
    assert n == 400
    assert report.calls == [("start", n)] + [("done", 128, n)] * 3 + [("done", 16, n)]


def test_a_plain_function_still_gets_the_chunks():
    calls = []
    delvjax.vector_map(
        "env1", batch_size=128, progress=lambda done, total: calls.append(done), grid=Grid(spacing=SPACING)
    )
    assert calls == [128, 128, 128, 16]


def test_bad_input_starts_no_progress():
    # the command line prints its line in `start`: an error must stay one line
    report = Recorder()
    with pytest.raises(InputError, match="spacing"):
        delvjax.vector_map("env1", progress=report, grid=Grid(spacing=-1.0))
    with pytest.raises(InputError, match="max_steps"):
        delvjax.catchment("env1", progress=report, grid=Grid(spacing=SPACING), rules=Rules(max_steps=0))
    assert report.calls == []


def test_a_map_carries_its_spacing_and_its_figure_needs_none(chunked):
    # before: `VectorMap` had no spacing and `vector_map_figure` required one
    vm, _ = chunked
    assert vm.spacing == SPACING
    env = delvjax.load_env("env1")

    def pixels(fig):
        canvas = FigureCanvasAgg(fig)
        canvas.draw()
        return np.asarray(canvas.buffer_rgba())

    alone = pixels(vector_map_figure(env, vm, title="t", classes=True))
    given = pixels(vector_map_figure(env, vm, SPACING, title="t", classes=True))
    half = pixels(vector_map_figure(env, vm, spacing=SPACING / 2, title="t", classes=True))
    assert np.array_equal(alone, given)
    assert not np.array_equal(alone, half)  # the keyword still decides when given
    with pytest.raises(ValueError, match="spacing="):
        vector_map_figure(
            env, maps.VectorMap(*(vm.points, vm.included, vm.heading, vm.direction, vm.valid, vm.error_deg))
        )


def test_the_cli_vector_map_calls_the_api_once_and_the_core_only_through_it(tmp_path, monkeypatch, capsys):
    # before: the CLI called `core.maps.vector_map` itself (around the API) and counted the grid itself
    api_calls, core_calls = [], []
    api_map, core_map = _main.api.vector_map, maps.vector_map

    def api_spy(*args, **kwargs):
        api_calls.append(kwargs)
        return api_map(*args, **kwargs)

    def core_spy(*args, **kwargs):
        core_calls.append(kwargs)
        return core_map(*args, **kwargs)

    monkeypatch.setattr(_main.api, "vector_map", api_spy)
    monkeypatch.setattr(maps, "vector_map", core_spy)
    out = tmp_path / "vm.csv"
    assert _main.main(["vector-map", "env1", "--spacing", "100", "--out", str(out)]) == 0
    assert len(api_calls) == 1 and len(core_calls) == 1
    assert isinstance(api_calls[0]["progress"], Progress)
    err = capsys.readouterr().err
    assert "(spacing 100 cm, 100 cells)" in err  # the count the API built, given to the bar's start


class Phases(Recorder):
    """A `Recorder` that also writes down the phases."""

    def phase(self, text):
        self.calls.append(("phase", text))


TINY_SWEEP = '[sweep]\nkind = "vector-map"\n[axes]\nenv = ["env1"]\nmethod = ["alv"]\nspacing = [400]\nseed = [0, 1]\n'


def test_a_sweep_reports_to_one_progress_start_phases_and_chunks():
    """`run_sweep` speaks to one `Progress`: `start(n)` once every cell is checked, `phase` where a program
    compiles, `(done, n)` per chunk (before: three callbacks, announce=, phase= and progress=)."""
    from delvjax.sweeps import parse_sweep, run_sweep

    report = Phases()
    run_sweep(parse_sweep(TINY_SWEEP), progress=report)
    assert report.calls[0] == ("start", 2) and report.calls[1] == ("phase", "compiling program 1 of 1")
    assert sum(c[1] for c in report.calls if c[0] == "done") == 2


def test_the_old_callbacks_still_work_with_a_deprecation_warning(monkeypatch):
    from delvjax.sweeps import parse_sweep, run_sweep

    seen = []
    with pytest.deprecated_call(match=r"run_sweep\(\): announce= and phase= are deprecated"):
        run_sweep(parse_sweep(TINY_SWEEP), announce=lambda: seen.append("announce"), phase=seen.append)
    assert seen == ["announce", "compiling program 1 of 1"]
    with pytest.raises(TypeError, match="unexpected keyword"):
        run_sweep(parse_sweep(TINY_SWEEP), anounce=print)
