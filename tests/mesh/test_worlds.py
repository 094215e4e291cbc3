"""Mesh worlds (docs/mesh.md §3-4): the Seville world's file forms read alike (written here in their layouts, not
shipped), bad files refused in one line naming the file, the generated habitat reproducible and clear of its
route; and, where the user has the Seville files (DELVJAX_ANTWORLD=folder), the render close to test_img.mat."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from scipy.io import savemat

from delvjax.core.errors import InputError
from delvjax.mesh import Eye, habitat, mesh_world, panoramas, read_mesh, read_route
from delvjax.mesh._habitat import distance_to


def seville_like(n=40, seed=0):
    """X, Y, Z, colp (n, 3) in metres: blades with two ground corners 0.1 m apart, some apexes below ground."""
    rng = np.random.default_rng(seed)
    base = rng.uniform(0, 10, (n, 2))
    x = np.c_[base[:, 0], base[:, 0] + 0.1, base[:, 0] + rng.normal(0, 0.05, n)]
    y = np.c_[base[:, 1], base[:, 1], base[:, 1] + rng.normal(0, 0.05, n)]
    z = np.c_[np.zeros(n), np.zeros(n), rng.uniform(-0.2, 0.6, n)]
    colp = np.repeat(rng.uniform(0.07, 0.98, (n, 1)), 3, 1)
    return x, y, z, colp


def test_the_mat_and_bin_forms_read_alike_in_cm(tmp_path):
    x, y, z, colp = seville_like()
    savemat(tmp_path / "w.mat", {"X": x, "Y": y, "Z": z, "colp": colp})
    np.concatenate([x, y, z, colp], 1).T.astype("<f8").tofile(tmp_path / "w.bin")  # column-major (T, 12)
    a, b = read_mesh(tmp_path / "w.mat"), read_mesh(tmp_path / "w.bin")
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_allclose(a.vertices[:, 1, 0] - a.vertices[:, 0, 0], 10.0)  # 0.1 m -> 10 cm
    assert (a.vertices[..., 2] >= 0).all() and (read_mesh(tmp_path / "w.mat", abs_z=False).vertices[..., 2] < 0).any()
    np.testing.assert_array_equal(a.shade, colp[:, 0])


def test_routes_and_obj_meshes(tmp_path):
    r = np.c_[np.arange(5.0) * 10 + 600, np.full(5, 800.0), np.full(5, 90.0)]
    savemat(tmp_path / "AntRoutes.mat", {"Ant1_Route1": r})
    r.T.astype("<f8").tofile(tmp_path / "ant1_route1.bin")
    for f in ("AntRoutes.mat", "ant1_route1.bin"):
        got = read_route(tmp_path / f)
        np.testing.assert_allclose(got, np.c_[r[:, :2], np.full(5, np.pi / 2)])
    (tmp_path / "q.obj").write_text("# a square\nv 0 0 0\nv 10 0 0\nv 10 10 5\nv 0 10 5\nf 1 2 3 4\n")
    m = read_mesh(tmp_path / "q.obj")
    assert m.vertices.shape == (2, 3, 3) and m.shade.tolist() == [0.5, 0.5]


@pytest.mark.parametrize(
    "content, says",
    [
        ("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "is degenerate"),
        ("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite vertex"),
        ("v 0 0 0\n", "holds no triangle"),
        ("v 0 0 0\nf 1 2 7\n", "names vertex 7"),
        ("v 0 0 zero\n", "cannot be read"),
    ],
)
def test_a_bad_mesh_is_refused_naming_it(tmp_path, content, says):
    (tmp_path / "m.obj").write_text(content)
    with pytest.raises(InputError, match=says):
        read_mesh(tmp_path / "m.obj")


def test_a_file_of_another_format_is_refused(tmp_path):
    (tmp_path / "w.mat").write_text("not matlab")
    (tmp_path / "w.bin").write_bytes(b"\0" * 40)
    (tmp_path / "w.png").write_bytes(b"\0")
    for name, says in (("w.mat", "not a MATLAB"), ("w.bin", "not 12 a triangle"), ("w.png", "must be a .mat")):
        with pytest.raises(InputError, match=says):
            read_mesh(tmp_path / name)
    with pytest.raises(InputError, match="not 3 a point"):
        read_route(tmp_path / "w.bin")


def test_the_habitat_is_seeded_and_its_route_passes_between_the_tussocks():
    a, b, c = habitat(3), habitat(3), habitat(4)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    assert not np.array_equal(a.vertices[:100], c.vertices[:100])
    blades = a.vertices[: 250 * 20]
    assert blades.shape[0] == 5000 and 12 < np.median(blades[:, 2, 2]) < 25
    assert distance_to(blades[:, :2, :2].reshape(-1, 2), a.route).min() > 25.0
    step = np.hypot(*np.diff(a.route[:, :2], axis=0).T)
    assert np.allclose(step[:-1], 1.0, atol=1e-6) and a.route.shape[0] > 700


def test_a_route_view_shows_grass_ground_and_sky():
    h = habitat(0)
    world = mesh_world(h)
    pose = [*h.route[0, :2], 1.0, h.route[0, 2]]
    img = panoramas(world, pose)[0]
    assert img.shape == (19, 74, 3)
    sky = np.all(np.isclose(img, [0, 1, 1]), -1)
    ground = np.all(np.isclose(img, [229 / 255, 183 / 255, 90 / 255]), -1)
    grass = ~sky & ~ground
    assert sky.mean() > 0.3 and ground.mean() > 0.1 and grass.mean() > 0.05
    wide = panoramas(world, pose, Eye(rows=45, cols=180, elev_top_deg=60.0, elev_bottom_deg=-30.0))
    assert wide.shape == (1, 45, 180, 3)


@pytest.mark.parametrize("poses, field", [([[0, 0, 1, np.nan]], "poses[0]"), ([[0, 0, 1]], "poses")])
def test_bad_poses_are_refused(poses, field):
    world = mesh_world(habitat(0, tussocks=5, blades=2, trees=0))
    with pytest.raises(InputError) as exc:
        panoramas(world, poses)
    assert exc.value.field == field


SEVILLE = os.environ.get("DELVJAX_ANTWORLD")


@pytest.mark.skipif(
    not SEVILLE, reason="set DELVJAX_ANTWORLD to a folder with world5000_gray.mat, AntRoutes.mat, test_img.mat"
)
def test_the_seville_render_is_close_to_test_img():
    """InvertSy's reference render (a MATLAB z-buffer, docs/mesh.md §3): at Ant1_Route1's first point, 1 cm high,
    heading -1.3035 deg (Example.m divides the heading by 100 too), 74 columns at 296 / 75 deg from +146 deg on the
    left: at least 88 % of pixels equal and 93 % of the same kind (sky, ground, grass)."""
    from scipy.io import loadmat

    folder = Path(SEVILLE)
    world = mesh_world(read_mesh(folder / "world5000_gray.mat"))
    x, y, _ = read_route(folder / "AntRoutes.mat")[0]
    eye = Eye(rows=19, cols=74, width_deg=74 * 296 / 75, elev_top_deg=60.0, elev_bottom_deg=-15.0)
    img = panoramas(world, [x, y, 1.0, np.radians(-1.3035)], eye)[0][:, ::-1]  # MATLAB's columns run clockwise
    got = np.round(img * 255).astype(int)
    ref = loadmat(folder / "test_img.mat")["test_img"].astype(int)
    kind = lambda a: np.where(np.all(a == [0, 255, 255], -1), 0, np.where(np.all(a == [229, 183, 90], -1), 1, 2))  # noqa: E731
    assert np.mean(np.all(got == ref, -1)) >= 0.88
    assert np.mean(kind(got) == kind(ref)) >= 0.93
