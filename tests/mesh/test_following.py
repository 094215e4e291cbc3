"""Familiarity on mesh worlds (docs/mesh.md §6-7): the views a model reads (the green channel, turned by whole
rendered columns, block-averaged), the route experiments on a habitat and on the user's files from the API and
the CLI, mesh databases in BoB's layout read back, and bad input refused in one line with nothing written."""

from __future__ import annotations

import json

import jax.numpy as jnp
import numpy as np
import pytest
from PIL import Image

from delvjax.cli import main
from delvjax.core.errors import InputError
from delvjax.core.familiarity.following import MeshViews
from delvjax.core.familiarity.mesh_views import mesh_camera
from delvjax.core.images import to_uint8
from delvjax.core.mesh.render import mesh_panorama
from delvjax.core.polyline import headings_along, resample
from delvjax.familiarity import route_experiments
from delvjax.familiarity._setup import any_world
from delvjax.images import load_database
from delvjax.mesh import habitat, mesh_world, render_mesh_database
from delvjax.mesh._site import MeshSite, site
from delvjax.sweeps._kinds.route_following import following_world

SMALL = dict(seed=5, size=300.0, tussocks=30, blades=8, trees=1)
RUN = ["--view-rows", "4", "--trials", "2", "--max-steps", "30", "--grid-spacing", "60", "--route-spacing", "8"]


@pytest.fixture(scope="module")
def small():
    h = habitat(**SMALL)
    return h, site(h, mesh_world(h), h.route, h.arena, "small")


@pytest.fixture(scope="module")
def files(small, tmp_path_factory):
    """The small habitat written as bob_robotics' world .bin (metres, column-major) and route .bin (deg)."""
    h, _ = small
    d = tmp_path_factory.mktemp("files")
    v = h.vertices / 100.0
    colp = np.repeat(h.shade[:, None], 3, 1)
    np.concatenate([v[..., 0], v[..., 1], v[..., 2], colp], 1).T.astype("<f8").tofile(d / "world.bin")
    np.c_[h.route[:, :2], np.degrees(h.route[:, 2])].T.astype("<f8").tofile(d / "route.bin")
    return d


def test_a_turn_rolls_the_green_panorama_by_whole_columns(small):
    _, s = small
    mc = mesh_camera(4, 90, 2, 1.0)
    views = MeshViews(s.mesh, mc, jnp.asarray(s.arena))
    x, h = jnp.asarray(s.route[40, :2], jnp.float32), jnp.float32(0.7)
    col = 2 * np.pi / mc.eye.cols
    turns = jnp.asarray([0.0, 3 * col, -5 * col], jnp.float32)
    got = np.asarray(views(x, h, turns))
    pano = np.asarray(mesh_panorama(s.mesh, mc.eye, jnp.array([x[0], x[1], 1.0, h])))
    green = np.asarray(to_uint8(jnp.asarray(pano[..., 1])), np.float64)
    for k, turn in zip((0, 3, -5), got):
        want = np.roll(green, -k, axis=1).reshape(4, 2, 90, 2).mean((1, 3))  # a left turn: the panorama moves left
        np.testing.assert_allclose(turn, want, atol=1e-4)
    turned = np.asarray(mesh_panorama(s.mesh, mc.eye, jnp.array([x[0], x[1], 1.0, h + 3 * col])))
    same = np.mean(np.asarray(to_uint8(jnp.asarray(turned[..., 1]))) == np.roll(green, -3, axis=1))
    assert same > 0.97  # rendering facing the turned heading: the same view but for pixels on an edge
    assert len(np.unique(green)) > 3  # grass, ground and sky are seen


def test_route_experiments_run_on_a_mesh_site_and_repeat(small):
    _, s = small
    kw = dict(trials=2, heading_noise_deg=20.0, route_spacing=8.0, view_rows=4, grid_spacing=60.0, max_steps=60)
    a = route_experiments(s, "perfect-memory", **kw)
    points = resample(s.waypoints(), 8.0)
    assert a.route.n_images == len(points) and a.route.views.shape[1:] == (4, 90)
    np.testing.assert_allclose(np.asarray(a.route.route.headings), headings_along(points), atol=1e-6)
    summary = a.summary()
    assert summary["settings"]["eye_height_cm"] == 1.0 and "recorded route" in summary["settings"]["route"]
    assert summary["trials"] == 2 and np.isfinite(summary["median_error_deg_all"])
    assert a.footprint.shape == (len(s.mesh.vertices), 3, 2)
    near = np.asarray(a.field.distance) <= 20
    assert near.any() and np.median(np.asarray(a.field.error_deg)[near]) < 45  # on the route it faces along it
    b = route_experiments(s, "perfect-memory", **kw)
    np.testing.assert_array_equal(np.asarray(a.trials.path), np.asarray(b.trials.path))
    points_far = np.asarray(a.field.distance) > 60
    assert np.median(np.asarray(a.field.value)[points_far]) > np.median(np.asarray(a.field.value)[near])


