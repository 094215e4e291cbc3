"""BoB robotics' image databases both ways (docs/images.md §4.1-4.2, §6.1): databases made in BoB's exact
format (its docs' example_grid and example_route, tests/cases/bob.py) load with the right poses and home
correctly, grid and route; what delvjax writes passes OpenCV's parser and BoB's reader checks; headings,
Z and UTM-scale positions survive; every convention choice is declared or refused."""

from __future__ import annotations

import math
import shutil
import warnings
from pathlib import Path

import jax
import numpy as np
import pytest

from delvjax.cli._main import main
from delvjax.images import database_catchment, database_vector_map, import_database, load_database
from delvjax.images._load import DatabaseWarning
from delvjax.images._render import ImageSettings, camera, lit, render_images, render_rings
from delvjax.images._worlds import image_world
from tests.cases.bob import bob_file_image, bob_read, write_bob_database
from tests.cases.images_io import entries, error_line, no_leftovers

pytest.importorskip("cv2")  # OpenCV's own parser (opencv-python-headless, a test dependency)

H, W = 12, 72
CAM = camera(H, W)
READ = {"elevation": (30.0, -30.0), "max_blobs": 4}  # the camera and extractor the fixtures were rendered with


def render(positions: np.ndarray, column0_deg: np.ndarray) -> np.ndarray:
    """Noise-free memory-order panoramas of the robot world (docs/images.md §8)."""
    iw = image_world("robot")
    return np.asarray(
        render_images(
            lit(iw.world, None),
            CAM,
            None,
            np.asarray(positions, np.float32),
            np.radians(np.asarray(column0_deg, np.float64)).astype(np.float32),
            np.arange(len(positions)),
            jax.random.PRNGKey(0),
            0.0,
            0.0,
        )
    )


def grid_points() -> np.ndarray:
    return np.array([(x, y) for y in range(30, 171, 20) for x in range(30, 171, 20)], np.float64)


def route_points() -> tuple[np.ndarray, np.ndarray]:
    """A route every 10 cm along three legs, ending at (150, 90), and BoB's compass heading of each
    image: 90 - atan2(dy, dx) of the leg it starts (route_continuous.cc), the last one's leg for the last."""
    legs = [np.array(p, np.float64) for p in [(20, 20), (20, 100), (90, 160), (150, 90)]]
    pts = [legs[0]]
    for a, b in zip(legs[:-1], legs[1:]):
        n = int(round(np.linalg.norm(b - a) / 10))
        pts += [a + (b - a) * k / n for k in range(1, n + 1)]
    pts = np.array(pts)
    d = np.diff(pts, axis=0)
    compass = np.mod(90.0 - np.degrees(np.arctan2(d[:, 1], d[:, 0])), 360.0)
    return pts, np.r_[compass, compass[-1]]


def bob_images(positions: np.ndarray, compass: np.ndarray) -> list[np.ndarray]:
    """BoB's files at these poses: rendered with column 0 along the centre column's angle + 180 deg."""
    column0 = np.mod(90.0 - compass + 180.0, 360.0)
    return [bob_file_image(m, c, b) for m, c, b in zip(render(positions, column0), column0, compass)]


@pytest.fixture(scope="module")
def bob_grid(tmp_path_factory) -> Path:
    """A 8 x 8 grid as BoB's GridRecorder writes it: heading 0 (north at the centre column), Z 10 mm."""
    pts = grid_points()
    xyz = np.c_[pts * 10.0, np.full(len(pts), 10.0)]
    return write_bob_database(
        tmp_path_factory.mktemp("bob") / "grid", bob_images(pts, np.zeros(len(pts))), xyz, np.zeros(len(pts)), "grid"
    )


@pytest.fixture(scope="module")
def bob_route(tmp_path_factory) -> Path:
    pts, compass = route_points()
    xyz = np.c_[pts * 10.0, np.full(len(pts), 10.0)]
    return write_bob_database(tmp_path_factory.mktemp("bob") / "route", bob_images(pts, compass), xyz, compass, "route")


