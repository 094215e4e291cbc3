"""Rendering and the image pipeline (docs/images.md §2-5) against their NumPy twin (twins/images.py)
and analytic cases: ray casting, cameras, unwrapping, HSV, thresholds, bands, blobs."""

from __future__ import annotations

import colorsys
import math

import equinox as eqx
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.images import pipeline, render
from delvjax.core.images.world import Camera, Catadioptric, make_world
from delvjax.images._worlds import image_world
from tests.twins import images as ref
from tests.twins.sensing import wrap

RED = (0.8, 0.1, 0.1)
panorama = eqx.filter_jit(render.panorama)
panoramas = eqx.filter_jit(render.panoramas)
donut = eqx.filter_jit(render.donut)
unwrap = eqx.filter_jit(pipeline.unwrap)
call_method = eqx.filter_jit(lambda method, home, view: method(home, view))
extract = eqx.filter_jit(
    lambda extractor, image, cam: extractor(pipeline.to_uint8(image).astype(jnp.float32) / 255.0, cam)
)


def _random_world(rng):
    """2-4 cylinders and 0-2 boxes (padded to 4 and 3) of random colours in a 600 cm arena, random light."""
    cyl = [(*rng.uniform(100, 500, 2), rng.uniform(10, 40), rng.uniform(20, 150)) for _ in range(rng.integers(2, 5))]
    boxes = []
    for _ in range(rng.integers(0, 3)):
        x0, y0 = rng.uniform(100, 450, 2)
        boxes.append((x0, y0, x0 + rng.uniform(20, 80), y0 + rng.uniform(20, 80), rng.uniform(20, 150)))
    cyl += [(0.0,) * 4] * (4 - len(cyl))
    boxes += [(0.0,) * 5] * (3 - len(boxes))
    return (
        make_world(
            cylinders=cyl,
            cylinder_rgb=rng.uniform(0, 1, (4, 3)),
            boxes=boxes,
            box_rgb=rng.uniform(0, 1, (3, 3)),
            arena=(0.0, 0.0, 600.0, 600.0),
            wall_height=rng.uniform(40, 200),
            light_azimuth_deg=rng.uniform(0, 360),
            light_elevation_deg=rng.uniform(10, 80),
            ambient=rng.uniform(0.2, 0.6),
            texture=rng.uniform(0, 1),
        ),
        np.array(cyl),
        np.array(boxes),
    )


def _free_poses(rng, cyl, boxes, n):
    """n poses in the arena outside every object (by 2 cm), random headings."""
    out = []
    while len(out) < n:
        p = rng.uniform(20, 580, 2)
        if any(h > 0 and math.hypot(p[0] - x, p[1] - y) < r + 2 for x, y, r, h in cyl):
            continue
        if any(b[4] > 0 and b[0] - 2 < p[0] < b[2] + 2 and b[1] - 2 < p[1] < b[3] + 2 for b in boxes):
            continue
        out.append(p)
    return np.array(out), rng.uniform(0, 2 * np.pi, n)


# ----------------------------------------------------------------------------- §3 ray casting
def _natural_padded():
    """The natural world (1 cylinder, 3 boxes) padded to the random worlds' shape (4 cylinders)."""
    w = image_world("natural").world
    pad = lambda a: jnp.concatenate([a, jnp.zeros((3, a.shape[1]))])  # noqa: E731
    return eqx.tree_at(lambda v: (v.cylinders, v.cylinder_rgb), w, (pad(w.cylinders), pad(w.cylinder_rgb)))


def test_panorama_of_random_worlds_matches_reference():
    rng = np.random.default_rng(0)
    cam = Camera(height=30.0, elev_top_deg=40.0, elev_bottom_deg=-35.0, rows=12, cols=48)
    cases = []
    for _ in range(4):
        world, cyl, boxes = _random_world(rng)
        cases.append((world, *_free_poses(rng, cyl, boxes, 2)))
    cases.append((_natural_padded(), np.array([[500.0, 500.0], [450.0, 250.0]]), np.array([0.3, 2.0])))
    differ, total, objects = 0, 0, 0
    for world, pos, hd in cases:
        wd = ref.world_dict(world)
        bare = dict(wd, cylinders=wd["cylinders"] * [1, 1, 1, 0], boxes=wd["boxes"] * [1, 1, 1, 1, 0])
        got = np.asarray(panoramas(world, cam, jnp.asarray(pos, jnp.float32), jnp.asarray(hd, jnp.float32)))
        for p, h, g in zip(pos, hd, got):
            want = ref.panorama(wd, p, h, cam.rows, cam.cols, cam.height, cam.elev_top_deg, cam.elev_bottom_deg)
            bad = np.abs(g - want).max(-1) > 1e-4
            differ += int(bad.sum())
            total += bad.size
            # pixels showing an object: they differ from the same world without objects
            empty = ref.panorama(bare, p, h, cam.rows, cam.cols, cam.height, cam.elev_top_deg, cam.elev_bottom_deg)
            objects += int(np.sum(np.abs(want - empty).max(-1) > 1e-6))
    assert objects > 0.05 * total, objects / total  # the objects are seen (measured: 12% of the pixels)
    assert differ <= 0.01 * total, differ / total  # measured: no pixel differs by more than 1e-4 (max 1.3e-5)


