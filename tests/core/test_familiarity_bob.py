"""bob_robotics' own test data, regenerated: its 100 random 10 x 90 images (std::mt19937(42)) and its
libstdc++ initial InfoMax weights are rebuilt in NumPy (tests/twins/familiarity.py), run through our
RIDF and InfoMax, and compared with numbers read from the tables BoB stores with its tests (at
bob_robotics 8f20a38a): their sums and a few entries, so no file of theirs is shipped. With
BOB_ROBOTICS_DATA pointing at a folder of those .bin files, every entry is compared too.
docs/familiarity.md §4."""

from __future__ import annotations

import os
from pathlib import Path

import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.familiarity.infomax import InfoMax
from delvjax.core.familiarity.ridf import ridf_table, rolled
from tests.twins.familiarity import bob_images, bob_initial_weights, bob_test_mask

AT = [(0, 0), (1, 5), (37, 44), (99, 89), (50, 1), (9, 60)]  # the entries kept from each stored table
STORED = {  # file: (rows, sum of the table, the entries AT; rows beyond the table None)
    "pm": (100, 771402.4909133911, [0.0, 84.21888732910156, 82.02666473388672, 87.79777526855469, 84.2699966430664, 83.49888610839844]),
    "mask_pm": (100, 773375.8650894165, [0.0, 84.58545684814453, 82.32624816894531, 87.59645080566406, 84.82603454589844, 84.32875061035156]),
    "pm_rms": (100, 944537.8150558472, [0.0, 103.00477600097656, 100.54098510742188, 106.82951354980469, 103.31295013427734, 103.14847564697266]),
    "mask_pm_rms": (100, 946881.5200119019, [0.0, 103.41242980957031, 101.10215759277344, 106.84403991699219, 103.82247161865234, 104.0730972290039]),
    "pm_ccoeff": (100, 8757.40224301815, [5.960464477539063e-08, 0.9765569567680359, 0.9259749054908752, 0.9569399952888489, 0.9801766276359558, 0.965129017829895]),
    "mask_pm_ccoeff": (100, 8743.634855926037, [0.0, 0.9729123115539551, 0.9334086775779724, 0.963257908821106, 0.9840454459190369, 0.9730474352836609]),
    "window_pm": (10, 77080.92668151855, [0.0, 84.21888732910156, None, None, None, 83.49888610839844]),
    "window_mask_pm_ccoeff": (10, 873.3851024508476, [0.0, 0.9729123115539551, None, None, None, 0.9730474352836609]),
}  # fmt: skip
KIND = {"pm": "abs", "pm_rms": "rms", "pm_ccoeff": "corr"}
INFOMAX_BIN = (695377.1552734375, [7841.49609375, 7260.17578125, 7761.2392578125, 7898.7001953125, 7800.763671875], 1)
INFOMAX_TRAIN0 = [(0, 0, -0.8121190667152405), (0, 1, 0.8536248803138733), (450, 450, -0.1824418604373932),
                  (900, 899, -0.20971930027008057), (17, 700, 0.8898861408233643)]  # fmt: skip
INFOMAX_DECISION = [
    (0, -15.698721885681152),
    (1, -2.7515687942504883),
    (450, 7.097739219665527),
    (900, -19.733203887939453),
]


def table_of(name: str) -> np.ndarray:
    images = bob_images()
    masked = "mask_" in name
    kind = KIND[name.replace("window_", "").replace("mask_", "")]
    mask = bob_test_mask() if masked else None
    snaps = images[: STORED[name][0]]
    masks = None if mask is None else np.broadcast_to(mask, snaps.shape)
    return np.asarray(ridf_table(images[0], snaps, kind, mask, masks), np.float64)


@pytest.mark.parametrize("name", list(STORED))
def test_the_ridf_tables_match_bobs_stored_ones(name):
    rows, total, entries = STORED[name]
    t = table_of(name)
    assert t.shape == (rows, 90)
    assert t.sum() == pytest.approx(total, rel=1e-6)
    for (i, j), want in zip(AT, entries):
        if want is not None:
            assert t[i, j] == pytest.approx(want, rel=1e-6, abs=1e-6), (i, j)


def test_the_rotation_sense_is_bobs_and_the_other_sense_is_not():
    """Rolling the other way is far from BoB's table: the comparison above would catch a flipped roll."""
    images = bob_images()
    other = np.asarray(ridf_table(images[0], images, "abs", shifts=(-np.arange(90)) % 90), np.float64)
    assert np.abs(other - table_of("pm")).max() > 5.0
    assert abs(other.sum() - STORED["pm"][1]) > 0 or np.abs(other[:, 1:] - table_of("pm")[:, 1:]).max() > 5.0


@pytest.fixture(scope="module")
def bob_infomax():
    w0 = bob_initial_weights(900, 901, seed=42)
    model = InfoMax(weights=jnp.asarray(w0, jnp.float32), learning_rate=1e-4, rate_divisor="hidden")
    return model, bob_images().astype(np.float32)


def test_infomax_after_one_image_matches_bobs_weights(bob_infomax):
    model, images = bob_infomax
    w = np.asarray(model.train(images[:1]).weights)
    for i, j, want in INFOMAX_TRAIN0:
        assert w[i, j] == pytest.approx(want, abs=1e-5)
    assert np.abs(w.mean(1)).max() < 1.0 and abs(np.sqrt((w**2).mean()) - 1.0) < 1e-3  # BoB's scaled weights


def test_infomax_trained_on_the_100_images_matches_bobs_decision_and_rotations(bob_infomax):
    model, images = bob_infomax
    trained = model.train(images)
    u = np.asarray(trained.inputs(jnp.asarray(images[0])) @ trained.weights.T)
    for i, want in INFOMAX_DECISION:
        assert u[i] == pytest.approx(want, abs=1e-3)  # BoB's tolerance
    f = np.asarray(trained.unfamiliarity(rolled(jnp.asarray(images[0]), jnp.arange(90))), np.float64)
    total, entries, best = INFOMAX_BIN
    assert f.sum() == pytest.approx(total, rel=1e-6)
    assert np.allclose(f[[0, 1, 2, 45, 89]], entries, rtol=1e-6)
    assert int(np.argmin(f)) == best


def bin_table(path: Path) -> np.ndarray:
    rows, cols = np.fromfile(path, "<i4", count=2)
    return np.fromfile(path, "<f4", offset=8).reshape(cols, rows).T


@pytest.mark.skipif(not os.environ.get("BOB_ROBOTICS_DATA"), reason="BOB_ROBOTICS_DATA: a folder of BoB's .bin files")
@pytest.mark.parametrize("name", list(STORED))
def test_every_entry_of_bobs_files_where_they_are_at_hand(name):
    path = Path(os.environ["BOB_ROBOTICS_DATA"]) / f"{name}.bin"
    np.testing.assert_allclose(table_of(name), bin_table(path), rtol=1e-5, atol=1e-5)