def mean_error(db, method: str = "alv") -> float:
    vm = database_vector_map(db, method)
    inc = np.asarray(vm.included)
    assert np.asarray(vm.valid)[inc].all()
    return float(np.asarray(vm.error_deg)[inc].mean())


# --- reading BoB's databases ---------------------------------------------------------------------------


def test_bob_fixtures_pass_bobs_own_reader(bob_grid, bob_route):
    assert bob_read(bob_grid)["type"] == "grid" and len(bob_read(bob_grid)["entries"]) == 64
    assert bob_read(bob_route)["type"] == "route"


def test_a_bob_grid_loads_with_its_poses_and_the_rings_of_its_poses(bob_grid):
    db = load_database(bob_grid, **READ)
    assert db.kind == "grid" and np.array_equal(db.absolute(np.asarray(db.rings.positions)), grid_points())
    # BoB heading 0: the centre column looks north, so column 0 looks south (270 deg, math)
    assert np.allclose(np.degrees(np.asarray(db.rings.headings)), 270.0)
    truth = render_rings(
        image_world("robot"),
        ImageSettings(camera=CAM, pixel_noise=0.0),
        grid_points(),
        np.full(64, math.radians(270.0)),
        jax.random.PRNGKey(0),
    )
    np.testing.assert_array_equal(np.asarray(db.rings.snapshots.mask), np.asarray(truth.snapshots.mask))
    np.testing.assert_array_equal(np.asarray(db.rings.snapshots.gray), np.asarray(truth.snapshots.gray))


def test_bob_conventions_home_correctly_and_the_wrong_ones_do_not(bob_grid, bob_route):
    """The issue's before/after: read in BoB's conventions (the default for BoB files) the grid and the
    route home; read as delvjax's former conventions (math heading of column 0) they are ~90 deg off."""
    for folder in (bob_grid, bob_route):
        right = mean_error(load_database(folder, **READ))
        wrong_db = load_database(folder, conventions={"heading": "math", "heading_column": "first"}, **READ)
        if folder == bob_grid:  # headings alike: the misreading is told, with the flags that fix it
            with pytest.warns(DatabaseWarning, match="--heading-convention compass --heading-column centre"):
                wrong = mean_error(wrong_db)
        else:
            wrong = mean_error(wrong_db)
        assert right < 25.0 and wrong > 60.0, (folder.name, right, wrong)


def test_a_route_is_a_route(bob_route):
    """docs/images.md §6.1: home is the route's last image, every image's unit move comes from the one
    before it, rollouts run on the route's snapshots."""
    pts, compass = route_points()
    db = load_database(bob_route, **READ)
    assert db.kind == "route" and db.home_index == len(pts) - 1 and np.allclose(db.absolute(db.home), pts[-1])
    heading0 = np.mod(90.0 - compass + 180.0, 360.0)
    # the fixture's CSV holds headings to 6 digits, as BoB's example route does ("219.962")
    np.testing.assert_allclose(np.degrees(np.asarray(db.rings.headings)) % 360, heading0, atol=1e-3)
    vm = database_vector_map(db, "alv")
    start = np.asarray(vm.heading)[1:]  # the move into image i comes from image i - 1
    d = np.diff(pts, axis=0)
    np.testing.assert_allclose(start, np.arctan2(d[:, 1], d[:, 0]), atol=2e-4)  # the CSV's 6 digits
    starts, paths = database_catchment(db, vm)
    assert len(starts) == int((np.linalg.norm(pts - pts[-1], axis=-1) > db.spacing).sum()) == len(pts) - 1
    assert np.asarray(paths.outcome).min() >= 0