@pytest.mark.parametrize(
    "dist, radius, height, bearing_deg, heading_deg",
    [(100.0, 8.0, 60.0, 0.0, 0.0), (140.0, 15.0, 75.0, 100.0, 30.0), (260.0, 30.0, 60.0, 250.0, 0.0)],
)
def test_one_cylinder_has_its_analytic_size(dist, radius, height, bearing_deg, heading_deg):
    """Columns covered: 2 asin(r / D) (within one pixel) about column (bearing - heading) (counter-clockwise);
    rows: from the top edge at atan((H - h_c) / (D - r)) down to the foot at -atan(h_c / (D - r)), 1 deg per
    row with row centres at half degrees (the cases put both edges 0.15-0.35 deg past a whole degree, so a
    half-row error in the elevations fails)."""
    b = math.radians(bearing_deg)
    world = make_world(
        cylinders=[(500.0 + dist * math.cos(b), 500.0 + dist * math.sin(b), radius, height)],
        cylinder_rgb=[RED],
        arena=(0.0, 0.0, 1000.0, 1000.0),
        wall_height=40.0,
    )
    cam = Camera()  # 60 rows from +30 to -30 deg, 360 columns: 1 deg per pixel
    img = panorama(world, cam, jnp.array([500.0, 500.0]), jnp.float32(math.radians(heading_deg)))
    mask = np.asarray(pipeline.segment(pipeline.rgb_to_hsv(img), 0.0, 40.0, 0.5, 0.15))
    cols = np.flatnonzero(mask.any(0))
    half = math.degrees(math.asin(radius / dist))
    assert abs(len(cols) - 2 * half) <= 1.0, (len(cols), 2 * half)
    centre = bearing_deg - heading_deg
    assert np.degrees(np.abs(wrap(np.radians(cols - centre)))).max() <= half + 1.0, cols
    rows = np.flatnonzero(mask[:, int(round(centre)) % cam.cols])
    top = math.degrees(math.atan((height - cam.height) / (dist - radius)))
    foot = -math.degrees(math.atan(cam.height / (dist - radius)))
    assert rows.min() == math.ceil(30.0 - top - 0.5)  # the first row centre at or below the top edge
    assert rows.max() == math.floor(30.0 - foot - 0.5)  # the last row centre at or above the foot
    assert len(rows) == rows.max() - rows.min() + 1


def test_donut_matches_reference_and_unwraps_to_the_panorama():
    """The robot world's donut equals the reference at sampled pixels, and unwrapped it equals the panorama
    rendered directly (mean abs difference measured 0.0045-0.0048; a mirrored azimuth gives 0.12-0.14, a roll by
    3 columns 0.03, upside down 0.20)."""
    iw = image_world("robot")
    wd = ref.world_dict(iw.world)
    cam, mirror = Camera(), Catadioptric()
    rng = np.random.default_rng(8)
    for pos, h in (((90.0, 90.0), 0.0), ((90.0, 90.0), 0.7), ((30.0, 160.0), 4.0)):
        img = donut(iw.world, mirror, jnp.asarray(pos, jnp.float32), jnp.float32(h))
        pixels = rng.integers(0, mirror.size, (150, 2))
        want = np.array([ref.donut_pixel(wd, pos, h, mirror.size, r, c) for r, c in pixels])
        got = np.asarray(img)[pixels[:, 0], pixels[:, 1]]
        assert (np.abs(got - want).max(-1) > 1e-4).sum() <= 2  # measured: none
        assert (want.max(-1) == 0).sum() > 10  # some samples fall on the black centre or rim
        pan = np.asarray(panorama(iw.world, cam, jnp.asarray(pos, jnp.float32), jnp.float32(h)))
        un = np.asarray(unwrap(img, mirror, cam))
        mad = np.abs(un - pan).mean()
        assert mad < 0.01, mad
        assert np.abs(un - pan[:, (-np.arange(cam.cols)) % cam.cols]).mean() > 5 * mad  # mirrored
        assert np.abs(un - np.roll(pan, 2, axis=1)).mean() > 3 * mad  # 2 columns off
        assert np.abs(un - pan[::-1]).mean() > 5 * mad  # upside down


