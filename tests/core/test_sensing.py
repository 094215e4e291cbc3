"""Ring rendering, blobs, background and the visual compass against the NumPy twin (docs/model.md §2, §4.4)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.methods.heading import visual_compass
from delvjax.core.sensing import extract_blobs, render
from delvjax.core.sensor import Sensor
from tests.cases.compiled import compiled
from tests.twins import methods as ref


@compiled
def render_poses(env, pos, heading, cfg):
    """`render` from every pose (pos (P, 2), heading (P,)), every valid landmark."""
    return jax.vmap(lambda p, h: render(env, env.valid, p, h, cfg))(pos, heading)


@compiled
def blobs_of_masks(masks, max_blobs):
    """`extract_blobs` of every mask (M, n_pix)."""
    return jax.vmap(lambda m: extract_blobs(m, max_blobs))(masks)


render_one, extract_blobs_one, visual_compass_one = map(compiled, (render, extract_blobs, visual_compass))


def _poses(seed, n=12):
    rng = np.random.default_rng(seed)
    return rng.uniform(20, 980, size=(n, 2)), rng.uniform(0, 2 * np.pi, size=n)


@pytest.mark.parametrize("background", ["distant", "walls", "none"])
def test_render_matches_reference(random_envs, background):
    cfg = Sensor(background=background)
    agree, total = 0, 0
    for i, (lm, env) in enumerate(random_envs[:8]):
        pos, hd = _poses(i)
        masks, grays = render_poses(env, jnp.asarray(pos, jnp.float32), jnp.asarray(hd, jnp.float32), cfg)
        for p, h, m, g in zip(pos, hd, np.asarray(masks), np.asarray(grays)):
            rm, rg = ref.render(lm, p, h, [0, 0, 1000, 1000], background)
            agree += int(np.sum(rm == m))
            total += m.size
            same = rm == m
            np.testing.assert_allclose(g[same], rg[same], atol=2e-4)
    assert agree / total >= 0.999, agree / total  # only ray-grazing pixels may differ by rounding


def test_occlusion_is_real():
    """A small cylinder straight behind a big one is hidden; in front it is seen (one blob)."""
    lms = np.array([[700.0, 500.0, 40.0], [850.0, 500.0, 10.0]])
    import delvjax

    env = delvjax.make_env(lms)
    mask, gray = render_one(env, env.valid, jnp.array([500.0, 500.0]), jnp.array(0.0), Sensor())
    mask_big_only, _ = render_one(env, jnp.array([True, False]), jnp.array([500.0, 500.0]), jnp.array(0.0), Sensor())
    np.testing.assert_array_equal(np.asarray(mask), np.asarray(mask_big_only))
    assert np.asarray(mask)[0] and np.asarray(gray)[0] == 1.0
    b, v = extract_blobs_one(mask, 2)
    assert int(v.sum()) == 1 and float(b[0]) == 0.0  # centred on pixel 0 (wraps through it)


def _random_mask(rng, n=360):
    kind = rng.integers(0, 6)
    if kind == 0:
        return np.ones(n, bool)
    if kind == 1:
        return np.zeros(n, bool)
    m = np.zeros(n, bool)
    for _ in range(rng.integers(1, 5)):
        s, length = rng.integers(0, n), rng.integers(1, 40)
        m[(s + np.arange(length)) % n] = True
    return m


def test_blobs_match_reference():
    rng = np.random.default_rng(0)
    masks = np.stack([_random_mask(rng) for _ in range(300)])
    bearing, valid = blobs_of_masks(jnp.asarray(masks), 4)
    for m, b, v in zip(masks, np.asarray(bearing), np.asarray(valid)):
        expect = ref.extract_blobs(m)
        assert v.sum() == len(expect)
        np.testing.assert_allclose(b[v], expect, atol=1e-5)
        assert not v[len(expect) :].any()


def test_visual_compass_matches_reference_and_recovers_rotation(random_envs):
    lm, env = random_envs[3]
    cfg = Sensor()
    _, home_gray = render_one(env, env.valid, env.home, jnp.array(0.0), cfg)
    for h_deg in (0.0, 37.0, 200.0, 359.0):
        h = np.radians(h_deg)
        _, gray = render_one(env, env.valid, env.home, jnp.array(h, jnp.float32), cfg)
        est = float(visual_compass_one(home_gray, gray))
        assert abs(ref.wrap(est - h)) < np.radians(1.01)
        _, rg = ref.render(lm, env.home, h, [0, 0, 1000, 1000])
        _, rhome = ref.render(lm, env.home, 0.0, [0, 0, 1000, 1000])
        assert abs(ref.wrap(est - ref.visual_compass(rhome, rg))) < 1e-6


def test_cylinder_blobs_equal_the_blobs_of_the_rendered_ring():
    """The closed-form blobs (core/cylinder_blobs.py) are exactly blob_runs of the rendered ring, on
    random scenes with overlapping, hidden, sub-pixel and surrounding cylinders and viewpoints inside one."""
    from delvjax.core.cylinder_blobs import blobs_of_cylinders
    from delvjax.core.sensing import blob_runs, ray_hits, sort_blobs

    rng = np.random.default_rng(7)
    n_views, n_lm, n_pix = 20000, 6, 360
    lms = np.zeros((n_views, n_lm, 3), np.float32)
    lms[..., :2] = rng.uniform(-300, 300, (n_views, n_lm, 2))
    lms[..., 2] = rng.choice([0.2, 5.0, 30.0, 80.0], (n_views, n_lm)) * rng.uniform(0.5, 1.5, (n_views, n_lm))
    half = n_views // 2  # clustered: blobs merge and hide each other
    lms[:half, 1:, :2] = lms[:half, :1, :2] + rng.uniform(-50, 50, (half, n_lm - 1, 2))
    visible = rng.uniform(size=(n_views, n_lm)) < 0.85
    origin = rng.uniform(-300, 300, (n_views, 2)).astype(np.float32)
    origin[:200] = lms[:200, 0, :2]  # inside a cylinder: the whole ring
    origin[200:400] = 0.0  # a ring of big cylinders around the origin covers it all
    ring = np.stack([np.cos(np.arange(n_lm)), np.sin(np.arange(n_lm))], -1) * 60.0
    lms[200:400, :, :2], lms[200:400, :, 2], visible[200:400] = ring, 45.0, True
    heading = rng.uniform(-7, 7, n_views).astype(np.float32)

    def rendered(lm, vis, o, h):
        return blob_runs(ray_hits(lm, vis, o, h, n_pix), n_lm)

    def closed_form(lm, vis, o, h):
        b, w, ok = blobs_of_cylinders(lm, vis, o, h, n_pix)
        b, ok, w = sort_blobs(b, ok, w)
        return b, w, ok

    old = [np.asarray(a) for a in jax.jit(jax.vmap(rendered))(lms, visible, origin, heading)]
    new = [np.asarray(a) for a in jax.jit(jax.vmap(closed_form))(lms, visible, origin, heading)]
    counts = old[2].sum(1)
    assert (counts == 0).any() and (counts >= 4).any() and (old[1][:, 0] > 6.28).sum() >= 300  # the cases occur
    for a, b in zip(old, new):
        np.testing.assert_array_equal(a, b)