def test_the_cli_runs_the_users_mesh_files_and_writes_databases_bob_reads(files, small, tmp_path):
    summary = tmp_path / "s.json"
    args = ["familiarity", "--mesh", str(files / "world.bin"), "--ant-route", str(files / "route.bin")]
    assert main([*args, *RUN, "--summary", str(summary), "--plot", str(tmp_path / "f.png")]) == 0
    s = json.loads(summary.read_text())
    assert s["world"] == "world:route" and s["trials"] == 2 and (tmp_path / "f.png").stat().st_size > 10_000
    db = tmp_path / "db"
    mesh = ["--mesh", str(files / "world.bin"), "--ant-route", str(files / "route.bin")]
    assert main(["images", "render-db", *mesh, "--kind", "route", "--spacing", "20", "--rows", "8", "--cols", "36",
                 "--out", str(db)]) == 0  # fmt: skip
    loaded = load_database(db, panoramas=True)
    assert loaded.kind == "route" and (db / "image00001.png").is_file()
    first = np.asarray(Image.open(db / "image00001.png"))
    assert np.array_equal(first[..., 0], first[..., 1]) and np.array_equal(first[..., 1], first[..., 2])  # green
    points = resample(small[1].waypoints(), 20.0)
    np.testing.assert_allclose(np.asarray(loaded.rings.positions), points, atol=0.01)
    assert loaded.rings.snapshots.panorama.shape[1:] == (8, 36)


@pytest.mark.parametrize(
    "argv, says",
    [
        (["familiarity", "habitat0", "--mesh", "{w}", "--summary", "{j}"], "not both"),
        (["familiarity", "--mesh", "{w}", "--summary", "{j}"], "go together"),
        (["familiarity", "--mesh", "{w}", "--ant-route", "{far}", "--summary", "{j}"], "leaves the world"),
        (["familiarity", "--mesh", "{r}", "--ant-route", "{r}", "--summary", "{j}"], "--mesh"),
        (["familiarity", "habitatx", "--summary", "{j}"], "habitat<seed>"),
        (["images", "render-db", "habitat0", "--donut", "--out", "{o}"], "--donut"),
        (["images", "render-db", "habitat0", "--pixel-noise", "0.1", "--out", "{o}"], "--pixel-noise"),
        (["images", "render-db", "robot", "--kind", "route", "--out", "{o}"], "--kind"),
        (["images", "render-db", "robot", "--colour", "--out", "{o}"], "--colour"),
        (["images", "render-db", "--mesh", "{w}", "--ant-route", "{far}", "--out", "{o}"], "leaves the world"),
    ],
)
def test_bad_mesh_input_is_one_line_and_writes_nothing(argv, says, files, tmp_path, capsys):
    far = tmp_path / "far.bin"
    r = np.fromfile(files / "route.bin", "<f8").reshape(3, -1)
    r[0] += 5000.0  # 50 m east: outside the world
    r.astype("<f8").tofile(far)
    (tmp_path / "r.bin").write_bytes(b"\0" * 24)  # 3 doubles: not a world .bin
    out = tmp_path / "out"
    fill = {"w": str(files / "world.bin"), "far": str(far), "r": str(tmp_path / "r.bin"), "o": str(out),
            "j": str(tmp_path / "s.json")}  # fmt: skip
    assert main([a.format(**fill) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and says in err[0], err
    assert (not out.exists() or not any(out.iterdir())) and not (tmp_path / "s.json").exists()


def test_worlds_by_name():
    assert isinstance(any_world("habitat3"), MeshSite) and any_world("habitat").name == "habitat0"
    assert isinstance(following_world("habitat2", lambda n: n), MeshSite)
    with pytest.raises(InputError, match="habitat<seed>"):
        any_world("habitat_x")


def test_the_studys_starts_lie_on_the_route_before_the_nest():
    from delvjax.studies.runs.ant_world import starts_before_nest

    route = np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 50.0]])  # 150 cm: east, then north
    xy, heading = starts_before_nest(route, [20.0, 50.0, 120.0, np.inf])
    np.testing.assert_allclose(xy, [[100.0, 30.0], [100.0, 0.0], [30.0, 0.0], [0.0, 0.0]], atol=1e-9)
    np.testing.assert_allclose(heading, [np.pi / 2, np.pi / 2, 0.0, 0.0], atol=1e-9)


@pytest.mark.parametrize(
    "kw, field",
    [({"spacing": 0.01}, "spacing"), ({"kind": "route", "band": 5.0}, "band"), ({"band": -1.0}, "band"),
     ({"kind": "circle"}, "kind"), ({"rows": 0}, "rows")],
)  # fmt: skip
def test_a_mesh_database_is_checked_before_any_work(kw, field, small, tmp_path):
    with pytest.raises(InputError) as e:
        render_mesh_database(small[1], tmp_path / "db", **kw)
    assert e.value.field == field and not (tmp_path / "db").exists()
