"""The command line: outputs, and bad input -> one-line error naming field and value, exit 2, no file."""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
import sys

import pytest

from delvjax.cli._main import main

GOOD = {
    "name": "t",
    "arena": [0, 0, 1000, 1000],
    "home": [500, 500],
    "landmarks": [{"x": 300, "y": 600, "r": 30}, {"x": 700, "y": 650, "r": 20}, {"x": 600, "y": 300, "r": 25}],
}


def test_vector_map_writes_csv_plot_and_summary(tmp_path):
    out, plot, summary = tmp_path / "m.csv", tmp_path / "m.png", tmp_path / "m.json"
    env = tmp_path / "env.json"
    env.write_text(json.dumps(GOOD))
    rc = main(
        [
            "vector-map",
            str(env),
            "--method",
            "delv",
            "--spacing",
            "100",
            "--out",
            str(out),
            "--plot",
            str(plot),
            "--summary",
            str(summary),
            "--classes",
        ]
    )
    assert rc == 0
    rows = list(csv.DictReader(out.open()))
    assert set("x,y,heading_deg,direction_deg,error_deg,valid".split(",")) <= set(rows[0])
    assert len(rows) == json.loads(summary.read_text())["points"] >= 90
    assert all(0.0 <= float(r["error_deg"]) <= 180.0 for r in rows)
    assert all((r["direction_deg"] == "nan") == (r["valid"] == "0") for r in rows)
    assert plot.stat().st_size > 10_000


