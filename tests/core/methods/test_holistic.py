"""Holistic comparators: warping (docs/model.md §4.3) and MFDID (docs/model.md §4.5).

Analytic cases first (the warp equation in a world where it is exact, the MFDID sign),
then agreement with the per-point NumPy twins (tests/twins/holistic.py) on random
environments, then interfaces and bad input.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli import _main as cli
from delvjax.core import maps
from delvjax.core.errors import InputError
from delvjax.core.methods import MFDID, Warping, mfdid, warping
from delvjax.core.metrics import angular_error_deg
from delvjax.core.sensing import render
from delvjax.core.sensor import Sensor
from tests.cases.compiled import call, compiled
from tests.conftest import random_landmarks
from tests.twins import holistic as rh
from tests.twins.methods import render as ref_render
from tests.twins.methods import wrap

KEY = jax.random.PRNGKey(0)


def random_points(env_lm: np.ndarray, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """n points in the arena at least 10 cm outside every cylinder, random headings."""
    rng = np.random.default_rng(seed)
    pts = []
    while len(pts) < n:
        p = rng.uniform(20, 980, size=2)
        if np.all(np.hypot(*(env_lm[:, :2] - p).T) > env_lm[:, 2] + 10):
            pts.append(p)
    return np.array(pts, np.float32), rng.uniform(0, 2 * math.pi, n).astype(np.float32)


@compiled
def _views(env, points, headings, cfg: Sensor):
    channel = 0 if cfg.channel == "mask" else 1
    everything = jnp.ones(env.landmarks.shape[0], bool)
    home = render(env, everything, env.home, jnp.float32(cfg.alpha_r), cfg)[channel]
    here = jax.vmap(lambda p, h: render(env, everything, p, h, cfg)[channel])(points, headings)
    return home, here


def views(env, points, headings, cfg: Sensor) -> tuple[np.ndarray, np.ndarray]:
    """The library's ring images: home (n_pix,) and current (P, n_pix) in `cfg.channel`."""
    home, here = _views(env, jnp.asarray(points), jnp.asarray(headings), cfg)
    return np.asarray(home), np.asarray(here)


@compiled
def search_all(S, C, method):
    """`warping.search(S, c, method)` for every row c of C."""
    return jax.vmap(lambda c: warping.search(S, c, method))(C)


# --- the warp table and its rounding rule ------------------------------------------------


