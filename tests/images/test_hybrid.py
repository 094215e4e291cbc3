"""The hybrid of thesis §6.3.3 (docs/model.md §4.8): DELV where its matching converges, MinWarping elsewhere."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.core.methods.delv import DELV
from delvjax.core.methods.hybrid import Hybrid
from delvjax.core.methods.minwarping import MinWarping
from delvjax.images import load_database
from delvjax.images._evaluate import database_vector_map

GRID = {"mw_n_alpha": 36, "mw_n_psi": 36}


@pytest.fixture(scope="module")
def maps(small_db):
    db = load_database(small_db, panoramas=True)
    out = {m: database_vector_map(db, m, **({} if m == "delv" else GRID)) for m in ("delv", "minwarping")}
    for rms in (1e-6, 25.0, 1e9):
        out[rms] = database_vector_map(db, "hybrid", hybrid_rms_max=rms, **GRID)
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
    with pytest.raises(Exception, match="mw_n_alpha"):
        Hybrid().check_input(72)
