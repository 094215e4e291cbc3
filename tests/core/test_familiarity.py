"""The familiarity core against its NumPy twin (tests/twins/familiarity.py) on random inputs, and
analytic cases: a rolled snapshot is found at its roll, trained views are familiar, BoB's window and
catchment rules on their own examples (docs/familiarity.md §1-3)."""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.familiarity.catchment import ca_bounds, medfilt, rca_bounds, route_catchments
from delvjax.core.familiarity.infomax import InfoMax, initial_weights
from delvjax.core.familiarity.mushroom_body import mushroom_body
from delvjax.core.familiarity.perfect_memory import PerfectMemory, window
from delvjax.core.familiarity.ridf import difference, ridf_table, rolled, turn_of_shift, unmasked_table
from tests.twins import familiarity as twin

RNG = np.random.default_rng(7)


def images(n, h=6, w=24, rng=RNG):
    return rng.integers(0, 256, (n, h, w)).astype(np.float32)


@pytest.mark.parametrize("kind", ["abs", "rms", "corr"])
@pytest.mark.parametrize("masked", [False, True])
def test_the_ridf_table_is_the_twins(kind, masked):
    view, snaps = images(1)[0], images(5)
    vm = RNG.random(view.shape) > 0.3 if masked else None
    sm = RNG.random(snaps.shape) > 0.3 if masked else None
    got = np.asarray(ridf_table(view, snaps, kind, vm, sm))
    np.testing.assert_allclose(got, twin.ridf_table(view, snaps, kind, vm, sm), rtol=2e-5, atol=2e-4)


@pytest.mark.parametrize("kind", ["abs", "rms", "corr"])
def test_the_unmasked_fast_table_is_the_masked_one_with_every_pixel_kept(kind):
    views, snaps = images(7), images(40)  # a flat pixel loop against the (H, W) reduction
    keep = np.ones((7, 6, 24), bool)
    got = np.asarray(unmasked_table(views, snaps, kind))
    want = np.asarray(jax.vmap(lambda s: difference(views, s[None], keep, kind))(jnp.asarray(snaps)))
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-4)
    assert got.shape == (40, 7)
    pm = PerfectMemory(kind=kind).train(snaps)
    masked = PerfectMemory(kind=kind).train(snaps, np.ones(snaps.shape, bool))
    assert pm.masks is None and masked.masks is not None
    np.testing.assert_allclose(np.asarray(pm.table(views)), np.asarray(masked.table(views)), rtol=1e-5, atol=1e-4)


def test_an_empty_common_mask_and_a_constant_image_are_nan_not_a_number():
    view, snaps = images(1)[0], images(2)
    none = np.zeros(view.shape, bool)
    assert np.isnan(np.asarray(ridf_table(view, snaps, "abs", none))).all()
    flat = np.full(view.shape, 7.0, np.float32)
    assert np.isnan(np.asarray(ridf_table(flat, snaps, "corr"))).all()


@pytest.mark.parametrize("select", ["best", "weighted"])
def test_perfect_memory_chooses_as_the_twin(select):
    snaps = images(6)
    view = np.roll(snaps[3], -5, axis=1) + RNG.normal(0, 20, snaps[3].shape).astype(np.float32)
    w = view.shape[1]
    turns = np.asarray(turn_of_shift(jnp.arange(w), w))
    pm = PerfectMemory(select=select).train(snaps)
    c = pm.choose(rolled(view, jnp.arange(w)), jnp.asarray(turns))
    want_turn, want_value, want_s = twin.perfect_memory_choice(twin.ridf_table(view, snaps), turns, select)
    assert float(c.turn) == pytest.approx(want_turn, abs=1e-5)
    assert float(c.value) == pytest.approx(want_value, rel=1e-5)
    assert int(c.snapshot) == want_s == 3


def test_a_rolled_snapshot_is_found_at_its_roll_with_zero_difference():
    snaps = images(4)
    w = snaps.shape[-1]
    for k in (0, 1, 7, w - 1):
        view = np.roll(snaps[2], -k, axis=1)  # seen after a turn of k columns to the left (ccw)
        pm = PerfectMemory().train(snaps)
        c = pm.choose(rolled(view, jnp.arange(w)), turn_of_shift(jnp.arange(w), w))
        assert int(c.snapshot) == 2 and float(c.value) == 0.0
        assert math.isclose(float(c.turn), math.remainder(-2 * math.pi * k / w, 2 * math.pi), abs_tol=1e-6)


@pytest.mark.parametrize("pointer,ahead,behind,want", [(-1, 3, 0, range(10)), (4, 3, 0, range(4, 7)), (8, 3, 0, range(7, 10)),
                                                       (4, 3, 2, range(2, 7)), (0, 3, 5, range(0, 3)), (5, 0, 0, range(10))])  # fmt: skip
