"""Reading and writing image databases as a demanding stranger would (docs/images.md §4): every reading
error exits 2 with one line naming the file and leaves nothing at --out; --out folders that are not
empty, not writable or not makeable; a render or import that fails midway; render-db's options."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from PIL import Image

from delvjax.cli._main import main
from delvjax.images import _writer as image_db
from delvjax.images._disk import ENTRIES, POSITIONS
from tests.cases.images_io import SMALL, entries, error_line, no_leftovers, read_csv, writer_argv

# --- reading errors: exit 2, one line naming the file, nothing at --out ----------------------------


def _break_missing(src: Path) -> list[str]:
    text = (src / POSITIONS).read_text().replace("p4.png", "ghost.png")
    (src / POSITIONS).write_text(text)
    return [str(src / "ghost.png"), "does not exist"]


def _break_garbage(src: Path) -> list[str]:
    (src / "p5.png").write_bytes(b"\x89PNG\r\n\x1a\n but then garbage" * 10)
    return [str(src / "p5.png"), "cannot be read"]


def _break_size(src: Path) -> list[str]:
    Image.new("RGB", (72, 13), (128, 128, 128)).save(src / "p6.png")
    return [str(src / "p6.png"), "72 x 13"]


def _break_number(src: Path) -> list[str]:
    lines = (src / POSITIONS).read_text().splitlines()
    f, x, y, h = lines[3].split(",")  # the CSV's row 4 (the header is row 1)
    lines[3] = ",".join([f, "eleven", y, h])
    (src / POSITIONS).write_text("\n".join(lines) + "\n")
    return [str(src / POSITIONS), "row 4", "eleven"]


def _break_no_csv(src: Path) -> list[str]:
    (src / POSITIONS).unlink()
    return [str(src), POSITIONS, ENTRIES]


def _break_outside(src: Path) -> list[str]:
    first = next(r["filename"] for r in read_csv(src / POSITIONS) if float(r["x"]) > 100 or float(r["y"]) > 100)
    return [str(src / first), "outside the arena"]


BREAKS = {
    "missing image": (_break_missing, []),
    "garbage png": (_break_garbage, []),
    "other size": (_break_size, []),
    "non-numeric": (_break_number, []),
    "no csv": (_break_no_csv, []),
    "outside arena": (_break_outside, ["--arena", "0", "0", "100", "100"]),
}


@pytest.mark.parametrize("command", ["import", "vector-map"])
@pytest.mark.parametrize("case", list(BREAKS))
def test_a_bad_plain_folder_exits_2_naming_the_file(plain9, tmp_path, capsys, command, case):
    src = tmp_path / "nine"
    shutil.copytree(plain9, src)
    breaker, extra = BREAKS[case]
    needed = breaker(src)
    out = tmp_path / ("out" if command == "import" else "m.csv")
    argv = (
        ["images", "import", str(src), "--out", str(out)]
        if command == "import"
        else ["vector-map", "--images", str(src), "--out", str(out)]
    )
    assert main(argv + extra) == 2
    line = error_line(capsys)
    assert all(n in line for n in needed), (needed, line)
    no_leftovers(out)


def test_a_bad_bob_database_names_the_file(small_db, tmp_path, capsys):
    src = tmp_path / "bob"
    shutil.copytree(small_db, src)
    rows = entries(src)
    (src / rows[30]["Filename"]).unlink()
    out = tmp_path / "out"
    assert main(["images", "import", str(src), "--out", str(out)]) == 2
    assert rows[30]["Filename"] in error_line(capsys)
    no_leftovers(out)
    lines = (src / ENTRIES).read_text().splitlines()
    lines[7] = lines[7].replace(", 2.70000000000000000e+02,", ", north,", 1)  # the heading of CSV row 8
    assert "north" in lines[7]
    (src / ENTRIES).write_text("\n".join(lines) + "\n")
    assert main(["vector-map", "--images", str(src), "--out", str(tmp_path / "m.csv")]) == 2
    line = error_line(capsys)
    assert ENTRIES in line and "row 8" in line and "north" in line, line
    assert not (tmp_path / "m.csv").exists()


@pytest.mark.parametrize("command", ["render-db", "import"])
def test_an_out_folder_that_is_not_empty_is_refused_and_left_alone(plain9, tmp_path, capsys, command):
    out = tmp_path / "db"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    argv = writer_argv(command, plain9)
    assert main(argv + ["--out", str(out)]) == 2
    line = error_line(capsys)
    assert "--out" in line and str(out) in line, line
    assert [p.name for p in out.iterdir()] == ["keep.txt"] and (out / "keep.txt").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["db"]


def test_an_empty_out_folder_is_accepted(small_db, tmp_path):
    out = tmp_path / "db"
    out.mkdir()
    assert main(["images", "import", str(small_db), "--out", str(out)]) == 0
    assert len(entries(out)) == 71 and sorted(p.name for p in tmp_path.iterdir()) == ["db"]


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes into any folder")
@pytest.mark.parametrize("command", ["render-db", "import"])
def test_an_out_folder_under_an_unwritable_folder_is_refused(plain9, tmp_path, capsys, command):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        out = locked / "db"
        argv = writer_argv(command, plain9)
        assert main(argv + ["--out", str(out)]) == 2
        assert "--out" in error_line(capsys)
        assert not list(locked.iterdir())
    finally:
        locked.chmod(0o700)


@pytest.mark.parametrize("where", ["under a file", "read-only file system"])
@pytest.mark.parametrize("command", ["render-db", "import"])
def test_an_out_folder_that_cannot_be_made_is_refused(plain9, tmp_path, capsys, command, where):
    """The same without permission bits (this also runs as root): a path under a file, or on /proc."""
    if where == "under a file":
        (tmp_path / "file").write_text("x")
        out = tmp_path / "file" / "db"
    else:
        if not Path("/proc/self").is_dir():
            pytest.skip("no /proc")
        out = Path("/proc") / f"delvjax-test-{tmp_path.name}"
    argv = writer_argv(command, plain9)
    assert main(argv + ["--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --out:") and str(out) in line, line
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == (["file"] if where == "under a file" else [])


@pytest.mark.parametrize(
    "exc", [OSError(28, "No space left on device"), KeyboardInterrupt()], ids=["disk full", "interrupted"]
)
def test_a_render_that_fails_midway_leaves_nothing(tmp_path, monkeypatch, exc):
    calls = []
    add = image_db.DatabaseWriter.add

    def failing_add(self, *args, **kwargs):
        calls.append(self.tmp)
        if len(calls) > 1:
            assert any(self.tmp.iterdir())  # the first chunk is on disk ...
            raise exc
        return add(self, *args, **kwargs)

    monkeypatch.setattr(image_db.DatabaseWriter, "add", failing_add)
    out = tmp_path / "db"
    argv = ["images", "render-db", "robot", *SMALL, "--chunk", "5", "--out", str(out)]
    if isinstance(exc, KeyboardInterrupt):  # Ctrl-C: one line, exit 130
        assert main(argv) == 130
    else:
        with pytest.raises(type(exc)):
            main(argv)
    assert len(calls) == 2
    no_leftovers(out)  # ... and gone
    assert not calls[0].exists() and not list(tmp_path.iterdir())


def test_an_import_that_fails_midway_leaves_nothing(small_db, tmp_path, capsys):
    """A bad image in the last chunk: the first chunks were already written into the temporary folder."""
    src = tmp_path / "bob"
    shutil.copytree(small_db, src)
    last = entries(src)[-1]["Filename"]
    (src / last).write_bytes(b"")
    out = tmp_path / "sub" / "out"
    assert main(["images", "import", str(src), "--out", str(out), "--spacing", "20"]) == 2  # ensure arena etc. pass
    assert last in error_line(capsys)
    no_leftovers(out)


@pytest.mark.parametrize(
    "flags, field",
    [
        (["--cols", "70"], "cols"),
        (["--rows", "0"], "rows"),
        (["--spacing", "0"], "spacing"),
        (["--spacing", "500"], "spacing"),
        (["--pixel-noise", "-0.1"], "pixel_noise"),
        (["--seed", "-1"], "seed"),
        (["--chunk", "0"], "chunk"),
        (["--max-points", "10"], "spacing"),
    ],
)
def test_render_db_checks_its_options_before_any_work(tmp_path, capsys, flags, field):
    out = tmp_path / "db"
    assert main(["images", "render-db", "robot", *SMALL, *flags, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(
        (f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:")
    ), err  # before any progress line
    assert not list(tmp_path.iterdir())


def test_render_db_of_an_unknown_world_and_images_of_no_folder(tmp_path, capsys):
    assert main(["images", "render-db", "atlantis", "--out", str(tmp_path / "db")]) == 2
    assert "atlantis" in error_line(capsys)
    assert main(["vector-map", "--images", str(tmp_path / "nowhere"), "--out", str(tmp_path / "m.csv")]) == 2
    line = error_line(capsys)
    assert str(tmp_path / "nowhere") in line and "is not a folder" in line, line
    assert main(["images", "import", str(tmp_path / "nowhere"), "--out", str(tmp_path / "db")]) == 2
    assert "nowhere" in error_line(capsys)
    assert not list(tmp_path.iterdir())


def test_a_render_that_would_not_fit_on_the_disk_is_refused(tmp_path, capsys, monkeypatch):
    import shutil
    from collections import namedtuple

    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**6, 0, 10**6))  # 1 MB free
    out = tmp_path / "db"
    assert main(["images", "render-db", "robot", "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --out:") and "GB free" in line and "71 images" in line, line
    assert not out.exists() and not list(tmp_path.glob(".db.*"))