def test_console_script_end_to_end(tmp_path):
    exe = shutil.which("delvjax") or f"{sys.executable} -m delvjax.cli"
    out = tmp_path / "sub" / "alv.csv"
    res = subprocess.run(
        f"{exe} vector-map env3 --method alv --spacing 100 --heading-deg 90 --out {out}",
        shell=True,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr
    rows = list(csv.DictReader(out.open()))
    assert all(abs(float(r["heading_deg"]) - 90.0) < 1e-3 for r in rows)
    assert "envs" in subprocess.run(f"{exe} --help", shell=True, capture_output=True, text=True).stdout


def _env_file(tmp_path, text):
    p = tmp_path / "env.json"
    p.write_text(text if isinstance(text, str) else json.dumps(text))
    return str(p)


def _mut(path, value):
    spec = json.loads(json.dumps(GOOD))
    obj = spec
    for k in path[:-1]:
        obj = obj[k]
    if value is KeyError:
        del obj[path[-1]]
    else:
        obj[path[-1]] = value
    return spec


BAD_ENVS = [
    ("malformed", '{"arena": [0, 0, 1000, 1000], "home": [500', "env"),
    ("missing landmarks", _mut(["landmarks"], KeyError), "landmarks"),
    ("missing r", _mut(["landmarks", 0, "r"], KeyError), "landmarks[0].r"),
    ("non-numeric", _mut(["landmarks", 1, "x"], "far"), "landmarks[1].x"),
    (
        "nan",
        '{"arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": NaN, "y": 1, "r": 1}]}',
        "landmarks[0].x",
    ),
    ("zero radius", _mut(["landmarks", 2, "r"], 0), "landmarks[2].r"),
    ("negative radius", _mut(["landmarks", 2, "r"], -3), "landmarks[2].r"),
    ("overlap", _mut(["landmarks", 1], {"x": 310, "y": 600, "r": 20}), "landmarks[1]"),
    ("covers home", _mut(["landmarks", 1], {"x": 510, "y": 500, "r": 20}), "landmarks[1]"),
    ("home outside", _mut(["home"], [1200, 500]), "home"),
    ("inverted arena", _mut(["arena"], [1000, 1000, 0, 0]), "arena"),
]


@pytest.mark.parametrize("label, spec, field", BAD_ENVS, ids=[b[0] for b in BAD_ENVS])
def test_bad_environment_file(tmp_path, capsys, label, spec, field):
    out = tmp_path / "o.csv"
    rc = main(["vector-map", _env_file(tmp_path, spec), "--out", str(out), "--plot", str(tmp_path / "o.png")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and field in err, err
    assert not out.exists() and not (tmp_path / "o.png").exists()


BAD_FLAGS = [
    (["--d", "0"], "d"),
    (["--d", "-5"], "d"),
    (["--d", "nan"], "d"),
    (["--levels", "0"], "levels"),
    (["--spacing", "-25"], "spacing"),
    (["--method", "magic"], "method"),
    (["--background", "sky"], "background"),
    (["--bearing-noise-deg", "-1"], "bearing_noise_deg"),
    (["--hide", "7"], "hide"),
]


@pytest.mark.parametrize("flags, field", BAD_FLAGS, ids=[" ".join(f) for f, _ in BAD_FLAGS])
def test_bad_flags(tmp_path, capsys, flags, field):
    out = tmp_path / "o.csv"
    rc = main(["vector-map", "env1", "--out", str(out), *flags])
    err = capsys.readouterr().err.strip()
    named = field in err or f"--{field.replace('_', '-')}" in err  # the API's keyword or, from the CLI, the flag
    assert rc == 2 and len(err.splitlines()) == 1 and named and flags[-1] in err, err
    assert not out.exists()


def test_unknown_preset_and_bad_output_path(tmp_path, capsys):
    assert main(["vector-map", "env9", "--out", str(tmp_path / "o.csv")]) == 2
    assert "env9" in capsys.readouterr().err
    assert main(["vector-map", "env1", "--out", str(tmp_path / "o.txt")]) == 2
    assert "--out" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_progress_counts_are_integers(capsys):
    from delvjax.cli._args import ProgressBar

    with ProgressBar("cell", 0) as bar:
        bar(3, 18)
    err = capsys.readouterr().err
    assert "3/18" in err and "3.00" not in err and "18.0" not in err


def test_the_bar_covers_the_whole_run_and_says_what_runs(capsys):
    from delvjax.cli._args import ProgressBar

    with ProgressBar("pt", 0) as bar:
        bar.phase("checking 250000 cells")  # before start: nothing (bad input must stay one line)
        assert capsys.readouterr().err == ""
        bar.start(250_000, "compiling program 1 of 2")  # shown before the first chunk returns
        bar(65_536, 250_000)
        bar.phase("compiling program 2 of 2")
        bar(184_464, 250_000)
    err = capsys.readouterr().err
    assert "compiling program 1 of 2" in err and "running" in err and "compiling program 2 of 2" in err
    assert "65536/250000" in err and "250000/250000" in err and "250k" not in err


def test_a_run_of_one_chunk_prints_its_phases_as_lines(capsys):
    from delvjax.cli._args import ProgressBar

    with ProgressBar("pt", 1000) as bar:
        bar.start(400, "compiling program 1 of 1 (cached for later runs)")
        bar(400, 400)
    assert capsys.readouterr().err == "[delvjax] compiling program 1 of 1 (cached for later runs) ...\n"


def test_a_catchment_csv_read_in_pandas_gives_the_catchment_and_the_summary_its_hidden_count(tmp_path):
    """Issue 53: near-wall rows had success = 0 and no column said which rows count, so `df.success.mean()` read
    70.5 % for a 98.46 % catchment; the summary said occlude 0 beside hidden [3]."""
    import pandas as pd

    out, summary = tmp_path / "c.csv", tmp_path / "c.json"
    args = ["catchment", "env1", "--method", "alv", "--hide", "3", "--spacing", "80", "--out", str(out)]
    assert main([*args, "--summary", str(summary)]) == 0
    df, s = pd.read_csv(out), json.loads(summary.read_text())
    assert (~df.counted.astype(bool)).sum() == 23 and df.success[~df.counted.astype(bool)].isna().all()
    assert 100.0 * df.success.mean() == pytest.approx(s["catchment_pct"]["mean"], abs=1e-6)
    assert s["occlude"] == 1 and s["per_mask"][0]["hidden"] == [3]


def test_a_summary_records_every_setting_and_the_figure_the_changed_ones(tmp_path, capsys):
    """Issue 53 point 3: the summary JSON had no d, spacing, seed or noise, and figure titles omitted the noise."""
    from delvjax.cli._args import changed_settings, command_settings
    from delvjax.cli._main import build_parser, command_defaults

    argv = ["catchment", "env1", "--method", "alv", "--spacing", "200", "--bearing-noise-deg", "2"]
    summary = tmp_path / "s.json"
    assert main(argv + ["--summary", str(summary)]) == 0
    settings = json.loads(summary.read_text())["command_settings"]
    assert settings["bearing_noise_deg"] == 2.0 and settings["spacing"] == 200.0 and settings["seed"] == 0
    assert settings["d"] == 50.0 and settings["home_radius"] == 50.0  # defaults are recorded too
    assert "levels" not in settings and "n_psi" not in settings  # settings ALV does not have
    parser = build_parser()
    args = parser.parse_args(argv + ["--plot", "x.png"])
    args.defaults = command_defaults(parser, args)
    assert changed_settings(args) == "bearing_noise_deg = 2.0, spacing = 200.0"
    assert command_settings(args)["method"] == "alv"
