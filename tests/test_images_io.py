"""Image databases on disk (docs/images.md §4, §6, §7), tried as a demanding stranger would: the BoB
layout `images render-db` writes, its files read back bit for bit, the file column convention, chunk
invariance, `images import` of BoB and plain folders, every reading error (exit 2, one line naming the
file, nothing left at --out), `vector-map --images` / `catchment --images`, and odd databases.

Small renders (72 x 12 panoramas) are shared by module-scoped fixtures; one default-size render
checks the stated size."""

from __future__ import annotations

import csv
import json
import math
import os
import shutil
from pathlib import Path

import jax
import numpy as np
import pytest
import yaml
from PIL import Image

from delvjax import image_db
from delvjax.api_image_eval import load_database
from delvjax.api_images import ImageSettings, camera, lit, render_images, render_rings, world_grid
from delvjax.cli import main
from delvjax.core.images import Catadioptric
from delvjax.image_db import BOB_COLUMNS, ENTRIES, METADATA, POSITIONS, file_columns, read_index
from delvjax.image_worlds import image_world

SMALL = ["--cols", "72", "--rows", "12"]
SEED = 7
HEADER = "X [mm],Y [mm],Z [mm],Heading [degrees],Filename,Grid X,Grid Y,Grid Z"
CYLINDERS = [(45.0, 135.0, 8.0), (130.0, 150.0, 8.0), (145.0, 55.0, 8.0), (55.0, 42.0, 8.0)]  # docs/images.md §8


# --- helpers ---------------------------------------------------------------------------------------

def render_db(out: Path, *extra: str) -> Path:
    assert main(["images", "render-db", "robot", "--out", str(out), *extra]) == 0
    return out


def writer_argv(command: str, src: Path) -> list[str]:
    """The command line of a command that writes a database, less --out."""
    return ["images", "render-db", "robot", *SMALL] if command == "render-db" else ["images", "import", str(src)]


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    errors = [ln for ln in err if ln.startswith("delvjax: error:")]
    assert len(errors) == 1 and "Traceback" not in "\n".join(err), err  # one line, no traceback
    return errors[0]


def no_leftovers(out: Path) -> None:
    """Nothing at --out and no temporary `.name.*` folder of the writer beside it."""
    assert not out.exists(), sorted(out.iterdir()) if out.is_dir() else out
    assert not list(out.parent.glob(f".{out.name}.*")), list(out.parent.glob(f".{out.name}.*"))


def entries(folder: Path) -> list[dict[str, str]]:
    with open(folder / ENTRIES, newline="") as fh:
        return list(csv.DictReader(fh))


def leaves_equal(a, b) -> None:
    la, lb = jax.tree.leaves(a), jax.tree.leaves(b)
    assert len(la) == len(lb)
    for x, y in zip(la, lb):
        x, y = np.asarray(x), np.asarray(y)
        assert x.shape == y.shape and x.dtype == y.dtype
        np.testing.assert_array_equal(x, y)  # exact; NaN equals NaN


