"""DELV without a compass in O(B^2) (delvjax/core/methods/rotations.py, docs/model.md §3.3): the
(rotation, shift) table from window and prefix sums equals every pairing summed on its own; the
search finds the direct table's winner; below MIN_SLOTS the direct table itself runs (bit for bit);
and the NumPy twin (tests/twins/methods.py) agrees at 8 and more landmarks."""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.geometry import TWO_PI
from delvjax.core.methods import delv
from delvjax.core.methods.pairing import shift_pairs
from delvjax.core.methods.rotations import MIN_SLOTS, best_rotated, rotation_table
from tests.twins import methods as twin

ALPHAS = TWO_PI * jnp.arange(360, dtype=jnp.float32) / 360


def _views(rng, items, size, cur_size=None):
    """Random views: sorted bearings, distances 50-1500 cm, random counts (many full), garbage padding;
    half the current views a rotated, shifted copy of the reference (a near-exact match)."""
    cur_size = cur_size or size
    out = []
    for b in (size, cur_size):
        ang = np.sort(rng.uniform(0, TWO_PI, (items, b)), axis=1)
        r = rng.uniform(50, 1500, (items, b))
        out.append((np.stack([r * np.cos(ang), r * np.sin(ang)], -1), ang))
    (ref, _), (cur, bearing) = out
    copy = rng.random(items) < 0.5
    m = min(size, cur_size)
    th = rng.uniform(0, TWO_PI, items)
    rot = np.stack([np.cos(th), np.sin(th), -np.sin(th), np.cos(th)], -1).reshape(items, 2, 2)
    cur[copy, :m] = np.einsum("nij,nbj->nbi", rot[copy], ref[copy, :m] + rng.normal(0, 30, (copy.sum(), 1, 2)))
    n_ref, n_cur = rng.integers(0, size + 1, items), rng.integers(0, cur_size + 1, items)
    n_ref[rng.random(items) < 0.4], n_cur[rng.random(items) < 0.4] = size, cur_size
    ref_ok, cur_ok = np.arange(size) < n_ref[:, None], np.arange(cur_size) < n_cur[:, None]
    ref = np.where(ref_ok[..., None], ref, rng.uniform(-1e3, 1e3, ref.shape))
    f32 = lambda x: jnp.asarray(x, jnp.float32)  # noqa: E731
    return f32(ref), jnp.asarray(ref_ok), f32(cur), jnp.asarray(cur_ok), f32(bearing)


def _direct(ref_v, ref_ok, cur_v, cur_ok, alphas, offsets):
    """The direct table of every rotation (`delv.pairing_table` over `delv.rotated_rows`, B^3)."""
    ref_idx, cur_idx, pair_ok, shift_ok = shift_pairs(ref_ok, cur_ok)
    rows, row_of = delv.rotated_rows(cur_idx, cur_ok, alphas, offsets)
    n = jnp.sum(pair_ok[0])
    p, alpha, var = delv.best_pairing(ref_v, cur_v, ref_idx, rows, pair_ok, shift_ok, n, alphas, row_of)
    return p, alpha, var, n


def _fast(ref_v, ref_ok, cur_v, cur_ok, alphas, offsets):
    """`rotations.best_rotated` at any size (`delv.match_arrangement` uses it from MIN_SLOTS slots)."""
    pairs = shift_pairs(ref_ok, cur_ok)
    p, alpha, var, _ = best_rotated(ref_v, ref_ok, cur_v, cur_ok, alphas, offsets, pairs, jnp.sum(pairs[2][0]))
    return p, alpha, var, jnp.sum(pairs[2][0])


def _run(f, views):
    ref, ref_ok, cur, cur_ok, bearing = views
    g = lambda r, ro, c, co, b: f(r, ro, c, co, ALPHAS, delv.list_offsets(b, co, ALPHAS))  # noqa: E731
    return [np.asarray(x) for x in jax.jit(jax.vmap(g))(ref, ref_ok, cur, cur_ok, bearing)]


