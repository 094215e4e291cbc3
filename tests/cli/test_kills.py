"""A command killed at any instant (docs/reliability.md): `sweep`, `reproduce` and `images render-db` are
killed by SIGKILL or SIGTERM inside their file writers (a file half written under its temporary name, or
whole but not yet renamed, or between chunks); SIGTERM leaves no temporary and exits 143 with one line;
the next run removes what SIGKILL left, completes, and writes the bytes of an uninterrupted run."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from delvjax.cli._main import main
from tests.cases.faults import contents, run_killed, temporaries
from tests.cases.images_io import SMALL

SWEEP = "[axes]\nd = [30, 60]\nseed = [0, 1]\nspacing = [150]\n"  # the programs of sweeps/test_sweeps.py's resume test
RENDER = ["images", "render-db", "robot", *SMALL, "--spacing", "40", "--chunk", "4"]


def check_killed(run, signal: str, folder: Path) -> None:
    if signal == "SIGKILL":
        assert run.returncode == -9, run.stderr[-2000:]
    else:
        assert run.returncode == 143, run.stderr[-2000:]
        assert run.stderr.strip().splitlines()[-1] == "delvjax: terminated: finished work is kept"
        assert temporaries(folder) == []  # SIGTERM removes its temporaries at once


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("sweep") / "s.toml"
    path.write_text(SWEEP)
    return path


@pytest.fixture(scope="module")
def uninterrupted(sweep_file) -> dict[str, bytes]:
    out = sweep_file.parent / "uninterrupted"
    assert main(["sweep", str(sweep_file), "--out", str(out)]) == 0
    return contents(out)


@pytest.mark.parametrize(
    "how, signal, n",
    [
        ("during", "SIGKILL", 1),  # the first chunk half written
        ("before-rename", "SIGKILL", 2),  # the second chunk whole, not renamed
        ("during", "SIGTERM", 4),  # sweep.csv, while the results are renamed into place
    ],
)
def test_a_killed_sweep_resumes_to_the_bytes_of_an_uninterrupted_one(
    sweep_file, uninterrupted, tmp_path, how, signal, n
):
    out = tmp_path / "out"
    run = run_killed(how, signal, n, ["sweep", str(sweep_file), "--out", str(out)], tmp_path)
    check_killed(run, signal, out)
    if signal == "SIGKILL":
        assert temporaries(out), "the kill left nothing to clean up: it came too late"
    assert main(["sweep", str(sweep_file), "--out", str(out)]) == 0
    assert temporaries(out) == [] and contents(out) == uninterrupted


def test_a_damaged_chunk_is_computed_again_with_a_warning(sweep_file, uninterrupted, tmp_path, capsys):
    out = tmp_path / "out"
    shutil.copytree(sweep_file.parent / "uninterrupted", out)
    (out / "sweep.nc").unlink()
    chunks = sorted((out / ".cells").glob("*.npz"))
    chunks[0].write_bytes(chunks[0].read_bytes()[:100])  # a copy cut short
    assert main(["sweep", str(sweep_file), "--out", str(out)]) == 0
    warnings = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("delvjax: warning:")]
    assert len(warnings) == 1 and chunks[0].name in warnings[0] and "computed again" in warnings[0]
    assert contents(out) == uninterrupted


def study_files(out: Path) -> dict:
    """The study's files, its record without the run's timing (which differs from run to run)."""
    files = contents(out / "environments")
    record = json.loads(files.pop("study.json"))
    return {**files, "study.json": {k: v for k, v in record.items() if "seconds" not in k}}


@pytest.mark.parametrize("how, signal", [("during", "SIGKILL"), ("before-rename", "SIGTERM")])
def test_a_killed_reproduce_completes_on_the_next_run(tmp_path, how, signal):
    argv = ["reproduce", "--only", "environments", "--workers", "1"]
    assert main([*argv, "--out", str(tmp_path / "ref")]) == 0
    out = tmp_path / "out"
    run = run_killed(how, signal, 2, [*argv, "--out", str(out)], tmp_path)
    check_killed(run, signal, out)
    assert main([*argv, "--out", str(out)]) == 0
    assert temporaries(out) == [] and study_files(out) == study_files(tmp_path / "ref")


@pytest.mark.parametrize("signal", ["SIGKILL", "SIGTERM"])
def test_a_killed_render_leaves_nothing_and_the_next_render_completes(tmp_path, signal):
    assert main([*RENDER, "--out", str(tmp_path / "ref" / "db")]) == 0
    out = tmp_path / "out" / "db"
    run = run_killed("chunk", signal, 1, [*RENDER, "--out", str(out)], tmp_path)
    check_killed(run, signal, out.parent)
    assert not out.exists()
    if signal == "SIGKILL":
        assert temporaries(out.parent), "the kill left no temporary folder: it came too late"
    assert main([*RENDER, "--out", str(out)]) == 0
    assert temporaries(out.parent) == [] and contents(out) == contents(tmp_path / "ref" / "db")


def test_a_full_disk_during_reproduce_is_one_line_and_leaves_no_temporary(tmp_path, capsys, monkeypatch):
    from delvjax.outputs import _files

    real = _files._publish

    def full(tmp, target):
        if target.name == "study.json":
            raise OSError(28, "No space left on device")
        return real(tmp, target)

    monkeypatch.setattr(_files, "_publish", full)
    out = tmp_path / "out"
    assert main(["reproduce", "--only", "environments", "--workers", "1", "--out", str(out)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("delvjax: error:")]
    assert len(err) == 1 and "No space left on device" in err[0]
    assert temporaries(out) == [] and not (out / "environments" / "study.json").exists()
    monkeypatch.setattr(_files, "_publish", real)
    assert main(["reproduce", "--only", "environments", "--workers", "1", "--out", str(out)]) == 0  # space again
