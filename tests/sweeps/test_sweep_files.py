"""Sweep files as a user writes them (issue 53): typos get the name meant, lists are capped as ranges are, a sweep
states its time first, a relative environment path is the file's folder's, and bands stay what a metric can be."""

from __future__ import annotations

import json

import numpy as np
import pytest

from delvjax.core.errors import InputError
from delvjax.sweeps._spec import parse_sweep


@pytest.mark.parametrize(
    "text, hint",
    [
        ("[axes]\nbearing_nosie_deg = [1]", "did you mean 'bearing_noise_deg'?"),
        ("[axes]\nD = [20]", "did you mean 'd'?"),
        ("[sweep]\nmetric = ['gt45_pct']", "did you mean 'metrics'?"),
        ("[sweep]\nmetrics = ['mean_eror_deg']", "did you mean 'mean_error_deg'?"),
        ("[sweep]\nbearing_noise_deg = [1]", "is an axis: put it under [axes]"),
        ("[sweep]\nbearing_nois_deg = [1]", "did you mean 'bearing_noise_deg'?), and axes go under [axes]"),
    ],
)
def test_a_typo_in_a_sweep_file_gets_the_name_it_was_meant_to_be(text, hint):
    """Issue 53 point 8: 53 axis names and no hint were not enough to find a swapped letter."""
    with pytest.raises(InputError) as exc:
        parse_sweep(text)
    assert hint in str(exc.value)


def test_a_list_of_a_million_seeds_is_refused_as_a_range_is():
    """Issue 53 point 9: the 100,000-value cap applied to ranges only, so a list of 10**6 seeds ran for hours."""
    text = "[axes]\nseed = [" + ", ".join(map(str, range(100_001))) + "]"
    with pytest.raises(InputError) as exc:
        parse_sweep(text)
    assert exc.value.field == "axes.seed" and "more than 100000 values" in str(exc.value)


def test_a_sweep_states_its_time_before_it_starts():
    small = parse_sweep("[axes]\nseed = [0, 1]")
    big = parse_sweep("[axes]\nseed = {start = 0, stop = 199}")
    assert 0 < small.seconds() < big.seconds() == pytest.approx(100 * small.seconds())
    rates = parse_sweep("[sweep]\nkind = 'success-rate'\ntrials = 100\n[axes]\nseed = [0, 1]")
    assert rates.seconds() == pytest.approx(2 * len(rates.distances) * 100 * 1.5e-3)


def test_a_relative_env_path_is_the_sweep_files_folders(tmp_path, monkeypatch, capsys):
    """Issue 53 point 6: a relative env path resolved against the working folder, so the sweep.toml a sweep
    writes could not be rerun from elsewhere. Now it is the file's folder's, and the text names it absolutely."""
    from delvjax.envs._presets import preset_dict
    from delvjax.sweeps import read_sweep
    from delvjax.sweeps._run import _envs

    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "mine.json").write_text(json.dumps({**preset_dict("env2"), "name": "mine"}))
    (tmp_path / "a" / "s.toml").write_text("[axes]\nenv = ['mine.json', 'env1']\nmethod = 'alv'\n")
    monkeypatch.chdir(tmp_path)  # not the file's folder
    spec = read_sweep("a/s.toml")
    assert spec.axes["env"] == ["mine.json", "env1"]  # the labels as written
    assert spec.env_files == {"mine.json": str((tmp_path / "a" / "mine.json").resolve())}
    assert _envs(spec)["mine.json"].name == "mine"
    again = parse_sweep(spec.text)  # the text a sweep writes as sweep.toml, read from anywhere
    assert again.axes["env"] == [str((tmp_path / "a" / "mine.json").resolve()), "env1"]
    (tmp_path / "b.json").write_text(json.dumps(preset_dict("env3")))
    (tmp_path / "a" / "t.toml").write_text("[axes]\nenv = ['b.json']\n")
    assert read_sweep("a/t.toml").env_files == {"b.json": str((tmp_path / "b.json").resolve())}  # the old reading
    assert "not in the sweep file's folder" in capsys.readouterr().err


def test_a_rates_band_over_seeds_stays_between_0_and_100():
    """Issue 53 point 2: plot-sweep's Student-t band over three seeds of 0, 0 and 30 % went below 0 %."""
    import xarray as xr

    from delvjax.plots._sweep import sweep_figure

    values = np.array([[0.0, 0.0, 30.0], [50.0, 55.0, 60.0]])
    ds = xr.Dataset(
        {"gt45_pct": (("d", "seed"), values, {"units": "percent"})},
        coords={"d": ("d", [20.0, 50.0], {"units": "cm"}), "seed": [0, 1, 2]},
    )
    _, rows = sweep_figure(ds, "d", None, "gt45_pct")
    assert rows[0]["ci95_lo"] == 0.0 and rows[0]["interval"].endswith("clipped to 0-100)")
    assert rows[1]["ci95_lo"] > 40  # an interval inside 0-100 is as it was
