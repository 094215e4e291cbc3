"""The hybrid of thesis §6.3.3 (docs/model.md §4.8): DELV where its matching converges, MinWarping elsewhere."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.core.methods.delv import DELV
from delvjax.core.methods.hybrid import Hybrid
from delvjax.core.methods.minwarping import MinWarping
from delvjax.images import load_database
from delvjax.images._evaluate import database_vector_map

GRID = {"n_alpha": 36, "n_psi": 36}


@pytest.fixture(scope="module")
def maps(small_db):
    db = load_database(small_db, panoramas=True)
    out = {m: database_vector_map(db, m, **({} if m == "delv" else GRID)) for m in ("delv", "minwarping")}
    for rms in (1e-6, 25.0, 1e9):
        out[rms] = database_vector_map(db, "hybrid", rms_max=rms, **GRID)
    return db, out


def test_every_answer_is_one_of_the_two(maps):
    _, out = maps
    d, w = (np.asarray(out[m].direction) for m in ("delv", "minwarping"))
    for rms in (1e-6, 25.0, 1e9):
        h = np.asarray(out[rms].direction)
        same = np.isclose(h, d, atol=1e-5) | np.isclose(h, w, atol=1e-5) | (np.isnan(h) & np.isnan(d))
        assert same.all(), rms


def test_the_threshold_moves_the_choice_from_minwarping_to_delv(maps):
    _, out = maps
    d, w = (np.asarray(out[m].direction) for m in ("delv", "minwarping"))
    inc = np.asarray(out["delv"].included)
    strict, loose = np.asarray(out[1e-6].direction), np.asarray(out[1e9].direction)
    # a residual of 1e-6 cm never converges: MinWarping everywhere it is valid
    wv = np.asarray(out["minwarping"].valid) & inc
    assert np.allclose(strict[wv], w[wv], atol=1e-5)
    # no residual limit: DELV wherever it sees every landmark of home, and more DELV than at 25 cm
    took = lambda h: int(np.sum(np.isclose(h, d, atol=1e-5) & ~np.isclose(d, w, atol=1e-5) & inc))  # noqa: E731
    assert took(loose) >= took(np.asarray(out[25.0].direction)) >= took(strict) == 0
    assert took(loose) > 0


def test_the_hybrid_is_a_method_module():
    h = Hybrid(landmarks=DELV(levels=3), image=MinWarping(n_alpha=36, n_psi=36), rms_max=10.0)
    assert h.reads_panorama() and h.reads_start_view()
    h.check_input(72)
    with pytest.raises(Exception, match="n_alpha"):
        Hybrid().check_input(96)  # the default 72 x 72 hypotheses do not divide 96 columns


def test_the_map_put_together_from_its_parts_is_the_hybrids_map(maps):
    """The `hybrid` study computes MinWarping once: DELV's map, MinWarping's and the gate's (where DELV
    converged) give the hybrid's map bit for bit, at every threshold."""
    from delvjax.core.methods.hybrid import HybridGate
    from delvjax.studies.runs.hybrid import hybrid_map

    db, out = maps
    for rms in (1e-6, 25.0, 1e9):
        gate = database_vector_map(db, HybridGate(), rms_max=rms)
        put = hybrid_map(out["delv"], gate, out["minwarping"])
        for field in ("direction", "valid", "error_deg"):
            np.testing.assert_array_equal(np.asarray(getattr(put, field)), np.asarray(getattr(out[rms], field)))


def test_an_exact_fit_converges_though_rounding_leaves_its_variance_below_zero(untyped):
    """Eq 3.5's minimised sum is a difference of sums: where the fit is exact, rounding can leave it a
    hair below 0 (seen at a point beside home of the robot world, 128 points at a time); its RMS is 0,
    not NaN, so DELV's answer counts as converged (the views are stand-ins: `untyped`)."""
    import jax.numpy as jnp

    from delvjax.core.methods import hybrid as hybrid_module

    class Exact(DELV):
        def fit(self, home, view):
            return jnp.float32(0.5), jnp.bool_(True), {"var": jnp.float32(-3e-7), "n": 4, "n_home": 4, "n_current": 4}

    h = hybrid_module.Hybrid(landmarks=Exact())
    angle, valid, converged = h.landmark_answer(None, None)
    assert bool(valid) and bool(converged)
