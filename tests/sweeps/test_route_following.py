"""Route-following sweeps (docs/sweeps.md "Route-following sweeps", issue 57): every cell equals
`delvjax.route_experiments`' trials with the same settings, number for number, however the cells are chunked;
the metrics move with the noise (not stuck at 100 %); bad cells are refused before any work, naming the cell."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax.core.errors import InputError
from delvjax.core.rollouts.rules import SUCCESS
from delvjax.sweeps import _run as sweep_run
from delvjax.sweeps._run import run_sweep
from delvjax.sweeps._spec import parse_sweep

SWEEP = """
[sweep]
kind = "route-following"
trials = 4
[axes]
method = ["perfect-memory", "infomax"]
heading_noise_deg = [0, 90]
max_steps = [40]
seed = [0, 3]
"""


@pytest.fixture(scope="module")
def swept():
    return run_sweep(parse_sweep(SWEEP))


def test_every_cell_is_route_experiments_trials(swept):
    for model in ("perfect-memory", "infomax"):
        for noise in (0, 90):
            r = delvjax.route_experiments(
                "robot", model, trials=4, heading_noise_deg=noise, max_steps=40, seed=3, grid_spacing=60.0
            )
            cell = swept.sel(homing_method=model, heading_noise_deg=noise, seed=3)
            ok = int(np.sum(np.asarray(r.trials.outcome) == SUCCESS))
            assert float(cell.route_success_pct) == pytest.approx(25.0 * ok)
            assert float(cell.mean_route_errors) == pytest.approx(np.mean(np.asarray(r.trials.errors)))
            assert float(cell.mean_moves) == pytest.approx(np.mean(np.asarray(r.trials.steps)))
            assert int(cell.trials_run) == 4


def test_the_success_rate_moves_with_the_noise(swept):
    """Without noise both models follow the route; at 90 deg they fail more often and leave it more."""
    quiet, noisy = swept.sel(heading_noise_deg=0), swept.sel(heading_noise_deg=90)
    assert float(quiet.route_success_pct.min()) == 100.0
    assert float(noisy.route_success_pct.mean()) < 100.0
    assert float(noisy.mean_route_errors.mean()) > float(quiet.mean_route_errors.mean())
    lo, hi = swept.route_success_ci95_lo_pct, swept.route_success_ci95_hi_pct
    assert bool((lo <= swept.route_success_pct).all() and (swept.route_success_pct <= hi).all())


def test_the_numbers_do_not_depend_on_the_chunks(swept, monkeypatch):
    monkeypatch.setattr(sweep_run, "CELL_CHUNK", 1)
    again = run_sweep(parse_sweep(SWEEP))
    for name in ("route_success_pct", "mean_route_errors", "mean_moves"):
        np.testing.assert_array_equal(again[name].values, swept[name].values)
    assert swept.attrs["programs_compiled"] <= 2  # one program per model


def test_an_environment_as_cylinders_and_a_model_setting_are_axes():
    text = SWEEP.replace(
        'method = ["perfect-memory", "infomax"]', 'method = ["perfect-memory"]\nenv = ["robot", "env1"]'
    )
    text = text.replace("heading_noise_deg = [0, 90]", 'heading_noise_deg = [10]\nkind = ["abs", "corr"]')
    ds = run_sweep(parse_sweep(text.replace("seed = [0, 3]", "seed = [0]")))
    assert ds.route_success_pct.shape == (2, 2)
    assert np.isfinite(ds.route_success_pct.values).all()


@pytest.mark.parametrize(
    "line, field, words",
    [
        ("learning_rate = [0.5]", "cell (", "is no setting of perfect-memory"),
        ("heading_noise_deg = [-1]", "cell (", "heading_noise_deg"),
        ("route_spacing = [0]", "cell (", "route_spacing"),
        ('env = ["nowhere"]', "env", "is no image world (robot, natural) nor habitat<seed>, and unknown preset"),
        ('method = ["delv"]', "cell (", "must be one of"),
        ("spacing = [25]", "axes.spacing", "is not an axis of kind"),
        ("bearing_noise_deg = [1]", "axes.bearing_noise_deg", "is not an axis of kind"),
    ],
)
def test_bad_cells_are_refused_before_any_work(line, field, words, monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_run, "evaluate", lambda *a, **k: calls.append(1))
    text = '[sweep]\nkind = "route-following"\ntrials = 2\n[axes]\nmax_steps = [5]\n' + line + "\n"
    with pytest.raises(InputError) as exc:
        run_sweep(parse_sweep(text))
    assert exc.value.field.startswith(field) and words in str(exc.value)
    assert not calls


def test_distances_belong_to_the_success_rate_kind():
    with pytest.raises(InputError) as exc:
        parse_sweep('[sweep]\nkind = "route-following"\ndistances = [50]\n')
    assert exc.value.field == "sweep.distances"
    assert parse_sweep('[sweep]\nkind = "route-following"\n').trials == 20


def test_the_results_are_saved_reloaded_and_drawn(swept, tmp_path):
    from delvjax.cli._main import main
    from delvjax.sweeps import load_sweep, save_sweep

    save_sweep(swept, tmp_path)
    back = load_sweep(tmp_path)
    np.testing.assert_array_equal(back.route_success_pct.values, swept.route_success_pct.values)
    assert back.heading_noise_deg.attrs["units"] == "degree" and back.route_success_pct.attrs["units"] == "percent"
    argv = ["plot-sweep", str(tmp_path), "--x", "heading_noise_deg", "--metric", "route_success_pct"]
    assert main(argv) == 0
    drawn = np.genfromtxt(tmp_path / "route_success_pct.csv", delimiter=",", names=True, dtype=None, encoding=None)
    assert len(drawn) == 4  # two models x two noise levels, mean over the seeds