def test_unwrap_is_bilinear_sampling():
    rng = np.random.default_rng(1)
    mirror, cam = Catadioptric(size=24), Camera(rows=6, cols=16)
    img = rng.uniform(0, 1, (24, 24, 3))
    got = np.asarray(unwrap(jnp.asarray(img, jnp.float32), mirror, cam))
    np.testing.assert_allclose(got, ref.unwrap(img, cam.rows, cam.cols), atol=1e-5)
    # a wide annulus reaches past the image: corners outside read black
    wide = Catadioptric(size=24, inner=0.5, outer=1.4)
    got = np.asarray(unwrap(jnp.asarray(img, jnp.float32), wide, cam))
    np.testing.assert_allclose(got, ref.unwrap(img, cam.rows, cam.cols, inner=0.5, outer=1.4), atol=1e-5)
    assert (got[0].max(-1) == 0).sum() >= 4  # the top row leaves the image along the axes: black


# ----------------------------------------------------------------------------- §5 pipeline
def test_rgb_to_hsv_is_the_hexcone():
    rng = np.random.default_rng(2)
    rgb = np.concatenate(
        [
            rng.uniform(0, 1, (400, 3)),
            np.round(rng.uniform(0, 1, (100, 3)), 1),  # ties
            np.eye(3),
            1 - np.eye(3),
            [[0, 0, 0], [1, 1, 1], [0.5, 0.5, 0.5]],
        ]
    ).astype(np.float32)
    got = np.asarray(pipeline.rgb_to_hsv(jnp.asarray(rgb)))
    assert ((got[:, 0] >= 0) & (got[:, 0] < 1)).all()
    for g, c in zip(got, rgb.astype(float)):
        want = colorsys.rgb_to_hsv(*c)
        assert abs(wrap(2 * np.pi * (g[0] - want[0]))) < 1e-5 and np.allclose(g[1:], want[1:], atol=1e-6), (c, g)
        assert np.allclose(ref.rgb_to_hsv(c), want, atol=1e-12)


def test_segment_hue_window_is_circular():
    hsv = np.array([[h / 360.0, 0.9, 0.8] for h in (359.0, 1.0, 19.0, 341.0, 21.5, 338.5, 180.0)], np.float32)
    got = np.asarray(pipeline.segment(jnp.asarray(hsv), 0.0, 40.0, 0.5, 0.15))
    np.testing.assert_array_equal(got, [True, True, True, True, False, False, False])
    # a window about 350 deg holds 5 deg (across 0) but not 20 deg
    got = np.asarray(pipeline.segment(jnp.asarray(hsv), 350.0, 40.0, 0.5, 0.15))
    np.testing.assert_array_equal(got, [True, True, False, True, False, True, False])
    rng = np.random.default_rng(3)
    hsv = rng.uniform(0, 1, (500, 3)).astype(np.float32)
    for hue, width, s, v in ((0.0, 40.0, 0.5, 0.15), (200.0, 90.0, 0.3, 0.4), (10.0, 360.0, 0.45, 0.0)):
        got = np.asarray(pipeline.segment(jnp.asarray(hsv), hue, width, s, v))
        want = [ref.is_landmark(x, hue, width, s, v) for x in hsv.astype(float)]
        np.testing.assert_array_equal(got, want)


