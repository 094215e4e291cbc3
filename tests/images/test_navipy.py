"""navipy interop (docs/images.md §9, docs/navipy.md): `to_navipy` and `from_navipy` are exact inverses, a
landmark lands at navipy's own azimuth and elevation for its direction, and navipy's rotational image
difference gives delvjax's visual-compass answer on the same rings.

navipy (0.1.2) is not a test extra (its install_requires pull in tables, opencv-python, sphinx, ...): the
tests that call it skip when it is not installed. Checked by hand: with `to_navipy` mirroring the columns
(delvjax's file order) `test_rotational_image_difference_matches_visual_compass` fails; without its row
flip, or without its roll by W // 2, `test_landmark_lands_at_navipy_direction` fails.
"""

from __future__ import annotations

import logging
import math
import warnings
from types import SimpleNamespace

import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.methods.heading import visual_compass
from delvjax.images import from_navipy, to_navipy


def _wrap_deg(a):
    """Angles (deg) to (-180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(a, np.float64), 360.0)


def _navipy(module: str = "navipy.comparing"):
    """A navipy module, or skip (navipy is not a test extra; docs/navipy.md)."""
    with warnings.catch_warnings():  # navipy.sensors.renderer warns that Blender's bpy is missing
        warnings.simplefilter("ignore")
        return pytest.importorskip(module)


# --- (a) the two functions, no navipy needed ---------------------------------------------------------------


@pytest.mark.parametrize("shape", [(5, 7, 3), (6, 8, 3), (1, 9, 3), (2, 3, 4, 10, 3)])
@pytest.mark.parametrize("dtype", [np.uint8, np.float32])
def test_round_trip_is_identity(shape, dtype):
    rng = np.random.default_rng(sum(shape))
    pano = (rng.integers(0, 256, shape) if dtype is np.uint8 else rng.random(shape)).astype(dtype)
    scene = to_navipy(pano)
    assert scene.shape == shape[:-1] + (4, 1) and scene.dtype == dtype
    back = from_navipy(scene)
    assert back.dtype == dtype and np.array_equal(back, pano)
    # and the other way: a navipy scene with its distance channel survives from_navipy -> to_navipy
    s = rng.random(shape[:-1] + (4, 1)).astype(dtype)
    assert np.array_equal(to_navipy(from_navipy(s, distance=True)), s)
    d = rng.random(shape[:-1]).astype(dtype)
    assert np.array_equal(from_navipy(to_navipy(pano.astype(np.float32), d), distance=True)[..., 3], d)


@pytest.mark.parametrize("width", [7, 8])
def test_pixel_goes_where_docs_say(width):
    """delvjax pixel (i, j) -> navipy row H - 1 - i, column (j + W // 2) mod W (docs/navipy.md)."""
    h = 5
    for i, j in [(0, 0), (1, 3), (4, width - 1)]:
        pano = np.zeros((h, width, 3), np.float32)
        pano[i, j] = 1.0
        r, c = np.argwhere(to_navipy(pano)[..., 0, 0] == 1.0)[0]
        assert (r, c) == (h - 1 - i, (j + width // 2) % width)


def test_refuses_wrong_shapes():
    with pytest.raises(ValueError):
        to_navipy(np.zeros((4, 5, 2)))
    with pytest.raises(ValueError):
        to_navipy(np.zeros((4, 5, 4)), distance=1.0)
    with pytest.raises(ValueError):
        from_navipy(np.zeros((4, 5, 3, 1)))


# --- (b) navipy's own viewing directions ----------------------------------------------------------------------


def _navipy_viewing_directions(height: int, width: int, elevation_deg, azimuth_deg) -> np.ndarray:
    """navipy's own (H, W, 2) [elevation, azimuth] of every scene pixel (deg): the property
    `BlenderRender.viewing_directions` (navipy/sensors/renderer.py) run on a stand-in for Blender's camera."""
    renderer = _navipy("navipy.sensors.renderer")
    scene_index = _navipy("navipy.scene")
    camera = SimpleNamespace(
        _logger=logging.getLogger("navipy"),
        camera_resolution=(width, height),
        camera_fov=np.array([elevation_deg, azimuth_deg], np.float64),
    )
    vd = renderer.BlenderRender.viewing_directions.fget(camera)
    idx = scene_index.__spherical_indeces__
    return np.stack([vd[..., idx["elevation"]], vd[..., idx["azimuth"]]], axis=-1)


@pytest.mark.parametrize("width", [72, 73])
def test_landmark_lands_at_navipy_direction(width):
    """A landmark at delvjax row i (elevation 30 - (i + 1/2) deg, docs/images.md §2's default camera) and
    column j (bearing 360 j / W) appears in the navipy scene at navipy's elevation and azimuth for that
    direction, within one pixel (navipy spaces its directions by linspace, 1/(W-1) of the range)."""
    h, top, bottom = 60, 30.0, -30.0
    vd = _navipy_viewing_directions(h, width, (bottom, top), (-180.0, 180.0))
    for i, j in [(3, 0), (10, 5), (20, width // 4), (47, width // 2), (55, width - 7)]:
        pano = np.zeros((h, width, 3), np.float32)
        pano[i, j] = 1.0
        r, c = np.argwhere(to_navipy(pano)[..., 0, 0] == 1.0)[0]
        elevation = top - (i + 0.5) * (top - bottom) / h
        bearing = 360.0 * j / width
        assert abs(vd[r, c, 0] - elevation) <= (top - bottom) / (h - 1), (i, j, vd[r, c], elevation)
        assert abs(_wrap_deg(vd[r, c, 1] - bearing)) <= 360.0 / (width - 1), (i, j, vd[r, c], bearing)


# --- (c) navipy's rotational image difference vs delvjax's visual compass -------------------------------------


def _ring(rng: np.random.Generator, width: int, turn_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """A smooth random gray ring seen at home and after the agent turned `turn_deg` counter-clockwise on the
    spot: current pixel j looks along home angle 360 j / W + turn (docs/model.md §2.2), sampled exactly."""
    m = np.arange(1, 9)
    amp, phase = rng.random(8) / m, rng.random(8) * 2 * np.pi
    phi = 2 * np.pi * np.arange(width) / width

    def g(a):
        return 0.5 + 0.25 * np.sum(amp * np.cos(np.outer(a, m) + phase), axis=-1)

    return g(phi), g(phi + math.radians(turn_deg))


@pytest.mark.parametrize(
    "width, turn_deg, seed",
    [(360, 37.0, 0), (360, -123.4, 1), (360, 90.0, 2), (360, 180.0, 3), (97, 200.0, 4), (96, 12.5, 5), (64, 0.0, 6)],
)
def test_rotational_image_difference_matches_visual_compass(width, turn_deg, seed):
    comparing = _navipy("navipy.comparing")
    home, current = _ring(np.random.default_rng(seed), width, turn_deg)
    pixel = 360.0 / width
    compass_deg = math.degrees(float(visual_compass(jnp.asarray(home, jnp.float32), jnp.asarray(current, jnp.float32))))

    # the same rings as 1-row gray panoramas, in navipy's frame (float: navipy subtracts in the array's dtype)
    def scene(ring):
        return to_navipy(np.repeat(ring[None, :, None], 3, axis=-1))

    ridf = comparing.rot_imagediff(scene(current), scene(home))  # (W, 4): per rotation, per channel
    best = int(np.argmin(ridf[:, 0]))
    # rot_imagediff rolls the current view by -best columns, a counter-clockwise turn by `best` pixels that
    # brings it onto the memory: the agent is `best` pixels clockwise of home, h - alpha_r = -best pixels.
    navipy_deg = -best * pixel
    assert abs(_wrap_deg(navipy_deg - compass_deg)) <= pixel, (navipy_deg, compass_deg)
    assert abs(_wrap_deg(compass_deg - turn_deg)) <= pixel, (compass_deg, turn_deg)
