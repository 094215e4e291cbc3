"""Ring rendering, blobs, background and the visual compass against the NumPy twin (docs/model.md §2, §4.4)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import reference as ref
from delvjax.core.sensor import Sensor
from delvjax.core.methods.heading import visual_compass
from delvjax.core.sensing import extract_blobs, render


def _poses(seed, n=12):
    rng = np.random.default_rng(seed)
    return rng.uniform(20, 980, size=(n, 2)), rng.uniform(0, 2 * np.pi, size=n)


@pytest.mark.parametrize("background", ["distant", "walls", "none"])
def test_render_matches_reference(random_envs, background):
    cfg = Sensor(background=background)
    agree, total = 0, 0
    for i, (lm, env) in enumerate(random_envs[:8]):
        pos, hd = _poses(i)
        masks, grays = jax.vmap(lambda p, h: render(env, env.valid, p, h, cfg))(jnp.asarray(pos, jnp.float32), jnp.asarray(hd, jnp.float32))
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
    mask, gray = render(env, env.valid, jnp.array([500.0, 500.0]), jnp.array(0.0), Sensor())
    mask_big_only, _ = render(env, jnp.array([True, False]), jnp.array([500.0, 500.0]), jnp.array(0.0), Sensor())
    np.testing.assert_array_equal(np.asarray(mask), np.asarray(mask_big_only))
    assert np.asarray(mask)[0] and np.asarray(gray)[0] == 1.0
    b, v = extract_blobs(mask, 2)
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
    bearing, valid = jax.vmap(lambda m: extract_blobs(m, 4))(jnp.asarray(masks))
    for m, b, v in zip(masks, np.asarray(bearing), np.asarray(valid)):
        expect = ref.extract_blobs(m)
        assert v.sum() == len(expect)
        np.testing.assert_allclose(b[v], expect, atol=1e-5)
        assert not v[len(expect):].any()


def test_visual_compass_matches_reference_and_recovers_rotation(random_envs):
    lm, env = random_envs[3]
    cfg = Sensor()
    _, home_gray = render(env, env.valid, env.home, jnp.array(0.0), cfg)
    for h_deg in (0.0, 37.0, 200.0, 359.0):
        h = np.radians(h_deg)
        _, gray = render(env, env.valid, env.home, jnp.array(h, jnp.float32), cfg)
        est = float(visual_compass(home_gray, gray))
        assert abs(ref.wrap(est - h)) < np.radians(1.01)
        _, rg = ref.render(lm, env.home, h, [0, 0, 1000, 1000])
        _, rhome = ref.render(lm, env.home, 0.0, [0, 0, 1000, 1000])
        assert abs(ref.wrap(est - ref.visual_compass(rhome, rg))) < 1e-6