def test_warp_table_rounding_is_unambiguous_and_psi_is_a_pixel_shift():
    cfg = Warping()
    n = Sensor().n_pix
    g = 2 * math.pi * np.arange(n) / n
    alpha = 2 * math.pi * np.arange(cfg.n_alpha) / cfg.n_alpha
    rho = rh.rho_values()
    assert np.allclose(warping.rho_values(cfg), np.arange(0.10, 0.80001, 0.05))
    x = (
        (g[None, None] - np.arcsin(rho[None, :, None] * np.sin(g[None, None] - alpha[:, None, None])))
        * n
        / (2 * math.pi)
    )
    assert np.min(np.abs(np.abs(x - np.floor(x)) - 0.5)) > 1e-5  # no angle near a pixel boundary
    table = warping.warp_indices(cfg, n).reshape(cfg.n_alpha, cfg.n_rho, n)
    for a, r, m in [(0, 0, 0), (7, 3, 11), (71, 14, 71), (36, 8, 40)]:  # the twin's literal g = phi + psi
        gg = g + 2 * math.pi * m / cfg.n_psi
        literal = rh.nearest_pixel(gg - np.arcsin(rho[r] * np.sin(gg - alpha[a])), n)
        assert np.array_equal(np.roll(table[a, r], -m * n // cfg.n_psi), literal)


def test_rotated_words_are_the_packed_rotations():
    rng = np.random.default_rng(3)
    mask = rng.random(360) < 0.3
    shifts = jnp.arange(72) * 5
    words = np.asarray(call(warping.rotated_words, jnp.asarray(mask), shifts))
    for m in (0, 1, 37, 71):
        rolled = np.roll(mask, 5 * m)  # C(g - s)
        assert np.array_equal(words[m], np.asarray(call(warping.pack_bits, jnp.asarray(rolled))))


# --- analytic: the warp equation where it is exact ---------------------------------------


def test_warping_is_accurate_where_every_landmark_is_equidistant_from_home():
    """ring6: six landmarks 250 cm from home. With headings on the psi grid (5 degrees) the
    warp model holds exactly up to pixel rounding; points up to rho = 0.8 (200 cm)."""
    env = delvjax.load_env("ring6")
    pts = maps.grid_points(env.arena, 25.0)
    dist = np.hypot(*(pts - np.asarray(env.home)).T)
    pts = jnp.asarray(pts[dist <= 200.0])
    heads = jnp.round(maps.random_headings(KEY, pts.shape[0]) / np.radians(5)) * np.radians(5)
    direction, valid = maps.homing_directions(env, pts, heads, KEY, Sensor(), Warping())
    err = np.asarray(angular_error_deg(direction, valid, pts, env.home))
    assert np.all(np.asarray(valid))
    assert err.mean() < 4.0 and err.max() <= 10.0, (err.mean(), err.max())


def test_warping_invalid_when_the_home_image_is_uniform():
    env = delvjax.Env(
        landmarks=jnp.array([[300.0, 300.0, 20.0]]),
        valid=jnp.array([False]),  # nothing to see
        home=jnp.array([500.0, 500.0]),
        arena=jnp.array([0.0, 0.0, 1000.0, 1000.0]),
    )
    d, v = maps.homing_directions(env, jnp.array([[300.0, 300.0]]), jnp.array([0.3]), KEY, Sensor(), Warping())
    assert not bool(v[0]) and math.isnan(float(d[0]))


# --- analytic: the MFDID sign convention ---------------------------------------------------


@pytest.mark.parametrize("channel", ["mask", "gray"])
def test_mfdid_points_home_for_small_displacements(channel):
    """ring4 (equal distances, where the flow templates are right): a point displaced along
    +x, +y, -x, -y is sent back along -x, -y, +x, +y."""
    env = delvjax.load_env("ring4")
    home = np.asarray(env.home)
    offsets = np.array([[30, 0], [0, 30], [-30, 0], [0, -30]], np.float32)
    pts = jnp.asarray(home + offsets)
    heads = jnp.array([0.0, 1.0, 2.5, -2.0])
    direction, valid = maps.homing_directions(env, pts, heads, KEY, Sensor(channel=channel), MFDID())
    expected = np.arctan2(-offsets[:, 1], -offsets[:, 0])
    err = np.degrees(np.abs(wrap(np.asarray(direction) - expected)))
    assert np.all(np.asarray(valid)) and np.all(err < 20.0), err


def test_mfdid_home_vector_is_minus_the_gradient_of_the_image_distance():
    """Finite differences of D(x) = sum (C_x - S)^2 on smooth synthetic 1D images."""
    n = 360
    t = 2 * math.pi * np.arange(n) / n
    lm = np.array([[0.0, 300.0], [-250.0, -100.0], [200.0, -200.0]])

    def image(x):  # three soft bumps seen from x (world frame), heading 0
        b = np.arctan2(lm[:, 1] - x[1], lm[:, 0] - x[0])
        return np.sum(np.exp(-0.5 * (wrap(t[:, None] - b[None]) / 0.15) ** 2), axis=1)

    S = image(np.zeros(2))
    x = np.array([20.0, -15.0])
    C = image(x)
    h = np.asarray(call(mfdid.home_vector, jnp.asarray(S, jnp.float32), jnp.asarray(C, jnp.float32), jnp.float32(0.0)))
    eps = 0.5
    grad = np.array(
        [
            (np.sum((image(x + e) - S) ** 2) - np.sum((image(x - e) - S) ** 2)) / (2 * eps)
            for e in (np.array([eps, 0.0]), np.array([0.0, eps]))
        ]
    )
    cos = -grad @ h / (np.linalg.norm(grad) * np.linalg.norm(h))
    assert cos > 0.95, cos


# --- agreement with the NumPy twins ---------------------------------------------------------

COARSE = dict(n_alpha=24, n_psi=24, n_rho=5)  # same code paths, 27x fewer hypotheses for the slow twin


@pytest.mark.parametrize(
    "hyp, cases", [({}, [(0, 2), (1, 2)]), (COARSE, [(2, 8), (3, 8), (4, 8)])], ids=["72x15x72", "24x5x24"]
)
def test_warping_mask_search_equals_the_twin_exactly(hyp, cases):
    """Same images in both: the minimum distance is exact; >= 90% of directions within 2 deg
    (ties between hypotheses are common on binary images)."""
    cfg, method = Sensor(), Warping(**hyp)
    n_total = agree = 0
    for seed, n in cases:
        lm = random_landmarks(seed)
        env = delvjax.make_env(lm, pad_to=6)  # one shape for every seed: one program
        pts, heads = random_points(lm, n, seed)
        S, C = views(env, pts, heads, cfg)
        s_ref, _ = ref_render(lm, np.asarray(env.home, float), 0.0, np.asarray(env.arena))
        assert np.array_equal(s_ref, S)  # the twin would render the same home image
        dist = search_all(jnp.asarray(S), jnp.asarray(C), method)[0]
        lib_dir, lib_valid = maps.homing_directions(env, jnp.asarray(pts), jnp.asarray(heads), KEY, cfg, method)
        assert np.all(np.asarray(lib_valid))
        for i in range(n):
            ref_dist, ra, _, rm = rh.warping_search(S.astype(float), C[i].astype(float), **hyp)
            assert float(dist[i]) == ref_dist, (seed, i, float(dist[i]), ref_dist)
            ref_dir = wrap(heads[i] + rh.TWO_PI * ra / method.n_alpha + math.pi - rh.TWO_PI * rm / method.n_psi)
            agree += abs(wrap(float(lib_dir[i]) - ref_dir)) <= math.radians(2.0)
            n_total += 1
    assert agree >= 0.9 * n_total, (agree, n_total)


def test_warping_gray_search_matches_the_twin():
    cfg = Sensor(channel="gray")
    lm = random_landmarks(5)
    env = delvjax.make_env(lm)
    pts, heads = random_points(lm, 3, 5)
    S, C = views(env, pts, heads, cfg)
    dist, a, r, m = search_all(jnp.asarray(S), jnp.asarray(C), Warping())
    agree = 0
    for i in range(len(pts)):
        ref_dist, ra, rr, rm = rh.warping_search(S.astype(float), C[i].astype(float))
        assert abs(float(dist[i]) - ref_dist) <= 1e-5 * max(ref_dist, 1.0)
        agree += abs(wrap(rh.TWO_PI * (ra - int(a[i])) / 72 - rh.TWO_PI * (rm - int(m[i])) / 72)) <= math.radians(2)
    assert agree >= 2


@pytest.mark.parametrize("channel", ["mask", "gray"])
def test_mfdid_matches_the_twin(channel):
    cfg = Sensor(channel=channel)
    close = total = 0
    for seed in (0, 1, 2):
        lm = random_landmarks(seed)
        env = delvjax.make_env(lm, pad_to=6)  # one shape for every seed: one program
        pts, heads = random_points(lm, 30, 100 + seed)
        lib_dir, lib_valid = maps.homing_directions(env, jnp.asarray(pts), jnp.asarray(heads), KEY, cfg, MFDID())
        S, C = views(env, pts, heads, cfg)
        for i in range(len(pts)):
            ref_agent = rh.mfdid_direction(S.astype(float), C[i].astype(float), wrap(float(heads[i])))
            assert math.isnan(ref_agent) == (not bool(lib_valid[i]))
            if not math.isnan(ref_agent):
                close += abs(wrap(float(lib_dir[i]) - heads[i] - ref_agent)) < math.radians(0.5)
                total += 1
    assert close >= 0.97 * total, (close, total)


def test_predicted_images_stay_unbatched_under_vmap():
    """The (n_alpha * n_rho, n_pix) table of predicted images depends on the home image only:
    vmapping over current views must not batch it (it is built once per map)."""
    cfg = Warping()
    S = jnp.zeros(360, bool).at[40:60].set(True)
    C = jnp.zeros((5, 360), bool).at[:, 100:130].set(True)
    jaxpr = jax.make_jaxpr(jax.vmap(lambda c: warping.search(S, c, cfg)))(C)
    shapes = [tuple(v.aval.shape) for eqn in jaxpr.eqns for v in eqn.outvars]
    assert (1080, 360) in shapes and (5, 1080, 360) not in shapes
    assert not any(len(s) == 3 and s[0] == 5 and s[1] == 1080 for s in shapes)


# --- interfaces and bad input ---------------------------------------------------------------


def test_api_runs_both_methods_and_channels():
    for method, channel in [("warping", "gray"), ("mfdid", "mask")]:
        vm = delvjax.vector_map("env1", method=method, channel=channel, grid=Grid(spacing=200.0))
        assert vm.direction.shape == (25,) and bool(np.all(np.asarray(vm.valid)[np.asarray(vm.included)]))
    coarse = delvjax.vector_map("env1", method="warping", n_alpha=36, n_psi=36, n_rho=8, grid=Grid(spacing=200.0))
    assert coarse.direction.shape == (25,)


@pytest.mark.parametrize(
    "flags",
    [
        ["--channel", "rgb"],
        ["--background", "sky"],
        ["--n-alpha", "0"],
        ["--n-psi", "-5"],
        ["--n-rho", "0"],
        ["--n-psi", "7"],
        ["--rho-max", "1.5"],
    ],
)
def test_cli_bad_input_exits_2_without_output(tmp_path, capsys, flags):
    out = tmp_path / "map.csv"
    assert cli.main(["vector-map", "env1", "--method", "warping", "--out", str(out), *flags]) == 2
    assert not out.exists()
    err = capsys.readouterr().err
    assert err.startswith("delvjax: error:") and len(err.strip().splitlines()) == 1


def test_direct_config_errors_at_trace_time():
    with pytest.raises(InputError, match="n_psi"):
        warping.search(jnp.zeros(360, bool), jnp.zeros(360, bool), Warping(n_psi=7))
    with pytest.raises(InputError, match="n_alpha"):
        delvjax.vector_map("env1", method="warping", n_alpha=0)


def test_mfdid_low_pass_is_identity_at_zero_and_helps_far_from_home():
    """The optional Gaussian low-pass (Möller & Vardy work on low-passed images): sigma 0 leaves
    the image unchanged; on env1 a 40 deg blur cuts MFDID's mean error at least in half."""
    from delvjax.core.methods.mfdid import low_pass

    img = (jnp.arange(360) % 50 < 9).astype(jnp.float32)
    np.testing.assert_allclose(np.asarray(call(low_pass, img, jnp.float32(0.0))), np.asarray(img), atol=1e-5)
    assert abs(float(call(low_pass, img, jnp.float32(20.0)).sum()) - float(img.sum())) < 1e-3  # mass preserved
    raw = delvjax.vector_map("env1", method="mfdid", grid=Grid(spacing=100.0))
    blurred = delvjax.vector_map("env1", method="mfdid", blur_deg=40.0, grid=Grid(spacing=100.0))
    inc = np.asarray(raw.included)
    assert np.asarray(blurred.error_deg)[inc].mean() < 0.5 * np.asarray(raw.error_deg)[inc].mean()
