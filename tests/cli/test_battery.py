"""The hostile battery (issue 53): inputs a new user or a hostile one may give, over every command and
file format (environment JSON, sweep TOML, image folders, study folders, flags). Each case is refused
in one line naming the field, before any work and without leaving a file behind, or handled correctly
(docs/reliability.md "Which inputs the battery covers")."""

from __future__ import annotations

import json
import re
import shutil
import time
from pathlib import Path

import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.envs._presets import preset_dict
from delvjax.images._disk import ENTRIES
from delvjax.options import _limits as limits


def shifted(by: float) -> dict:
    """env1 with every coordinate moved by `by` cm along x and y."""
    d = preset_dict("env1")
    d["arena"] = [v + by for v in d["arena"]]
    d["home"] = [v + by for v in d["home"]]
    d["landmarks"] = [{"x": lm["x"] + by, "y": lm["y"] + by, "r": lm["r"]} for lm in d["landmarks"]]
    return d


def grid_of(n: int) -> dict:
    """n x n small landmarks 100 cm apart in a square arena, home between them."""
    lms = [{"x": 50.0 + 100 * i, "y": 50.0 + 100 * j, "r": 1.0} for i in range(n) for j in range(n)]
    return {"arena": [0, 0, 100 * n, 100 * n], "home": [50 * n, 50 * n], "landmarks": lms}


