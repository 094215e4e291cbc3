"""The familiarity experiments on BoB image databases (docs/familiarity.md §3.4): a route database
written exactly as BoB writes one (tests/cases/bob.py), a grid database to test on; through the API and
the command line."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.familiarity import database_experiments
from delvjax.images import load_database
from tests.cases.bob import write_bob_database
from tests.images.test_bob import READ, bob_images, grid_points, route_points

pytest.importorskip("cv2")


@pytest.fixture(scope="module")
def bob_route(tmp_path_factory):
    pts, compass = route_points()
    xyz = np.c_[pts * 10.0, np.full(len(pts), 10.0)]
    return write_bob_database(tmp_path_factory.mktemp("bob") / "route", bob_images(pts, compass), xyz, compass, "route")


@pytest.fixture(scope="module")
def bob_grid(tmp_path_factory):
    pts = grid_points()
    xyz = np.c_[pts * 10.0, np.full(len(pts), 10.0)]
    zero = np.zeros(len(pts))
    return write_bob_database(tmp_path_factory.mktemp("bob") / "grid", bob_images(pts, zero), xyz, zero, "grid")


VIEW = {"view_rows": 6, "view_cols": 36}  # the fixtures' 12 x 72 images at half resolution


def loaded(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_database(path, panoramas=True, **READ)


def test_held_out_route_images_find_the_route_heading(bob_route):
    db = loaded(bob_route)
    r = database_experiments(db, "perfect-memory", **VIEW)
    err = np.asarray(r.field.error_deg)
    assert len(err) == len(np.asarray(db.rings.positions)) // 2  # the odd images
    assert np.median(err) < 15.0, err
    c = r.catchment_columns()
    assert len(c["image"]) == len(np.asarray(db.rings.positions)) and np.all(c["ca_size_on_route"] >= 0)


def test_a_grid_tests_every_image_and_errors_grow_away_from_the_route(bob_route, bob_grid):
    r = database_experiments(loaded(bob_route), "infomax", test_db=loaded(bob_grid), **VIEW)
    err, dist = np.asarray(r.field.error_deg), np.asarray(r.field.distance)
    assert len(err) == 64 and np.all(np.isfinite(err))
    assert np.median(err[dist <= 20.0]) < np.median(err[dist > 40.0])


def test_on_a_grid_the_route_is_followed_on_stored_views_and_noise_can_stop_it(bob_route, bob_grid):
    """BoB's camera looks back along the route (column 0 opposite the direction of travel): the agent
    moves the other way than its column 0, and still follows the route; heavy noise makes it fail."""
    route, grid = loaded(bob_route), loaded(bob_grid)
    calm = database_experiments(route, "perfect-memory", test_db=grid, trials=8, heading_noise_deg=10.0, **VIEW)
    assert abs(abs(float(calm.rules.camera_offset)) - np.pi) < 0.05
    assert calm.summary()["success_pct"] >= 75.0
    wild = database_experiments(route, "perfect-memory", test_db=grid, trials=8, heading_noise_deg=90.0, **VIEW)
    assert wild.summary()["success_pct"] < calm.summary()["success_pct"]
    assert wild.summary()["mean_route_errors"] > calm.summary()["mean_route_errors"]


def test_a_grid_database_is_no_route(bob_grid):
    with pytest.raises(InputError, match="must be a route database"):
        database_experiments(loaded(bob_grid), "perfect-memory", **VIEW)


def test_the_command_runs_on_a_route_database(bob_route, bob_grid, tmp_path, capsys):
    out, summary = tmp_path / "f.csv", tmp_path / "s.json"
    argv = ["familiarity", "--images", str(bob_route), "--test-images", str(bob_grid), "--model", "mushroom-body",
            "--n-kc", "2000", "--n-active", "20", "--view-rows", "6", "--view-cols", "36", "--trials", "3",
            "--out", str(out), "--summary", str(summary), "--catchments-out", str(tmp_path / "c.csv"),
            "--plot", str(tmp_path / "p.png")]  # fmt: skip
    assert main(argv) == 0
    s = json.loads(summary.read_text())
    assert s["trials"] == 3 and s["success_pct"] is not None and s["field_points"] == 64
    assert (tmp_path / "p.png").stat().st_size > 10000
    assert "route_image_heading_deg" in out.read_text().splitlines()[0]
    assert "success" in capsys.readouterr().out
    assert main(["familiarity", "robot", "--images", str(bob_route), "--out", str(tmp_path / "g.csv")]) == 2
    assert main(["familiarity", "--images", str(bob_route), "--step", "3", "--out", str(tmp_path / "g.csv")]) == 2
    assert not (tmp_path / "g.csv").exists()
