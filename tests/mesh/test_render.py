"""The mesh renderer (docs/mesh.md §2) against the plain NumPy ray caster (tests/twins/mesh.py): pixel for pixel
on meshes of a few hundred random triangles at poses with pitch and roll, full and partial eyes, apart from
pixels whose ray passes within a tolerance of a triangle's edge."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.core.mesh.eye import ANT_EYE, Eye
from delvjax.core.mesh.mesh import make_mesh
from delvjax.core.mesh.render import mesh_panorama, mesh_panoramas
from tests.twins import mesh as twin


def random_mesh(seed: int, n: int = 300):
    """Triangles of every size: blades near the eye, far small ones, a few large slabs overhead and across."""
    rng = np.random.default_rng(seed)
    centre = np.concatenate([rng.uniform(-300, 300, (n, 2)), rng.uniform(0, 40, (n, 1))], -1)
    size = np.exp(rng.uniform(np.log(2.0), np.log(80.0), (n, 1, 1)))
    v = centre[:, None, :] + size * rng.normal(size=(n, 3, 3))
    v[:3] = [[[-50, -50, 60], [50, -40, 70], [0, 60, 65]], [[-400, 30, 0], [400, 40, 5], [0, 35, 90]],
             [[20, -3, 0], [25, 3, 0], [22, 0, 15]]]  # fmt: skip  # overhead, a wall across, a blade at the eye
    rgb = np.stack([np.arange(n) / n, rng.uniform(size=n), rng.uniform(size=n)], -1)
    return v, rgb


EYES = [
    Eye(rows=18, cols=72),
    ANT_EYE,
    Eye(rows=12, cols=40, width_deg=200.0, elev_top_deg=80.0, elev_bottom_deg=-80.0),
]


@pytest.mark.parametrize("e", range(len(EYES)))
@pytest.mark.parametrize("seed", [0, 1])
def test_the_panorama_is_the_ray_casters_pixel_for_pixel(e, seed):
    v, rgb = random_mesh(seed)
    eye = EYES[e]
    ground, sky = np.array([0.9, 0.7, 0.35]), np.array([0.0, 1.0, 1.0])
    mesh = make_mesh(v, rgb, ground_rgb=ground, sky_rgb=sky)
    rng = np.random.default_rng(seed + 10)
    for pose in ([0.0, 0.0, 1.0, 0.3, 0.0, 0.0], [5.0, -8.0, 12.0, -2.0, 0.2, -0.15]):
        pose = np.asarray(pose) + np.r_[rng.normal(0, 3, 2), 0, 0, 0, 0]
        got = np.asarray(mesh_panorama(mesh, eye, pose))
        want, near = twin.render(v, rgb, ground, sky, pose, eye.rows, eye.cols, eye.width_deg, eye.elev_top_deg,
                                 eye.elev_bottom_deg)  # fmt: skip
        differ = np.any(np.abs(got - want) > 1e-6, -1)
        assert not np.any(differ & ~near), np.argwhere(differ & ~near)[:5].tolist()
        assert near.mean() < 0.05
        kinds = {tuple(c) for c in want.reshape(-1, 3).round(6)}
        assert len(kinds) > 10  # many triangles, the ground and the sky are seen: a test that could fail


def test_poses_in_a_batch_are_the_poses_one_at_a_time():
    v, rgb = random_mesh(3)
    mesh = make_mesh(v, rgb)
    poses = np.array([[0.0, 0.0, 1.0, 0.0], [10.0, 5.0, 2.0, 1.0], [-20.0, 7.0, 5.0, -2.5]], np.float32)
    batch = np.asarray(mesh_panoramas(mesh, ANT_EYE, poses, batch=2))
    for p, img in zip(poses, batch):
        np.testing.assert_array_equal(img, np.asarray(mesh_panorama(mesh, ANT_EYE, p)))