@pytest.mark.parametrize("size, cur_size", [(9, 9), (8, 11)])
def test_the_table_is_every_pairing_summed_on_its_own(size, cur_size):
    """const and z of Eq 3.5 for rotation r, shift k, against a float64 sum over the pairs of
    `shift_pairs` with the current list rotated by r (fewer, equal and more current landmarks)."""
    rng = np.random.default_rng(size)
    ref, ref_ok, cur, cur_ok, _ = _views(rng, 24, size, cur_size)
    tables = [np.asarray(t) for t in jax.jit(jax.vmap(rotation_table))(ref, ref_ok, cur, cur_ok)]
    for i in range(24):
        ref_idx, cur_idx, pair_ok, shift_ok = (np.asarray(x) for x in shift_pairs(ref_ok[i], cur_ok[i]))
        m = max(int(np.sum(cur_ok[i])), 1)
        a_all, b_all = np.asarray(ref[i], np.float64), np.asarray(cur[i], np.float64)
        scale = np.sum(a_all[np.asarray(ref_ok[i])] ** 2) + np.sum(b_all[np.asarray(cur_ok[i])] ** 2) + 1.0
        for r in range(m):
            for k in np.nonzero(shift_ok)[0]:
                s = pair_ok[k]
                a = a_all[ref_idx[k][s]]
                b = b_all[np.minimum((cur_idx[k][s] + r) % m, cur_size - 1)]
                if len(a) == 0:
                    continue
                a, b = a - a.mean(0), b - b.mean(0)
                want = (np.sum(a * a + b * b), np.sum(a * b), np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))
                got = [t[i][r, k] for t in tables]
                assert np.allclose(got, want, rtol=0, atol=2e-5 * scale), (i, r, k, got, want)


@pytest.mark.parametrize("size", [8, 12])
def test_the_search_finds_the_direct_tables_winner(size):
    """Same hypothesis and pair count as the direct table; p within float32 rounding of it."""
    views = _views(np.random.default_rng(size), 300, size)
    p, alpha, var, n = _run(_fast, views)
    if size >= MIN_SLOTS:  # what DELV runs
        assert all(np.array_equal(x, y) for x, y in zip((p, alpha, var, n), _run(delv.match_arrangement, views)))
    p0, alpha0, var0, n0 = _run(_direct, views)
    assert np.array_equal(n, n0)
    same = alpha == alpha0
    assert same.mean() >= 0.99, same.mean()
    assert np.allclose(p[same], p0[same], rtol=0, atol=1e-3)
    ref, ref_ok, cur, cur_ok, _ = (np.asarray(x) for x in views)
    scale = np.sum(ref**2 * ref_ok[..., None], axis=(1, 2)) + np.sum(cur**2 * cur_ok[..., None], axis=(1, 2))
    finite = np.isfinite(var0)
    assert np.array_equal(finite, np.isfinite(var))
    ok = finite & same
    assert np.all(np.abs(var[ok] - var0[ok]) <= 1e-6 * scale[ok])  # float32 rounding of sums of that size


def test_memory_grows_as_b_squared_not_b_cubed():
    """At 48 landmarks the direct table holds B^3 = 110592 pair vectors a view; the search keeps
    (B x A) hypothesis tables. XLA's own account of the compiled program's scratch memory."""
    views = _views(np.random.default_rng(0), 16, 48)

    def temp_bytes(f):
        ref, ref_ok, cur, cur_ok, bearing = views
        g = lambda r, ro, c, co, b: f(r, ro, c, co, ALPHAS, delv.list_offsets(b, co, ALPHAS))  # noqa: E731
        return jax.jit(jax.vmap(g)).lower(*views).compile().memory_analysis().temp_size_in_bytes

    fast, direct = temp_bytes(delv.match_arrangement), temp_bytes(_direct)  # 48 >= MIN_SLOTS: the fast one
    assert fast < direct / 4, (fast, direct)


def test_below_min_slots_it_is_the_direct_table_bit_for_bit():
    views = _views(np.random.default_rng(4), 200, MIN_SLOTS - 1)
    for x, y in zip(_run(delv.match_arrangement, views), _run(_direct, views)):
        assert np.array_equal(x, y, equal_nan=True)


def test_the_numpy_twin_agrees_at_ten_landmarks():
    """tests/twins/methods.py's match (every shift x hypothesis, the list sorted per hypothesis)."""
    rng = np.random.default_rng(10)
    ref, ref_ok, cur, cur_ok, bearing = _views(rng, 6, 10)
    cur_ok = ref_ok = jnp.ones_like(ref_ok)  # the twin pairs whole lists
    p, alpha, var, _ = _run(_fast, (ref, ref_ok, cur, cur_ok, bearing))
    alphas = [float(a) for a in np.asarray(ALPHAS)]
    for i in range(6):
        k, alpha_t, p_t, var_t = twin.match_arrangement(ref[i], cur[i], alphas, cur_bearings=np.asarray(bearing[i]))
        assert math.isclose(alpha[i], alpha_t, abs_tol=1e-6), (i, alpha[i], alpha_t)
        assert np.allclose(p[i], p_t, atol=1e-2 * max(1.0, np.abs(p_t).max()) ** 0.5)