def _striped_image(rng, rows, cols):
    """Random grey pixels with red and green patches of random extent."""
    img = rng.uniform(0, 1, (rows, cols, 1)) * np.ones(3)
    for colour in (RED, (0.1, 0.7, 0.1), RED, RED):
        r0, c0 = rng.integers(0, rows), rng.integers(0, cols)
        rr, cc = np.arange(r0, r0 + rng.integers(1, rows)), np.arange(c0, c0 + rng.integers(1, cols // 3))
        img[np.ix_(rr % rows, cc % cols)] = colour
    return (img * rng.uniform(0.5, 1.0)).astype(np.float32)


def test_band_rings_and_blobs_match_reference():
    rng = np.random.default_rng(4)
    cam = Camera(rows=20, cols=72)
    rings = eqx.filter_jit(lambda ex, img: ex.rings(img, cam))
    snap = eqx.filter_jit(lambda ex, share, gray: pipeline.ring_snapshot(share, gray, ex))
    settings = [(0.0, 10.0, 0.5), (-9.0, 4.0, 0.3), (4.0, 0.5, 0.5), (12.0, 30.0, 0.7)]  # (4, 0.5): no row centre
    n_blobs = 0
    for i in range(12):
        band, height, fill = settings[i % len(settings)]
        ex = pipeline.Extractor(
            band_deg=jnp.float32(band), band_height_deg=jnp.float32(height), fill=jnp.float32(fill), max_blobs=6
        )
        img = _striped_image(rng, cam.rows, cam.cols)
        share, gray = rings(ex, jnp.asarray(img))
        want_share, want_gray = ref.band_rings(img.astype(float), band, height)
        np.testing.assert_allclose(np.asarray(share), want_share, atol=1e-6)
        np.testing.assert_allclose(np.asarray(gray), want_gray, atol=1e-5)
        s = snap(ex, share, gray)
        mask, bearings, widths = ref.ring_blobs(want_share, fill)
        np.testing.assert_array_equal(np.asarray(s.mask), mask)
        valid = np.asarray(s.valid)
        assert valid.sum() == len(bearings) and not valid[len(bearings) :].any()
        np.testing.assert_allclose(np.asarray(s.bearing)[valid], bearings, atol=1e-5)
        np.testing.assert_allclose(np.asarray(s.width)[valid], widths, atol=1e-5)
        n_blobs += len(bearings)
    assert n_blobs >= 12
    assert ref.band_rows(20, 4.0, 0.5) == [8]  # the fallback: the row centred at 4.5 deg


def test_robot_blobs_from_home_are_the_true_bearings():
    """Zero camera noise, 8-bit image: the four red cylinders' blob bearings within one pixel (1 deg)."""
    iw = image_world("robot")
    cam = Camera()
    img = panorama(iw.world, cam, jnp.array([90.0, 90.0]), jnp.float32(0.0))
    snap = extract(iw.extractor, img, cam)
    c = np.asarray(iw.world.cylinders)
    true = np.sort(np.mod(np.arctan2(c[:, 1] - 90.0, c[:, 0] - 90.0), 2 * np.pi))
    assert np.asarray(snap.valid).all()
    err = np.degrees(np.abs(wrap(np.asarray(snap.bearing) - true)))
    assert err.max() <= 1.0, err  # measured 0.31 deg at most
    # turning the camera turns the bearings the other way by whole pixels
    img = panorama(iw.world, cam, jnp.array([90.0, 90.0]), jnp.float32(np.radians(30.0)))
    turned = extract(iw.extractor, img, cam)
    np.testing.assert_allclose(
        np.sort(np.mod(np.asarray(turned.bearing) + np.radians(30.0), 2 * np.pi)), np.asarray(snap.bearing), atol=1e-4
    )


def test_noise_levels_and_extractor_settings_share_one_program_and_keep_their_bits():
    """docs/images.md §5: `render_images` and `extract_rings` trace the camera-noise sigmas and the
    extractor's numbers (Python floats would be static under `equinox.filter_jit`, one program per value),
    and the traced program gives the static one's images and rings bit for bit."""
    import jax

    from delvjax.images import _render as rendering

    iw = image_world("robot")
    cam = rendering.camera(12, 72)
    poses = (np.array([[60.0, 80.0], [140.0, 120.0]], np.float32), np.array([0.3, 2.0], np.float32), np.arange(2))
    key = jax.random.PRNGKey(3)
    programs = rendering._render_images._cached._cache_size()
    quiet, noisy = (rendering.render_images(iw.world, cam, None, *poses, key, s, 0.03) for s in (0.0, 0.05))
    assert rendering._render_images._cached._cache_size() <= programs + 1  # both levels: one program
    assert not np.array_equal(np.asarray(quiet), np.asarray(noisy))  # the level is used
    static = rendering._render_images(iw.world, cam, None, *poses, key, 0.05, 0.03, rendering.IMAGE_WIDTH)
    assert np.array_equal(np.asarray(static), np.asarray(noisy))
    programs = rendering._extract_rings._cached._cache_size()
    thin, wide = (rendering.extract_rings(noisy, cam, None, pipeline.Extractor(band_height_deg=h)) for h in (2.0, 40.0))
    assert rendering._extract_rings._cached._cache_size() <= programs + 1
    assert not np.array_equal(np.asarray(thin.gray), np.asarray(wide.gray))
    static = rendering._extract_rings(noisy, cam, None, pipeline.Extractor(band_height_deg=40.0))
    for a, b in zip(jax.tree.leaves(static), jax.tree.leaves(wide)):
        assert np.array_equal(np.asarray(a), np.asarray(b))
