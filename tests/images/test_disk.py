"""Image databases on disk (docs/images.md §4, §6): the BoB layout `images render-db` writes, its files read
back bit for bit, the file column convention, chunk invariance, and `images import` of BoB and plain folders.
Small renders (72 x 12 panoramas) are shared by module-scoped fixtures (conftest.py)."""

from __future__ import annotations

import math

import jax
import numpy as np
import pytest
import yaml
from PIL import Image

from delvjax.cli._main import main
from delvjax.core.images import Catadioptric
from delvjax.images import load_database
from delvjax.images._disk import ENTRIES, METADATA, POSITIONS, file_columns, read_index
from delvjax.images._render import ImageSettings, camera, lit, render_images, render_rings, world_grid
from delvjax.images._worlds import image_world
from delvjax.images._writer import BOB_COLUMNS, BOB_GRID_COLUMNS
from tests.cases.images_io import (
    CYLINDERS,
    HEADER,
    SEED,
    SMALL,
    at,
    by_position,
    entries,
    leaves_equal,
    read_csv,
    render_db,
    summary_numbers,
    write_plain,
)

# --- the BoB layout --------------------------------------------------------------------------------


def test_render_db_writes_the_bob_layout(default_db):
    iw = image_world("robot")
    pts, grid = world_grid(iw, iw.spacing)
    assert (default_db / ENTRIES).read_text().splitlines()[0] == HEADER
    assert ", ".join(BOB_COLUMNS + BOB_GRID_COLUMNS) == HEADER
    rows = entries(default_db)
    assert len(rows) == len(pts) == 71  # 9 x 9 less the points within r + 10 cm of a cylinder
    for r, p, (gx, gy) in zip(rows, pts, grid):
        x_mm, y_mm = float(r["X [mm]"]), float(r["Y [mm]"])
        assert (x_mm, y_mm) == pytest.approx((10 * p[0], 10 * p[1]), abs=1e-6)  # millimetres
        assert (x_mm, y_mm) == pytest.approx((200 * gx + 100, 200 * gy + 100))  # cell centres every 20 cm
        # Z: the camera's height (250 mm); the heading in BoB's conventions: the centre column looks west,
        # a compass bearing of 270 (docs/images.md §4.1); BoB's numbers (%.17e) and file names (mm)
        assert float(r["Z [mm]"]) == 250 and float(r["Heading [degrees]"]) == 270 and r["Grid Z"] == "0"
        assert r["X [mm]"] == f"{x_mm:.17e}" and r["Pitch [degrees]"] == "nan"
        assert (int(r["Grid X"]), int(r["Grid Y"])) == (gx, gy)
        assert r["Filename"] == f"image_{round(x_mm):+07d}_{round(y_mm):+07d}_+000250.png"
        for cx, cy, cr in CYLINDERS:
            assert math.hypot(x_mm / 10 - cx, y_mm / 10 - cy) > cr + 10
    text = (default_db / METADATA).read_text()
    assert text.splitlines()[0] == "%YAML:1.0"
    meta = yaml.safe_load(text.split("\n", 1)[1])["metadata"]
    assert meta["camera"]["resolution"] == [360, 60] and meta["needsUnwrapping"] == 0 and meta["isGreyscale"] == 0
    assert meta["type"] == "grid" and meta["grid"] == {
        "beginAtMM": [100.0, 100.0, 250.0],
        "separationMM": [200.0, 200.0, 0.0],
        "size": [9, 9, 1],
    }
    assert (meta["headingConvention"], meta["headingColumn"], meta["columnOrder"]) == ("compass", "centre", "clockwise")
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
    mem = np.asarray(
        render_images(
            lit(iw.world, None),
            s.camera,
            None,
            pts,
            np.zeros(len(pts), np.float32),
            np.arange(len(pts)),
            jax.random.PRNGKey(SEED),
            s.pixel_noise,
            s.gain_noise,
        )
    )
    rows = entries(small_db)
    for i, r in enumerate(rows):
        with Image.open(small_db / r["Filename"]) as im:
            f = np.asarray(im.convert("RGB"))
        assert np.array_equal(f, file_columns(mem[i])), r["Filename"]
        assert np.array_equal(file_columns(f), mem[i])
    # home (90, 90), heading 0: where the red cylinders appear in the file
    home = at(rows, 900, 900)
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
    # BoB writes ", " between fields, as delvjax does; without the spaces it reads alike
    compact = (out / ENTRIES).read_text().replace(", ", ",")
    assert compact.startswith("X [mm],Y [mm],Z [mm],Heading [degrees],Pitch [degrees]")
    (out / ENTRIES).write_text(compact)
    leaves_equal(a.rings, load_database(out).rings)


