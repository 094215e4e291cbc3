"""Output files (issue 10, item 1): every output location is checked before any work, and the outputs of
one command are written as a unit. A location that cannot be written, found before or during the
writes, is exit 2 with one line naming the option and the path, and no file is left behind."""

from __future__ import annotations

import json
import os
import tempfile

import pytest

from delvjax.cli import _main as cli
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.outputs import _files as io
from delvjax.outputs._files import output_set


def _permissions_ignored() -> bool:
    """Root (CAP_DAC_OVERRIDE) ignores permission bits: a read-only folder is still writable for it."""
    with tempfile.TemporaryDirectory() as d:
        os.chmod(d, 0o555)
        try:
            return os.access(d, os.W_OK)
        finally:
            os.chmod(d, 0o755)


ROOT = os.geteuid() == 0 and _permissions_ignored()
COMMANDS = {  # the fastest settings; a bad output is refused before any of them runs
    "vector-map": ["vector-map", "env1", "--spacing", "200"],
    "catchment": ["catchment", "env1", "--spacing", "200"],
    "success-rate": ["success-rate", "env1", "--trials", "2", "--distances", "100", "--max-steps", "10"],
    "trajectories": ["trajectories", "env1", "--start", "400", "400", "--max-steps", "10"],
}


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err  # one line: no progress line, no traceback
    return err[0]


def files_under(folder) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def bad_plot_folder(tmp_path, kind: str, monkeypatch):
    """A folder --plot cannot be written into: under a regular file, read-only, or refused by os.access."""
    if kind == "under_file":
        (tmp_path / "blocker").write_text("a file")
        return tmp_path / "blocker"
    folder = tmp_path / "ro"
    folder.mkdir()
    if kind == "read_only":
        if ROOT:
            pytest.skip("root ignores a read-only folder (see the under_file and access cases)")
        folder.chmod(0o555)
    else:
        real = os.access
        monkeypatch.setattr(io.os, "access", lambda p, mode: False if str(p) == str(folder) else real(p, mode))
    return folder


@pytest.mark.parametrize("kind", ["under_file", "read_only", "access"])
@pytest.mark.parametrize("command", list(COMMANDS))
def test_an_unwritable_plot_folder_is_refused_before_any_work(tmp_path, capsys, monkeypatch, command, kind):
    folder = bad_plot_folder(tmp_path, kind, monkeypatch)
    before = files_under(tmp_path)
    plot = folder / "p.png"
    argv = COMMANDS[command] + [
        "--out",
        str(tmp_path / "r.csv"),
        "--summary",
        str(tmp_path / "s.json"),
        "--plot",
        str(plot),
    ]
    try:
        assert main(argv) == 2
    finally:
        folder.chmod(0o755) if folder.is_dir() else None
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --plot:") and str(plot) in line
    assert files_under(tmp_path) == before


def test_an_existing_output_that_cannot_be_written_is_refused(tmp_path, capsys, monkeypatch):
    out = tmp_path / "r.csv"
    out.write_text("old")
    real = os.access
    monkeypatch.setattr(io.os, "access", lambda p, mode: False if str(p) == str(out) else real(p, mode))
    assert main(COMMANDS["vector-map"] + ["--out", str(out)]) == 2
    assert error_line(capsys) == f"delvjax: error: --out: exists and is not writable, got {str(out)!r}"
    assert out.read_text() == "old"


def test_two_options_naming_one_file_are_refused(tmp_path, capsys):
    out = tmp_path / "r.csv"
    argv = COMMANDS["success-rate"] + ["--out", str(out), "--trials-out", str(tmp_path / "." / "r.csv")]
    assert main(argv) == 2
    assert "--trials-out: names the same file as --out" in error_line(capsys)
    assert files_under(tmp_path) == []


def test_an_output_over_the_environment_file_is_refused(tmp_path, capsys):
    env = tmp_path / "env.json"
    env.write_text(
        json.dumps(
            {"name": "e", "arena": [0, 0, 1000, 1000], "home": [500, 500], "landmarks": [{"x": 200, "y": 200, "r": 20}]}
        )
    )
    text = env.read_text()
    assert main(["vector-map", str(env), "--summary", str(env)]) == 2
    assert "--summary: is the input env" in error_line(capsys)
    assert env.read_text() == text and files_under(tmp_path) == ["env.json"]


def test_a_figure_that_fails_to_render_leaves_no_output(tmp_path, capsys, monkeypatch):
    """Neither the CSV nor the JSON, nor the folders made for them; an older file keeps its content."""
    from matplotlib.figure import Figure

    def broken(*args, **kwargs):
        raise RuntimeError("renderer failed\nsecond line")

    monkeypatch.setattr(Figure, "savefig", broken)
    (tmp_path / "old.json").write_text("old")
    plot = tmp_path / "new" / "deeper" / "p.png"
    argv = COMMANDS["vector-map"] + [
        "--out",
        str(tmp_path / "new" / "r.csv"),
        "--summary",
        str(tmp_path / "old.json"),
        "--plot",
        str(plot),
    ]
    assert main(argv) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]  # after the progress lines
    assert (
        line
        == f"delvjax: error: --plot: could not be written (RuntimeError: renderer failed second line), got {str(plot)!r}"
    )
    assert files_under(tmp_path) == ["old.json"] and (tmp_path / "old.json").read_text() == "old"