def test_the_camera_comes_from_the_metadata(bob_grid, tmp_path):
    """BoB's ant-world camera (`opengl`): 75 deg from +60 to -15; Z (10 mm) is the camera height. A
    database that says nothing gets the assumed values with a warning naming them."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        db = load_database(bob_grid)
    assert (db.camera.elev_top_deg, db.camera.elev_bottom_deg, db.camera.height) == (60.0, -15.0, 1.0)
    bare = tmp_path / "bare"
    shutil.copytree(bob_grid, bare)
    text = (bare / "database_metadata.yaml").read_text().replace("name: opengl", "name: pixpro")
    (bare / "database_metadata.yaml").write_text(text)
    lines = (bare / "database_entries.csv").read_text().splitlines()
    (bare / "database_entries.csv").write_text(
        "\n".join([lines[0]] + [ln.replace(", 10, ", ", , ") for ln in lines[1:]])
    )
    with pytest.warns(DatabaseWarning) as seen:
        db = load_database(bare)
    said = " ".join(str(w.message) for w in seen)
    assert "+30 to -30" in said and "--elevation" in said and "25 cm" in said and "--camera-height" in said
    assert (db.camera.elev_top_deg, db.camera.height) == (30.0, 25.0)


def test_utm_millimetres_keep_their_rows(bob_grid, tmp_path):
    """Positions of a car database (UTM millimetres, ~5e8 east, ~6e9 north) keep every row and give the
    same vector map: float64 on the host, an origin before float32 (docs/images.md §4)."""
    utm = tmp_path / "utm"
    shutil.copytree(bob_grid, utm)
    lines = (utm / "database_entries.csv").read_text().splitlines()
    out = [lines[0]]
    for ln in lines[1:]:
        f = ln.split(", ")
        f[0], f[1] = repr(float(f[0]) + 512345678.0), repr(float(f[1]) + 6012345678.0)
        out.append(", ".join(f))
    (utm / "database_entries.csv").write_text("\n".join(out) + "\n")
    a, b = load_database(bob_grid, **READ), load_database(utm, **READ)
    assert len(np.unique(np.asarray(b.rings.positions)[:, 1])) == 8 and b.spacing == 20.0
    np.testing.assert_allclose(b.absolute(b.home), a.home + [51234567.8, 601234567.8], rtol=0, atol=1e-6)
    np.testing.assert_array_equal(
        np.asarray(database_vector_map(a, "alv").error_deg), np.asarray(database_vector_map(b, "alv").error_deg)
    )


# --- writing what BoB reads ----------------------------------------------------------------------------


def test_what_delvjax_writes_passes_opencv_and_bobs_reader(small_db, donut_db):
    for folder in (small_db, donut_db):
        read = bob_read(folder)
        assert read["type"] == "grid" and len(read["entries"]) == len(entries(folder))
        meta = read["metadata"]
        assert meta.getNode("delvjax").getNode("home_cm").at(0).real() == 90.0
        assert meta.getNode("headingConvention").string() == "compass"
        assert read["entries"][0]["xyz"][2] == 250.0  # Z: the camera's height


def test_import_of_a_bob_route_keeps_its_numbers_exactly(bob_route, tmp_path, capsys):
    out = tmp_path / "copy"
    assert main(["images", "import", str(bob_route), "--out", str(out), "--elevation", "30", "-30"]) == 0
    assert "route images" in capsys.readouterr().err
    read = bob_read(out)
    assert read["type"] == "route"
    src, dst = entries(bob_route), entries(out)
    assert [r["Filename"] for r in dst] == [f"image{i:05d}.png" for i in range(1, len(src) + 1)]
    for a, b in zip(src, dst):
        for k in ("X [mm]", "Y [mm]", "Z [mm]", "Heading [degrees]"):
            assert float(a[k]) == float(b[k]), (k, a[k], b[k])
    a, b = load_database(bob_route, **READ), load_database(out, max_blobs=4)
    np.testing.assert_array_equal(np.asarray(a.rings.snapshots.mask), np.asarray(b.rings.snapshots.mask))
    assert mean_error(a) == mean_error(b)


def test_writing_in_other_conventions_reads_back_the_same(bob_route, tmp_path):
    """Any declared convention round-trips: the images and headings are rewritten, the rings stay."""
    a = load_database(bob_route, **READ)
    for write_as in ({"heading": "math", "heading_column": "first"}, {"columns": "anticlockwise"}):
        out = tmp_path / "_".join(write_as.values())
        import_database(bob_route, out, write_as=write_as, **READ)
        b = load_database(out, max_blobs=4)
        np.testing.assert_array_equal(np.asarray(a.rings.snapshots.mask), np.asarray(b.rings.snapshots.mask))
        np.testing.assert_allclose(np.asarray(a.rings.headings), np.asarray(b.rings.headings), atol=1e-5)


# --- refused: one line naming the file or the choice, exit 2, nothing written -----------------------------


def _refused(argv, capsys, out: Path, *says: str) -> None:
    assert main(argv) == 2
    line = error_line(capsys)
    assert all(s in line for s in says), line
    no_leftovers(out)


def test_a_database_that_does_not_say_its_conventions_is_refused(bob_grid, tmp_path, capsys):
    bare = tmp_path / "bare"
    shutil.copytree(bob_grid, bare)
    (bare / "database_metadata.yaml").unlink()
    out = tmp_path / "out"
    _refused(["images", "import", str(bare), "--out", str(out)], capsys, out, "--heading-convention", "--columns")
    assert (
        main(
            [
                "images",
                "import",
                str(bare),
                "--out",
                str(out),
                "--heading-convention",
                "compass",
                "--heading-column",
                "centre",
                "--columns",
                "clockwise",
                "--elevation",
                "30",
                "-30",
            ]
        )
        == 0
    )


def test_conventions_that_contradict_the_database_are_refused(small_db, tmp_path, capsys):
    out = tmp_path / "out"
    argv = ["images", "import", str(small_db), "--out", str(out), "--heading-convention", "math"]
    _refused(argv, capsys, out, "--heading-convention", "headingConvention: compass")


@pytest.mark.parametrize(
    "edit, says",
    [
        (lambda rows: rows[:1], "lists no images"),
        (lambda rows: rows[:2], "route of one image"),
        (lambda rows: rows[:4] + [rows[4].replace("image_00003", "image_00002")] + rows[5:], "again"),
        (
            lambda rows: rows[:3] + [", ".join(rows[2].split(", ")[:4] + rows[3].split(", ")[4:])] + rows[4:],
            "share one position",
        ),
        (lambda rows: rows[:3] + ["nan, " + rows[3].split(", ", 1)[1]] + rows[4:], "not finite"),
    ],
    ids=["empty route", "one image", "image named twice", "two images at one place", "nan position"],
)
def test_a_bad_route_is_refused(bob_route, tmp_path, capsys, edit, says):
    bad = tmp_path / "bad"
    shutil.copytree(bob_route, bad)
    rows = (bad / "database_entries.csv").read_text().splitlines()
    (bad / "database_entries.csv").write_text("\n".join(edit(rows)) + "\n")
    out = tmp_path / "out"
    _refused(["images", "import", str(bad), "--out", str(out)], capsys, out, says, "bad")


def test_a_home_without_an_image_is_named(small_db, capsys):
    with pytest.warns(DatabaseWarning, match=r"home \(95, 90\) has no image.*5 cm away"):
        db = load_database(small_db, home=(95, 90))
    assert tuple(db.home) == (90.0, 90.0)
    assert main(["vector-map", "--images", str(small_db), "--home", "500", "500", "--summary", "s.json"]) == 2
    line = error_line(capsys)
    assert "(500, 500)" in line and "np.float64" not in line, line


def test_every_extractor_setting_is_on_the_command_line(capsys):
    with pytest.raises(SystemExit):
        main(["vector-map", "--help"])
    text = capsys.readouterr().out
    for flag in (
        "--hue-deg",
        "--hue-width-deg",
        "--sat-min",
        "--val-min",
        "--band-deg",
        "--band-height-deg",
        "--fill",
        "--max-blobs",
        "--heading-convention",
        "--columns",
        "--elevation",
        "--camera-height",
    ):
        assert flag in text, flag