ENV1 = preset_dict("env1")
SWEEP = '[sweep]\nkind = "vector-map"\n[axes]\nspacing = [200]\n'
# (id, files to write, argv with {t} for the folder, regex the one error line must match after "error: ")
REFUSED = [
    ("env shifted 1e6 cm", {"e.json": shifted(1e6)}, ["vector-map", "{t}/e.json"], r"arena\[0\]: .*float32"),
    ("env shifted 1e8 cm", {"e.json": shifted(1e8)}, ["catchment", "{t}/e.json"], r"arena\[0\]: .*float32"),
    ("env shifted 1e10 cm", {"e.json": shifted(1e10)}, ["catchment", "{t}/e.json"], r"arena\[0\]: .*too far"),
    ("10,000 landmarks", {"e.json": grid_of(100)}, ["vector-map", "{t}/e.json", "--spacing", "400"], r"landmarks: "),
    (
        "warping hypotheses product",
        {},
        ["vector-map", "env1", "--method", "warping", "--n-alpha", "3600", "--n-rho", "1000"],
        r"settings: .*GiB.*n_alpha = 3600, n_rho = 1000",
    ),
    ("env NaN", {"e.json": "NAN"}, ["vector-map", "{t}/e.json"], r"landmarks\[0\]\.x: must be finite"),
    ("env top-level list", {"e.json": [ENV1]}, ["vector-map", "{t}/e.json"], r"environment: "),
    ("env no landmarks", {"e.json": {**ENV1, "landmarks": []}}, ["vector-map", "{t}/e.json"], r"landmarks: "),
    ("env home as text", {"e.json": {**ENV1, "home": ["500", 500]}}, ["vector-map", "{t}/e.json"], r"home\[0\]: "),
    ("env radius true", {"e.json": "BOOL"}, ["catchment", "{t}/e.json"], r"landmarks\[0\]\.r: "),
    ("env overlap", {"e.json": "TWIN"}, ["vector-map", "{t}/e.json"], r"landmarks\[1\]: .*overlaps landmarks\[0\]"),
    ("env empty file", {"e.json": ""}, ["vector-map", "{t}/e.json"], r"env: .*JSON"),
    ("env home outside", {"e.json": {**ENV1, "home": [2000, 2000]}}, ["vector-map", "{t}/e.json"], r"^home: must lie"),
    ("env no arena", {"e.json": {"landmarks": [[100, 100, 10]]}}, ["vector-map", "{t}/e.json"], r"^arena: missing"),
    ("env is a folder", {"e.json/x": ""}, ["vector-map", "{t}/e.json"], r"env: "),
    ("spacing 0", {}, ["vector-map", "env1", "--spacing", "0"], r"spacing: "),
    ("spacing nan", {}, ["catchment", "env1", "--spacing", "nan"], r"spacing: "),
    ("d negative", {}, ["vector-map", "env1", "--d", "-5"], r"d: "),
    ("n_heading 0", {}, ["vector-map", "env1", "--n-heading", "0"], r"n.heading: "),
    ("hide beyond landmarks", {}, ["catchment", "env1", "--hide", "9"], r"hide: "),
    ("trials 0", {}, ["success-rate", "env1", "--trials", "0"], r"trials: "),
    ("distance negative", {}, ["success-rate", "env1", "--distances", "-10"], r"distances?: "),
    ("max steps huge", {}, ["catchment", "env1", "--max-steps", "1000000000"], r"max.steps: "),
    ("start outside", {}, ["trajectories", "env1", "--start", "5000", "5000"], r"start"),
    ("seed fraction", {}, ["vector-map", "env1", "--seed", "1.5"], r"seed: "),
    ("out suffix", {}, ["vector-map", "env1", "--out", "{t}/m.txt"], r"out: "),
    (
        "sweep axis typo",
        {"s.toml": SWEEP + "bering_noise_deg = [1]\n"},
        ["sweep", "{t}/s.toml", "--out", "{t}/sw"],
        r"did you mean",
    ),
    ("sweep bad TOML", {"s.toml": "[sweep\nkind = 1\n"}, ["sweep", "{t}/s.toml", "--out", "{t}/sw"], r"s\.toml|sweep"),
    ("sweep empty file", {"s.toml": "\n"}, ["sweep", "{t}/s.toml", "--out", "{t}/sw"], r"s\.toml: is empty"),
    ("sweep empty axis", {"s.toml": SWEEP + "d = []\n"}, ["sweep", "{t}/s.toml", "--out", "{t}/sw"], r"d"),
    (
        "sweep step 0",
        {"s.toml": SWEEP + "d = {start = 1, stop = 5, step = 0}\n"},
        ["sweep", "{t}/s.toml", "--out", "{t}/sw"],
        r"d",
    ),
    (
        "sweep env missing",
        {"s.toml": SWEEP + 'env = ["nowhere.json"]\n'},
        ["sweep", "{t}/s.toml", "--out", "{t}/sw"],
        r"env",
    ),
    ("plot-sweep no sweep", {"x/a.txt": "a"}, ["plot-sweep", "{t}/x", "--out", "{t}/p.png"], r"."),
    ("reproduce unknown study", {}, ["reproduce", "--only", "nosuchstudy", "--out", "{t}/r"], r"only: "),
    (
        "reproduce study typo",
        {},
        ["reproduce", "--only", "step_distanse", "--out", "{t}/r"],
        r"^--only: unknown study \(did you mean 'step_distance'\?\)",
    ),
    ("reproduce out is a file", {"r": "x"}, ["reproduce", "--only", "environments", "--out", "{t}/r"], r"out: "),
    ("layout landmarks 0", {}, ["optimise-layout", "--landmarks", "0", "--out", "{t}/o"], r"landmarks: "),
    ("sensitivity tau 0", {}, ["sensitivity", "env1", "--tau", "0", "--out", "{t}/s"], r"tau: "),
    ("traps near negative", {}, ["traps", "env1", "--near", "-1", "--out", "{t}/t"], r"near: "),
    ("images empty folder", {"db/x.txt": ""}, ["images", "import", "{t}/db", "--out", "{t}/bob"], r"."),
    ("radius below float32", {"e.json": "TINY"}, ["vector-map", "{t}/e.json"], r"landmarks\[0\]\.r: .*float32"),
    (
        "arena thinner than spacing",
        {"e.json": "THIN"},
        ["vector-map", "{t}/e.json"],
        r"spacing: .*smaller than the arena",
    ),
    ("clearance huge", {}, ["vector-map", "env1", "--clearance", "1e30"], r"clearance: "),
    ("d below resolution", {}, ["vector-map", "env1", "--d", "1e-30"], r"d: .*float32"),
    ("d beyond the arena", {}, ["catchment", "env1", "--d", "1e30"], r"d: .*diagonal"),
    ("home radius past the arena", {}, ["catchment", "env1", "--home-radius", "1e30"], r"home.radius: .*farthest"),
    ("n_pix 1", {}, ["vector-map", "env1", "--n-pix", "1"], r"^--n-pix: .*wider than every landmark.*got 1$"),
    ("n_pix 8", {}, ["catchment", "env1", "--n-pix", "8"], r"^--n-pix: .*use n_pix >= 16, got 8$"),
    ("scale 1e-40", {}, ["vector-map", "env1", "--scale", "1e-40", "--levels", "3"], r"^--scale: .*step.*got 1e-40$"),
    ("levels 10^6", {}, ["success-rate", "env1", "--levels", "1000000"], r"^--levels: .*step.*got 1000000$"),
    (
        "sweep n_pix 1",
        {"s.toml": SWEEP + "n_pix = [1]\n"},
        ["sweep", "{t}/s.toml", "--out", "{t}/sw"],
        r"n_pix: .*wider",
    ),
    (
        "sweep env shifted 1e6 cm",
        {"e.json": shifted(1e6), "s.toml": SWEEP + 'env = ["e.json"]\n'},
        ["sweep", "{t}/s.toml", "--out", "{t}/sw"],
        r"arena\[0\]: .*float32.*\(in .*e\.json\)",
    ),
]
SPECIAL = {
    "NAN": '{"arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": NaN, "y": 10, "r": 5}]}',
    "BOOL": '{"arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": 100, "y": 100, "r": true}]}',
    "TINY": '{"arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": 100, "y": 100, "r": 1e-50}]}',
    "THIN": '{"arena": [0, 0, 1000, 1], "home": [500, 0.5], "landmarks": [{"x": 499, "y": 0.5, "r": 0.1}]}',
    "TWIN": json.dumps({**ENV1, "landmarks": [ENV1["landmarks"][0]] * 2}),
}