def read_csv(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def by_position(rows: list[dict[str, str]]) -> dict[tuple[float, float], dict[str, str]]:
    out = {(round(float(r["x"]), 3), round(float(r["y"]), 3)): r for r in rows}
    assert len(out) == len(rows)
    return out


def summary_numbers(path: Path) -> dict:
    s = json.loads(path.read_text())
    return {k: v for k, v in s.items() if k not in ("images", "seconds")}


def write_plain(folder: Path, src: Path, rows: list[dict[str, str]], rename=lambda i, f: f, heading=True) -> Path:
    """A plain folder: the images of `rows` (BoB entries of `src`) copied under new names + positions.csv (cm)."""
    folder.mkdir(parents=True)
    with open(folder / POSITIONS, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["filename", "x", "y"] + (["heading_deg"] if heading else []))
        for i, r in enumerate(rows):
            name = rename(i, r["Filename"])
            shutil.copyfile(src / r["Filename"], folder / name)
            w.writerow([name, float(r["X [mm]"]) / 10, float(r["Y [mm]"]) / 10]
                       + ([r["Heading [degrees]"]] if heading else []))
    return folder


# --- shared databases ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def default_db(tmp_path_factory) -> Path:
    """The robot world at the default size (360 x 60)."""
    return render_db(tmp_path_factory.mktemp("default") / "robot")


@pytest.fixture(scope="module")
def small_db(tmp_path_factory) -> Path:
    return render_db(tmp_path_factory.mktemp("small") / "robot", *SMALL, "--seed", str(SEED))


@pytest.fixture(scope="module")
def donut_db(tmp_path_factory) -> Path:
    return render_db(tmp_path_factory.mktemp("donut") / "robot", *SMALL, "--donut", "--seed", str(SEED))


@pytest.fixture(scope="module")
def plain_db(tmp_path_factory, small_db) -> Path:
    """The small database as a plain folder: shuffled rows, other file names, positions.csv in cm."""
    rows = entries(small_db)
    order = np.random.default_rng(0).permutation(len(rows))
    return write_plain(tmp_path_factory.mktemp("plain") / "panos", small_db, [rows[i] for i in order],
                       rename=lambda i, f: f"pano {i:03d}.png")


@pytest.fixture(scope="module")
def plain9(tmp_path_factory, small_db) -> Path:
    """A 3 x 3 plain folder (centre (90, 90)), the template the error cases break."""
    rows = [r for r in entries(small_db) if max(abs(float(r["X [mm]"]) - 900), abs(float(r["Y [mm]"]) - 900)) <= 200]
    assert len(rows) == 9
    return write_plain(tmp_path_factory.mktemp("plain9") / "nine", small_db, rows, rename=lambda i, f: f"p{i}.png")


# --- the BoB layout --------------------------------------------------------------------------------

def test_render_db_writes_the_bob_layout(default_db):
    iw = image_world("robot")
    pts, grid = world_grid(iw, iw.spacing)
    assert (default_db / ENTRIES).read_text().splitlines()[0] == HEADER
    assert ",".join(BOB_COLUMNS) == HEADER
    rows = entries(default_db)
    assert len(rows) == len(pts) == 71  # 9 x 9 less the points within r + 10 cm of a cylinder
    for r, p, (gx, gy) in zip(rows, pts, grid):
        x_mm, y_mm = float(r["X [mm]"]), float(r["Y [mm]"])
        assert (x_mm, y_mm) == pytest.approx((10 * p[0], 10 * p[1]), abs=1e-6)  # millimetres
        assert (x_mm, y_mm) == pytest.approx((200 * gx + 100, 200 * gy + 100))  # cell centres every 20 cm
        assert float(r["Z [mm]"]) == 0 and float(r["Heading [degrees]"]) == 0 and r["Grid Z"] == "0"
        assert (int(r["Grid X"]), int(r["Grid Y"])) == (gx, gy)
        assert r["Filename"] == f"image_{gx:+05d}_{gy:+05d}_+0000.png"
        for cx, cy, cr in CYLINDERS:
            assert math.hypot(x_mm / 10 - cx, y_mm / 10 - cy) > cr + 10
    text = (default_db / METADATA).read_text()
    assert text.splitlines()[0] == "%YAML:1.0"
    meta = yaml.safe_load(text.split("\n", 1)[1])["metadata"]
    assert meta["camera"]["resolution"] == [360, 60] and meta["needsUnwrapping"] == 0 and meta["isGreyscale"] == 0
    d = meta["delvjax"]
    assert d["world"] == "robot" and d["arena_cm"] == [0, 0, 180, 180] and d["home_cm"] == [90, 90]
    assert d["spacing_cm"] == 20 and d["camera_height_cm"] == 25 and d["elevation_deg"] == [30, -30]
    assert d["panorama"] == [60, 360] and d["extractor"]["max_blobs"] == 4
    assert sorted(map(tuple, d["obstacles"]["cylinders"])) == sorted(CYLINDERS) and d["obstacles"]["boxes"] == []
    pngs = sorted(p.name for p in default_db.iterdir() if p.suffix == ".png")
    assert pngs == sorted(r["Filename"] for r in rows)
    assert sorted(p.name for p in default_db.iterdir()) == sorted(pngs + [ENTRIES, METADATA])
    for name in pngs:
        with Image.open(default_db / name) as im:
            assert im.format == "PNG" and im.mode == "RGB" and im.size == (360, 60)
    assert not list(default_db.parent.glob(".robot.*"))  # the temporary folder was renamed into place


def test_small_render_has_the_stated_size_and_metadata(small_db, donut_db):
    for name in (r["Filename"] for r in entries(small_db)):
        with Image.open(small_db / name) as im:
            assert im.size == (72, 12)
    meta = read_index(small_db)
    assert meta.meta["panorama"] == [12, 72] and meta.meta["seed"] == SEED and not meta.needs_unwrapping
    donut = read_index(donut_db)
    assert donut.needs_unwrapping and donut.meta["panorama"] == [12, 72] and donut.meta["catadioptric"]["size"] == 240
    with Image.open(donut.files[0]) as im:
        assert im.size == (240, 240)


# --- bit for bit -----------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["panorama", "donut"])
def test_loaded_rings_equal_the_in_memory_rings(small_db, donut_db, kind):
    """8-bit quantization before the pipeline: the rings of the files equal render_rings, bit for bit."""
    folder = small_db if kind == "panorama" else donut_db
    iw = image_world("robot")
    pts, _ = world_grid(iw, iw.spacing)
    settings = ImageSettings(camera=camera(12, 72), mirror=Catadioptric() if kind == "donut" else None)
    mem = render_rings(iw, settings, pts, np.zeros(len(pts), np.float32), jax.random.PRNGKey(SEED))
    db = load_database(folder)
    assert np.allclose(np.asarray(db.rings.positions), pts, atol=1e-4)
    assert np.array_equal(np.asarray(db.rings.headings), np.zeros(len(pts), np.float32))
    leaves_equal(db.rings.snapshots, mem.snapshots)
    valid = np.asarray(db.rings.snapshots.valid).sum(-1)
    assert valid.min() >= 2 and valid.max() == 4  # the rings see the red cylinders: the comparison is not vacuous
    if kind == "panorama":
        other = render_rings(iw, settings, pts, np.zeros(len(pts), np.float32), jax.random.PRNGKey(SEED + 1))
        assert not np.array_equal(np.asarray(other.snapshots.gray), np.asarray(mem.snapshots.gray))  # seed matters


def test_file_columns_is_its_own_inverse_and_maps_j_to_minus_j():
    rng = np.random.default_rng(1)
    for w in (1, 2, 7, 72):
        a = rng.integers(0, 256, size=(3, 4, w, 3), dtype=np.uint8)
        f = file_columns(a)
        assert np.array_equal(file_columns(f), a)
        for j in range(w):
            assert np.array_equal(f[..., j, :], a[..., (-j) % w, :])


def test_a_file_is_the_unmirrored_view(small_db):
    """A panorama read from its file is file_columns() of the in-memory image, and file column c looks
    along heading - 360 c / W (clockwise to the right)."""
    iw = image_world("robot")
    pts, _ = world_grid(iw, iw.spacing)
    s = ImageSettings(camera=camera(12, 72))
    mem = np.asarray(render_images(lit(iw.world, None), s.camera, None, pts, np.zeros(len(pts), np.float32),
                                   np.arange(len(pts)), jax.random.PRNGKey(SEED), s.pixel_noise, s.gain_noise))
    rows = entries(small_db)
    for i, r in enumerate(rows):
        with Image.open(small_db / r["Filename"]) as im:
            f = np.asarray(im.convert("RGB"))
        assert np.array_equal(f, file_columns(mem[i])), r["Filename"]
        assert np.array_equal(file_columns(f), mem[i])
    # home (90, 90), heading 0: where the red cylinders appear in the file
    home = next(r for r in rows if r["X [mm]"] == "900.0" and r["Y [mm]"] == "900.0")
    with Image.open(small_db / home["Filename"]) as im:
        f = np.asarray(im.convert("RGB")).astype(int)
    band = f[5:7]  # the two rows about the horizon (centres at +2.5 and -2.5 deg)
    red = ((band[..., 0] > 60) & (band[..., 0] > 3 * band[..., 1]) & (band[..., 0] > 3 * band[..., 2])).any(0)
    seen = np.degrees(-2 * np.pi * np.flatnonzero(red) / 72) % 360  # file column c looks along -360 c / W
    truth = [math.degrees(math.atan2(cy - 90, cx - 90)) % 360 for cx, cy, _ in CYLINDERS]
    diff = lambda a, b: abs((a - b + 180) % 360 - 180)  # noqa: E731
    assert all(min(diff(t, s) for s in seen) <= 10 for t in truth), (seen, truth)
    assert all(min(diff(s, t) for t in truth) <= 15 for s in seen), (seen, truth)


def test_render_db_files_do_not_depend_on_chunk(small_db, tmp_path):
    other = render_db(tmp_path / "c5", *SMALL, "--seed", str(SEED), "--chunk", "5")
    names = sorted(p.name for p in small_db.iterdir())
    assert names == sorted(p.name for p in other.iterdir())
    for name in names:
        assert (small_db / name).read_bytes() == (other / name).read_bytes(), name


# --- import ----------------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["panorama", "donut"])
def test_import_of_a_bob_database_round_trips(small_db, donut_db, tmp_path, capsys, kind):
    src = small_db if kind == "panorama" else donut_db
    out = tmp_path / "imported"
    assert main(["images", "import", str(src), "--out", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().out
    assert (out / ENTRIES).read_text().splitlines()[0] == HEADER
    a, b = load_database(src), load_database(out)
    leaves_equal(a.rings, b.rings)
    assert (a.home == b.home).all() and (a.arena == b.arena).all() and a.spacing == b.spacing
    assert a.camera == b.camera and (a.mirror is None) == (b.mirror is None) and a.extractor == b.extractor
    assert a.obstacles == b.obstacles
    for ra, rb in zip(entries(src), entries(out)):
        assert ra == rb
        with Image.open(src / ra["Filename"]) as ia, Image.open(out / rb["Filename"]) as ib:
            assert np.array_equal(np.asarray(ia.convert("RGB")), np.asarray(ib.convert("RGB"))), ra["Filename"]
    assert not list(tmp_path.glob(".imported.*"))
    # BoB itself writes "X [mm], Y [mm], ..." with a space after every comma: read alike
    spaced = (out / ENTRIES).read_text().replace(",", ", ")
    assert spaced.startswith("X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X")
    (out / ENTRIES).write_text(spaced)
    leaves_equal(a.rings, load_database(out).rings)


def test_a_plain_folder_is_imported_and_evaluated_to_the_same_numbers(small_db, plain_db, tmp_path, capsys):
    imported = tmp_path / "imported"
    assert main(["images", "import", str(plain_db), "--out", str(imported)]) == 0
    assert [float(r["X [mm]"]) for r in entries(imported)] == [float(x) * 10 for x in
                                                               (r["x"] for r in read_csv(plain_db / POSITIONS))]
    results = {}
    for name, folder in [("bob", small_db), ("imported", imported), ("plain", plain_db)]:
        out, summary = tmp_path / f"{name}.csv", tmp_path / f"{name}.json"
        plot = ["--plot", str(tmp_path / "bob.png")] if name == "bob" else []
        assert main(["vector-map", "--images", str(folder), "--method", "delv", "--out", str(out),
                     "--summary", str(summary), *plot]) == 0
        results[name] = by_position(read_csv(out)), summary_numbers(summary)
    capsys.readouterr()
    with Image.open(tmp_path / "bob.png") as im:
        assert im.format == "PNG" and min(im.size) > 200
    bob_rows, bob_summary = results["bob"]
    assert len(bob_rows) == 70 and bob_summary["points"] == 70 and bob_summary["home"] == [90, 90]
    assert bob_summary["invalid"] < 70 and bob_summary["mean_error_deg"] < 90  # DELV homes on this database
    for name in ("imported", "plain"):
        rows, summary = results[name]
        assert summary == bob_summary, name
        assert rows == bob_rows, name


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


BREAKS = {"missing image": (_break_missing, []), "garbage png": (_break_garbage, []),
          "other size": (_break_size, []), "non-numeric": (_break_number, []), "no csv": (_break_no_csv, []),
          "outside arena": (_break_outside, ["--arena", "0", "0", "100", "100"])}


@pytest.mark.parametrize("command", ["import", "vector-map"])
@pytest.mark.parametrize("case", list(BREAKS))
def test_a_bad_plain_folder_exits_2_naming_the_file(plain9, tmp_path, capsys, command, case):
    src = tmp_path / "nine"
    shutil.copytree(plain9, src)
    breaker, extra = BREAKS[case]
    needed = breaker(src)
    out = tmp_path / ("out" if command == "import" else "m.csv")
    argv = (["images", "import", str(src), "--out", str(out)] if command == "import"
            else ["vector-map", "--images", str(src), "--out", str(out)])
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
    lines[7] = lines[7].replace("0,0.0,", "0,north,", 1)  # the heading of CSV row 8
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


@pytest.mark.parametrize("exc", [OSError(28, "No space left on device"), KeyboardInterrupt()],
                         ids=["disk full", "interrupted"])
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
    with pytest.raises(type(exc)):
        main(["images", "render-db", "robot", *SMALL, "--chunk", "5", "--out", str(out)])
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


@pytest.mark.parametrize("flags, field", [
    (["--cols", "70"], "cols"), (["--rows", "0"], "rows"), (["--spacing", "0"], "spacing"),
    (["--spacing", "500"], "spacing"), (["--pixel-noise", "-0.1"], "pixel_noise"), (["--seed", "-1"], "seed"),
    (["--chunk", "0"], "chunk"), (["--max-points", "10"], "spacing"),
])
def test_render_db_checks_its_options_before_any_work(tmp_path, capsys, flags, field):
    out = tmp_path / "db"
    assert main(["images", "render-db", "robot", *SMALL, *flags, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"delvjax: error: {field}:"), err  # before any progress line
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


# --- vector-map / catchment --images options ---------------------------------------------------------

@pytest.mark.parametrize("command, flags, field", [
    ("vector-map", ["--bearing-noise-deg", "2"], "--bearing-noise-deg"),
    ("vector-map", ["--hide", "0"], "--hide"),
    ("vector-map", ["--heading-deg", "90"], "--heading-deg"),
    ("vector-map", ["--d", "10"], "--d"),
    ("vector-map", ["--turn-noise-deg", "3"], "--turn-noise-deg"),
    ("vector-map", ["robot"], "env"),
    ("catchment", ["--lanes", "8"], "--lanes"),
    ("catchment", ["--first-move", "release"], "--first-move"),
    ("catchment", ["--step-noise", "0.1"], "--step-noise"),
    ("catchment", ["env1"], "env"),
])
def test_options_that_do_not_apply_to_images_are_refused(small_db, tmp_path, capsys, command, flags, field):
    out = tmp_path / "m.csv"
    argv = [command, *flags, "--images", str(small_db), "--out", str(out)]
    if flags[0] in ("robot", "env1"):  # the positional first
        argv = [command, flags[0], "--images", str(small_db), "--out", str(out)]
    assert main(argv) == 2
    line = error_line(capsys)
    assert line.startswith(f"delvjax: error: {field}:"), line
    assert not out.exists() and not list(tmp_path.iterdir())


@pytest.mark.parametrize("command", ["vector-map", "catchment"])
def test_neither_an_environment_nor_images_is_an_error(tmp_path, capsys, command):
    out = tmp_path / "m.csv"
    assert main([command, "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: env:") and "--images" in line, line
    assert not out.exists()


def test_catchment_images_refuses_an_unknown_collision_rule(small_db, tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["catchment", "--images", str(small_db), "--collisions", "maybe", "--summary", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: collisions:")
    assert not out.exists()


@pytest.mark.parametrize("flags", [["--method", "magic"], ["--levels", "0"], ["--chunk", "0"]])
def test_vector_map_images_checks_options_before_announcing_work(small_db, tmp_path, capsys, flags):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "--images", str(small_db), *flags, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert not out.exists()
    assert len(err) == 1 and err[0].startswith("delvjax: error: "), err


def test_a_database_map_with_every_point_invalid_warns(small_db, tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "--images", str(small_db), "--hue-deg", "180", "--out", str(out)]) == 0  # no red
    assert all(r["valid"] == "0" for r in read_csv(out))
    warnings = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("delvjax: warning:")]
    assert len(warnings) == 1 and "invalid" in warnings[0]


def test_catchment_on_a_database(small_db, tmp_path, capsys):
    res = {}
    for rule in ("ignore", "fail"):
        out, summary = tmp_path / f"{rule}.csv", tmp_path / f"{rule}.json"
        assert main(["catchment", "--images", str(small_db), "--method", "delv", "--collisions", rule,
                     "--out", str(out), "--summary", str(summary)]) == 0
        res[rule] = json.loads(summary.read_text()), read_csv(out)
    capsys.readouterr()
    for rule, (s, rows) in res.items():
        assert 0 <= s["catchment_pct"] <= 100 and s["collisions"] == rule
        assert s["releases"] == len(rows) == 71 - 5  # every image farther than the spacing from home
        assert s["home_radius_cm"] == 20 and s["step_cm"] == 20
        shares = [s[f"{k}_pct"] for k in ("catchment", "timeout", "landmark", "arena", "undefined")]
        assert sum(shares) == pytest.approx(100)
        assert {r["outcome"] for r in rows} <= {"success", "timeout", "landmark", "arena", "undefined"}
        assert s["catchment_pct"] == pytest.approx(100 * sum(r["outcome"] == "success" for r in rows) / len(rows))
        assert all(math.hypot(float(r["x"]) - 90, float(r["y"]) - 90) > 20 for r in rows)
    ignore, fail = res["ignore"][0], res["fail"][0]
    assert ignore["landmark_pct"] == 0 and fail["landmark_pct"] > 0  # obstacles count only with --collisions fail
    assert fail["catchment_pct"] <= ignore["catchment_pct"]
    for a, b in zip(res["ignore"][1], res["fail"][1]):  # a trial that hits a cylinder fails instead
        if b["outcome"] != a["outcome"]:
            assert b["outcome"] == "landmark"


def test_noisy_rollouts_repeat_with_the_same_seed(small_db, tmp_path, capsys):
    def run(seed: int, tag: str):
        out, summary = tmp_path / f"{tag}.csv", tmp_path / f"{tag}.json"
        assert main(["catchment", "--images", str(small_db), "--method", "alv", "--seed", str(seed),
                     "--motion-heading-noise-deg", "40", "--motion-step-noise", "0.3", "--out", str(out),
                     "--summary", str(summary)]) == 0
        return out.read_bytes(), summary_numbers(summary)

    a, b, c = run(5, "a"), run(5, "b"), run(6, "c")
    capsys.readouterr()
    assert a == b
    assert c[0] != a[0]  # the noise is drawn from the seed


# --- edge databases ----------------------------------------------------------------------------------

def test_a_database_of_one_image(small_db, tmp_path, capsys):
    home = next(r for r in entries(small_db) if r["X [mm]"] == "900.0" and r["Y [mm]"] == "900.0")
    one = write_plain(tmp_path / "one", small_db, [home], heading=False)
    out = tmp_path / "imported"
    assert main(["images", "import", str(one), "--out", str(out)]) == 2
    line = error_line(capsys)
    assert "one image" in line and "spacing" in line and str(one) in line, line
    no_leftovers(out)
    assert main(["vector-map", "--images", str(one), "--summary", str(tmp_path / "s.json")]) == 2
    assert "spacing" in error_line(capsys)
    assert not (tmp_path / "s.json").exists()
    # with a spacing, the lone image is home and has no neighbour for the home record's unit move
    assert main(["images", "import", str(one), "--out", str(out), "--spacing", "20"]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: home:") and "unit move" in line and "home" in line, line
    no_leftovers(out)


def test_a_home_without_an_axis_neighbour_does_not_pass_silently(small_db, tmp_path, capsys):
    """docs/images.md §6: the home record is the move from home to its first axis neighbour. Here home
    has none; a home record of a zero-length move (home -> home) must not give a valid-looking map: an
    error naming home, a warning naming home, or every point invalid. (The four neighbours are moved
    7 cm off the grid rather than removed: the database keeps its shape and its compiled programs.)"""
    gone = {(1100, 900), (700, 900), (900, 1100), (900, 700)}
    rows = [dict(r) for r in entries(small_db)]
    for r in rows:
        if (round(float(r["X [mm]"])), round(float(r["Y [mm]"]))) in gone:
            r["X [mm]"], r["Y [mm]"] = str(float(r["X [mm]"]) + 70), str(float(r["Y [mm]"]) + 70)
    iso = write_plain(tmp_path / "iso", small_db, rows)
    out = tmp_path / "m.csv"
    rc = main(["vector-map", "--images", str(iso), "--method", "delv", "--home", "90", "90", "--spacing", "20",
               "--out", str(out)])
    err = capsys.readouterr().err
    if rc == 2:  # refused, naming home
        assert "delvjax: error: home" in err and not out.exists(), err
        return
    assert rc == 0
    rows = read_csv(out)
    warned = any(ln.startswith("delvjax: warning:") and "home" in ln for ln in err.splitlines())
    assert warned or all(r["valid"] == "0" for r in rows), err
