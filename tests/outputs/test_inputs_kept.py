"""No output overwrites an input (docs/reliability.md): an output path that is an input file, or lies in an
input folder (an image database, a sweep folder's files), symlinks followed, is refused before any work
with one line naming both options; the input keeps its bytes."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from delvjax.cli._main import main
from delvjax.images._disk import ENTRIES
from tests.cases.faults import fake_sweep
from tests.outputs.test_files import error_line


def snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def write_env(path: Path) -> Path:
    env = {"name": "e", "arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": 200, "y": 200, "r": 20}]}
    path.write_text(json.dumps(env))
    return path


@pytest.mark.parametrize("option", ["--out", "--plot", "--summary", "link"])
def test_an_output_inside_the_image_database_is_refused(small_db, tmp_path, capsys, option):
    before = snapshot(small_db)
    image = sorted(p.name for p in small_db.glob("*.png"))[0]
    target = {
        "--out": small_db / ENTRIES,  # the database's index
        "--plot": small_db / image,  # one of its images
        "--summary": small_db / "summary.json",  # a new file inside it
        "link": tmp_path / "link" / "x.csv",  # through a symlink to the database
    }[option]
    if option == "link":
        os.symlink(small_db, tmp_path / "link")
    flag = "--out" if option == "link" else option
    assert main(["vector-map", "--images", str(small_db), flag, str(target)]) == 2
    line = error_line(capsys)
    assert line.startswith(f"delvjax: error: {flag}:") and "the input --images" in line
    assert snapshot(small_db) == before


def test_import_into_its_own_source_is_refused(small_db, capsys):
    before = snapshot(small_db)
    assert main(["images", "import", str(small_db), "--out", str(small_db / "copy")]) == 2
    assert "--out: lies inside the input src" in error_line(capsys)
    assert snapshot(small_db) == before


@pytest.mark.parametrize("out", ["sweep.png", "sweep.svg"])
def test_plot_sweep_never_writes_over_the_sweep_files(tmp_path, capsys, out):
    """--out DIR/sweep.png would write its numbers to DIR/sweep.csv, the sweep's own table."""
    folder = fake_sweep(tmp_path / "s")
    before = snapshot(folder)
    assert main(["plot-sweep", str(folder), "--x", "d", "--out", str(folder / out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --out:") and "the input dir" in line
    assert snapshot(folder) == before


def test_plot_sweep_beside_the_sweep_files_still_works(tmp_path, capsys):
    folder = fake_sweep(tmp_path / "s")
    assert main(["plot-sweep", str(folder), "--x", "d"]) == 0  # default: DIR/mean_error_deg.png and .csv
    assert (folder / "mean_error_deg.png").is_file() and (folder / "sweep.csv").read_text().startswith("d,seed,")


@pytest.mark.parametrize(
    "command, name",
    [(["traps"], "traps.json"), (["optimise-layout"], "optimised_env.json"), (["sensitivity"], "landmarks.csv")],
)
def test_a_folder_command_never_writes_over_its_environment_file(tmp_path, capsys, command, name):
    env = write_env(tmp_path / name)
    text = env.read_text()
    assert main([*command, str(env), "--out", str(tmp_path)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --out:") and "is the input env" in line
    assert env.read_text() == text


def test_a_sweep_never_writes_its_table_over_its_own_file(tmp_path, capsys):
    file = tmp_path / "sweep.csv"  # a sweep file given the name of the table the sweep writes
    file.write_text("[axes]\nd = [50]\n")
    assert main(["sweep", str(file), "--out", str(tmp_path)]) == 2
    assert "the input file" in error_line(capsys)
    assert file.read_text() == "[axes]\nd = [50]\n"