def run(argv: list[str]) -> int:
    """The exit status of `delvjax argv` (argparse's own refusals exit instead of returning)."""
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def write(folder: Path, files: dict) -> set[Path]:
    for name, content in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        text = content if isinstance(content, str) else json.dumps(content)
        path.write_text(SPECIAL.get(text, text))
    return set(folder.rglob("*"))


@pytest.mark.parametrize("files, argv, says", [c[1:] for c in REFUSED], ids=[c[0] for c in REFUSED])
def test_a_hostile_input_is_refused_in_one_line_naming_it(tmp_path, capsys, monkeypatch, files, argv, says):
    monkeypatch.chdir(tmp_path)
    before = write(tmp_path, files)
    start = time.perf_counter()
    if argv[0] in ("vector-map", "catchment", "success-rate", "trajectories") and "--out" not in argv:
        argv = [*argv, "--out", "{t}/o.csv"]
    assert run([a.replace("{t}", str(tmp_path)) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err  # one line: no traceback, no usage block
    assert re.search(says, err[0].removeprefix("delvjax: error: ")), err[0]
    assert time.perf_counter() - start < 20  # refused before any work: no hang
    assert set(tmp_path.rglob("*")) == before  # no litter


def test_a_shifted_environment_within_float32s_resolution_gives_the_same_numbers():
    """Shifted by 1000 cm (float32 resolves 1.2e-4 cm there) env1's map is env1's, moved: within the
    tolerance the coordinates are kept, beyond it they are refused (above)."""
    kw = dict(method="delv-compass", grid=Grid(spacing=100.0, heading_deg=30.0))
    a = delvjax.vector_map("env1", **kw)
    b = delvjax.vector_map(delvjax.make_env(*_parts(shifted(1000.0))), **kw)
    assert np.allclose(np.asarray(b.points) - 1000.0, np.asarray(a.points))
    assert np.allclose(np.asarray(a.error_deg), np.asarray(b.error_deg), atol=0.05)


def _parts(d: dict) -> tuple:
    return [(lm["x"], lm["y"], lm["r"]) for lm in d["landmarks"]], d["home"], d["arena"]


def test_the_far_coordinates_of_the_api_name_the_field_too():
    with pytest.raises(InputError, match=r"home\[0\].*float32"):
        delvjax.make_env([(10.0, 10.0, 1.0)], home=(2e5, 500.0), arena=(0.0, 0.0, 1000.0, 1000.0))


def test_ten_thousand_landmarks_are_checked_in_seconds_not_minutes():
    start = time.perf_counter()
    with pytest.raises(InputError, match="landmarks"):
        delvjax.vector_map(delvjax.make_env(*_parts(grid_of(100))), grid=Grid(spacing=400.0))
    assert time.perf_counter() - start < 15  # the overlap check took 17 s in Python loops


def test_the_default_runs_pass_the_memory_check(tmp_path, capsys):
    for method in ("delv", "warping", "alv"):
        assert (
            main(["vector-map", "env1", "--method", method, "--spacing", "200", "--out", str(tmp_path / "m.csv")]) == 0
        )
    capsys.readouterr()


def test_a_mutated_image_index_is_refused_without_litter(small_db, tmp_path, capsys):
    """A position that is not a number in a database's index: one line naming the file, nothing written."""
    db = Path(shutil.copytree(small_db, tmp_path / "db"))
    lines = (db / ENTRIES).read_text().splitlines()
    fields = lines[2].split(",")
    lines[2] = ",".join([fields[0], "nan", *fields[2:]])
    (db / ENTRIES).write_text("\n".join(lines) + "\n")
    assert main(["images", "import", str(db), "--out", str(tmp_path / "bob")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ENTRIES in err[0], err
    assert not (tmp_path / "bob").exists()


def test_an_image_databases_hypothesis_tables_are_bounded_before_they_are_built(
    small_db, tmp_path, capsys, monkeypatch
):
    """Warping's tables on a database's images (n_alpha x n_rho x width, 2.5 GB here) are checked in the
    setup every command shares, against the memory available (1 GiB here): one line, no output."""
    monkeypatch.setattr(limits, "available_bytes", lambda: 2**30)
    argv = ["vector-map", "--images", str(small_db), "--method", "warping", "--n-alpha", "3600", "--n-rho", "300"]
    assert run([*argv, "--out", str(tmp_path / "m.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()  # "reading ..." (the width comes from the index), then:
    assert "n_alpha = 3600, n_rho = 300" in err[-1] and not any("Traceback" in e for e in err), err
    assert not list(tmp_path.iterdir())


@pytest.fixture(scope="module")
def finished_sweep(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("sweep")
    (folder / "s.toml").write_text(SWEEP.replace("spacing = [200]", "spacing = [200]\nd = [10, 20]"))
    assert run(["sweep", str(folder / "s.toml"), "--out", str(folder / "out")]) == 0
    return folder / "out"


@pytest.mark.parametrize(
    "extra, says",
    [
        (["--x", "d", "--metric", "gt45"], r"metric: .*gt45_pct"),
        (["--x", "nope"], r"x: .*axes: d"),
        (["--x", "d", "--y", "d"], r"y: must differ"),
        (["--x", "d", "--out", "{t}/p.txt"], r"out: must end in"),
        (["--x", "d", "--sweep-nc-cut"], r"sweep\.nc that cannot be read"),
    ],
    ids=["metric typo", "axis typo", "y is x", "figure suffix", "truncated sweep.nc"],
)
def test_plot_sweep_refuses_in_one_line(finished_sweep, tmp_path, capsys, extra, says):
    folder = Path(shutil.copytree(finished_sweep, tmp_path / "sw"))
    if "--sweep-nc-cut" in extra:
        extra = extra[:-1]
        (folder / "sweep.nc").write_bytes((finished_sweep / "sweep.nc").read_bytes()[:100])
    before = set(tmp_path.rglob("*"))
    argv = ["plot-sweep", str(folder), *extra] + ([] if "--out" in extra else ["--out", "{t}/p.png"])
    assert run([a.replace("{t}", str(tmp_path)) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and re.search(says, err[0]), err
    assert set(tmp_path.rglob("*")) == before


def test_a_ring_too_coarse_and_a_step_below_resolution_are_refused_by_the_api_too():
    """The checks sit in the setup every command and the Python API share (issue 53: both ran, every point
    invalid, with a hint about landmarks); the smallest accepted values run."""
    with pytest.raises(InputError, match=r"n_pix: .*use n_pix >= 16"):
        delvjax.vector_map("env1", n_pix=15, grid=Grid(spacing=400.0))
    with pytest.raises(InputError, match=r"scale: .*scale >= levels x 0.01 cm = 0.03 cm"):
        delvjax.catchment("env1", levels=3, scale=0.029, grid=Grid(spacing=400.0))
    vm = delvjax.vector_map("env1", n_pix=16, levels=3, scale=0.03, grid=Grid(spacing=400.0))
    assert np.asarray(vm.included).any()


def test_an_image_summary_records_the_settings_that_ran(small_db, tmp_path, capsys):
    """Newcomer pass (issue 53 point 3): an image database's summary recorded d = 50 and spacing = 25 (the
    scene defaults, which the database replaces: its unit move ran) and `background` as its index 0."""
    out = tmp_path / "s.json"
    assert main(["vector-map", "--images", str(small_db), "--method", "delv", "--summary", str(out)]) == 0
    s = json.loads(out.read_text())
    settings = s["command_settings"]
    assert settings["spacing"] == s["spacing_cm"] and not {"d", "n_pix", "background", "clearance"} & set(settings)
    assert main(["vector-map", "env1", "--spacing", "400", "--summary", str(out)]) == 0
    assert json.loads(out.read_text())["command_settings"]["background"] == "distant"
    capsys.readouterr()


@pytest.mark.parametrize("extra", [["--x", "seed"], ["--x", "d", "--y", "seed"], ["--x", "method"]])
def test_plot_sweep_draws_the_seeds_along_an_axis(tmp_path, capsys, extra):
    """Newcomer pass: `plot-sweep --x seed` (or --y seed) ended in a traceback ("axes don't match array"):
    the seeds, replicates elsewhere, are drawn one value each, without an interval; `--x method` draws the
    dimension `homing_method` (docs/sweeps.md)."""
    from delvjax.sweeps._kinds import sum_names
    from delvjax.sweeps._results import dataset, save_sweep
    from delvjax.sweeps._spec import parse_sweep

    spec = parse_sweep('[axes]\nmethod = ["delv", "alv"]\nd = [10, 20]\nseed = [0, 1, 2]\nspacing = [200]\n')
    sums = {k: np.arange(1.0, spec.n_cells + 1) for k in sum_names(spec.kind)}
    save_sweep(dataset(spec, sums, 0), tmp_path / "sw")
    assert main(["plot-sweep", str(tmp_path / "sw"), *extra, "--out", str(tmp_path / "p.png")]) == 0
    rows = (tmp_path / "p.csv").read_text().splitlines()
    assert (tmp_path / "p.png").is_file() and rows[0].split(",")[:2] == [
        "panel",
        "method" if len(extra) == 2 else "seed",
    ]
    if extra == ["--x", "seed"]:
        assert len(rows) == 1 + 2 * 2 * 3 and all(r.endswith("none: one seed per point") for r in rows[1:])
    capsys.readouterr()