def test_a_failed_figure_leaves_none_of_four_outputs(tmp_path, capsys, monkeypatch):
    from matplotlib.figure import Figure

    monkeypatch.setattr(Figure, "savefig", lambda *a, **k: (_ for _ in ()).throw(ValueError("too large")))
    names = {"--out": "r.csv", "--trials-out": "t.csv", "--summary": "s.json", "--plot": "p.svg"}
    argv = COMMANDS["success-rate"] + [a for flag, name in names.items() for a in (flag, str(tmp_path / name))]
    assert main(argv) == 2
    assert "--plot: could not be written (ValueError: too large)" in capsys.readouterr().err
    assert files_under(tmp_path) == []


@pytest.mark.parametrize("change", ["file", "read_only"])
def test_a_folder_that_becomes_unwritable_after_the_check_is_one_line(tmp_path, capsys, monkeypatch, change):
    """The plot's folder turns into a file (or read-only) while the map is computed."""
    if change == "read_only" and ROOT:
        pytest.skip("root ignores a read-only folder")
    folder = tmp_path / "figs"
    if change == "read_only":
        folder.mkdir()
    columns = cli.vector_map_columns

    def meanwhile(vm):
        folder.write_text("now a file") if change == "file" else folder.chmod(0o555)
        return columns(vm)

    monkeypatch.setattr(cli, "vector_map_columns", meanwhile)
    plot = folder / "p.png"
    argv = COMMANDS["vector-map"] + ["--out", str(tmp_path / "r.csv"), "--plot", str(plot)]
    try:
        assert main(argv) == 2
    finally:
        folder.chmod(0o755)
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith("delvjax: error: --plot: could not be written (") and line.endswith(repr(str(plot)))
    assert files_under(tmp_path) == ["figs"]


def test_output_set_writes_all_or_nothing(tmp_path, monkeypatch):
    """A rename failing at the very end removes the targets already renamed, every temporary file and
    the folders made; without a failure every file is there with ordinary permissions."""
    real = os.replace

    def second_fails(src, dst):
        if str(dst).endswith(".json"):
            raise OSError(28, "No space left on device")
        real(src, dst)

    monkeypatch.setattr(io.os, "replace", second_fails)
    with pytest.raises(InputError, match=r"^--summary: could not be written \(No space left on device\)"):
        with output_set() as files:
            files.csv(tmp_path / "a" / "r.csv", {"x": [1, 2]}, "--out")
            files.json(tmp_path / "a" / "b" / "s.json", {"n": float("nan")}, "--summary")
    assert files_under(tmp_path) == []
    monkeypatch.undo()
    with output_set() as files:
        files.rows_csv(tmp_path / "a" / "r.csv", [{"x": 1}, {"y": True}], "--out")
        files.json(tmp_path / "s.json", {"n": float("nan")}, "--summary")
    assert files_under(tmp_path) == ["a", "a/r.csv", "s.json"]
    assert (tmp_path / "a" / "r.csv").read_text().splitlines() == ["x,y", "1,", ",1"]
    assert json.loads((tmp_path / "s.json").read_text()) == {"n": None}
    umask = os.umask(0)
    os.umask(umask)
    assert (tmp_path / "s.json").stat().st_mode & 0o777 == 0o666 & ~umask


def test_output_set_cleans_up_when_the_block_raises(tmp_path):
    with pytest.raises(KeyError):
        with output_set() as files:
            files.csv(tmp_path / "new" / "r.csv", {"x": [1]}, "--out")
            raise KeyError("interrupted")
    assert files_under(tmp_path) == []


def test_a_target_of_the_longest_legal_name_is_written(tmp_path):
    """The temporary beside it has a short name of its own (a 249-character name failed before)."""
    target = tmp_path / ("a" * 250 + ".json")
    io.write_json(target, {"x": 1})
    assert json.loads(target.read_text()) == {"x": 1} and files_under(tmp_path) == [target.name]


def test_stale_temporaries_of_dead_processes_are_removed_and_live_ones_kept(tmp_path):
    import subprocess
    import sys

    from delvjax.outputs import _temporary

    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    pid = int(dead.stdout)
    stale = tmp_path / f".delvjax-{pid}-0123456789ab.part"
    stale.write_text("half a file")
    (tmp_path / f".delvjax-{pid}-0123456789ac.part").mkdir()  # half a database
    live = tmp_path / f".delvjax-{os.getpid()}-0123456789ab.part"
    live.write_text("being written")
    other = tmp_path / ".hidden"
    other.write_text("not ours")
    removed = _temporary.remove_stale(tmp_path)
    assert len(removed) == 2 and sorted(files_under(tmp_path)) == sorted([live.name, other.name])