def test_the_window_is_bobs_clamp(pointer, ahead, behind, want):
    got = np.flatnonzero(np.asarray(window(10, jnp.int32(pointer), ahead, behind)))
    assert got.tolist() == list(want)


def test_infomax_training_and_decision_are_the_twins():
    snaps = images(5, 4, 12)
    w0 = np.asarray(initial_weights(jax.random.key(3), 48, 50))
    assert np.abs(w0.mean(0)).max() < 1e-5 and np.allclose(np.sqrt((w0**2).mean(0)), 1.0, atol=1e-5)
    model = InfoMax(weights=jnp.asarray(w0), learning_rate=0.01, rate_divisor="hidden").train(snaps)
    want = twin.infomax_train(w0, snaps, 0.01 / 50)
    np.testing.assert_allclose(np.asarray(model.weights), want, rtol=1e-4, atol=1e-5)
    got = np.asarray(model.unfamiliarity(snaps[:2]))
    assert got == pytest.approx([twin.infomax_unfamiliarity(want, s) for s in snaps[:2]], rel=1e-4)


def test_infomax_finds_trained_views_more_familiar_than_new_ones():
    snaps, new = images(20, 6, 24), images(20, 6, 24)
    model = InfoMax(weights=initial_weights(jax.random.key(0), 144, 144), learning_rate=0.97)
    trained = model.train(snaps)
    assert float(jnp.mean(trained.unfamiliarity(snaps))) < 0.9 * float(jnp.mean(trained.unfamiliarity(new)))
    assert float(jnp.mean(model.unfamiliarity(snaps))) > 0.95 * float(
        jnp.mean(model.unfamiliarity(new))
    )  # untrained: no preference


def test_the_mushroom_body_is_the_twins_and_knows_what_it_saw():
    snaps, new = images(4, 6, 24), images(3, 6, 24)
    mb = mushroom_body((6, 24), jax.random.key(1), n_kc=500, pn_per_kc=5, n_active=20)
    wiring = np.asarray(mb.wiring)
    assert all(len(set(row)) == 5 for row in wiring)  # distinct PNs per KC
    trained = mb.train(snaps)
    want_w = twin.mushroom_train(wiring, np.ones(500), snaps, 20)
    np.testing.assert_array_equal(np.asarray(trained.kc_weights), want_w)
    got = np.asarray(trained.unfamiliarity(np.concatenate([snaps, new])))
    want = [twin.mushroom_unfamiliarity(wiring, want_w, v, 20) for v in np.concatenate([snaps, new])]
    np.testing.assert_allclose(got, want, atol=1e-6)
    assert np.all(got[:4] == 0.0) and np.all(got[4:] > 0.3)


@pytest.mark.parametrize("seed", range(6))
def test_catchment_bounds_are_the_twins_on_random_curves(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 12))
    vals = np.round(rng.random(n) * 4) if seed % 2 else rng.random(n)
    errs = rng.random(n) * 90
    for g in range(n):
        assert tuple(float(v) for v in ca_bounds(jnp.asarray(vals, jnp.float32), g)) == twin.ca_bounds(vals, g)
        assert tuple(float(v) for v in rca_bounds(jnp.asarray(errs, jnp.float32), g)) == twin.rca_bounds(errs, g)


def test_bobs_own_catchment_examples():
    assert [float(v) for v in ca_bounds(jnp.array([1, 2, 0, 2, 3, 1.0]), 2)] == [1, 4]
    assert [float(v) for v in ca_bounds(jnp.array([1, 1, 0, 2, 1.0]), 2)] == [-math.inf, 3]
    assert [float(v) for v in rca_bounds(jnp.array([45, 10, 0, 10, 45.0]), 2)] == [1, 3]
    x = RNG.random(15)
    from scipy.signal import medfilt as scipy_medfilt  # noqa: PLC0415 (the reference)

    np.testing.assert_allclose(np.asarray(medfilt(jnp.asarray(x), 5)), scipy_medfilt(x, 5), atol=1e-6)


def test_route_catchments_of_a_smooth_route_grow_from_its_images():
    """Views that change smoothly along a route: the IDF of every goal rises both ways, so the CA reaches
    the route's ends; a route of repeated views then another scene stops it at the change."""
    base = images(1, 6, 24)[0]
    smooth = np.stack([np.roll(base, k // 2, axis=1) * (1 - 0.02 * k) for k in range(8)])
    out = route_catchments(jnp.asarray(smooth))
    assert np.all(np.asarray(out["ca_size_on_route"]) >= 1)
    assert np.all(np.asarray(out["rca_size_on_route"]) >= 1)