def test_a_plain_folder_is_imported_and_evaluated_to_the_same_numbers(small_db, plain_db, tmp_path, capsys):
    imported = tmp_path / "imported"
    assert main(["images", "import", str(plain_db), "--out", str(imported)]) == 0
    assert [float(r["X [mm]"]) for r in entries(imported)] == [
        float(x) * 10 for x in (r["x"] for r in read_csv(plain_db / POSITIONS))
    ]
    results = {}
    for name, folder in [("bob", small_db), ("imported", imported), ("plain", plain_db)]:
        out, summary = tmp_path / f"{name}.csv", tmp_path / f"{name}.json"
        plot = ["--plot", str(tmp_path / "bob.png")] if name == "bob" else []
        assert (
            main(
                [
                    "vector-map",
                    "--images",
                    str(folder),
                    "--method",
                    "delv",
                    "--out",
                    str(out),
                    "--summary",
                    str(summary),
                    *plot,
                ]
            )
            == 0
        )
        results[name] = by_position(read_csv(out)), summary_numbers(summary)
    capsys.readouterr()
    with Image.open(tmp_path / "bob.png") as im:
        assert im.format == "PNG" and min(im.size) > 200
    bob_rows, bob_summary = results["bob"]
    assert len(bob_rows) == 70 and bob_summary["points"] == 70 and bob_summary["home"] == [90, 90]
    assert bob_summary["invalid"] < 70 and bob_summary["mean_error_deg"] < 90  # DELV homes on this database
    for name in ("imported", "plain"):  # the same numbers up to float32 rounding of the home-frame sort
        rows, summary = results[name]
        assert _close(summary, bob_summary), name
        assert _close(rows, bob_rows), name


def _close(a, b) -> bool:
    """Equal, numbers (or numeric strings) within 1e-4 deg / 1e-5 relative."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    try:
        x, y = float(a), float(b)
    except (TypeError, ValueError):
        return a == b
    return x == y or (x == x and y == y and abs(x - y) <= 1e-4 + 1e-5 * abs(y))


def test_images_closer_than_the_spacing_keep_every_image(small_db, tmp_path):
    """Images closer than the spacing share grid cells: import names them by their millimetres (BoB's
    grid names) instead of overwriting one with another."""
    rows = [dict(r) for r in entries(small_db)[:6]]
    for i, r in enumerate(rows):  # 5 cm apart along y = 90, spacing 20
        r["X [mm]"], r["Y [mm]"] = str(1000 + 50 * i), "900"
    plain = write_plain(tmp_path / "route", small_db, rows, rename=lambda i, f: f"r{i}.png")
    out = tmp_path / "db"
    assert main(["images", "import", str(plain), "--out", str(out), "--spacing", "20", "--home", "100", "90"]) == 0
    names = [r["Filename"] for r in entries(out)]
    assert names == [f"image_{1000 + 50 * i:+07d}_+000900_+000000.png" for i in range(6)]
    assert all((out / n).is_file() for n in names)
    a, b = load_database(plain, spacing=20, home=(100, 90)), load_database(out)
    assert np.array_equal(np.asarray(a.rings.snapshots.mask), np.asarray(b.rings.snapshots.mask))
