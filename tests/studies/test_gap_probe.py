"""The gap probe (`studies/runs/_gap_probe.py`, `causes_probe --gaps`, the method variants of `_gap_methods`): its
bands per thesis number, the committed file's consistency, the writer's merge, and ACV's nearest-bearing variant."""

from __future__ import annotations

import json

import numpy as np
import pytest

import delvjax
from delvjax.studies.runs import _gap_probe, causes_probe
from delvjax.studies.runs._common import env
from delvjax.studies.runs._ensemble_stats import SOURCE_LABEL, thesis_numbers
from delvjax.options import METHODS
from delvjax.studies.runs._gap_methods import ACV_NEAREST, register_variants, unregister_variants

PROBE = _gap_probe.Probe("t", "a test cause", "a test hypothesis", ("env1",), k_max=2)


def fake_measure(probe, members=16, **_) -> dict:
    """Members' numbers 0, 10, ..., 10 (members - 1) at every k for every quantity of the probe's families."""
    col = 10.0 * np.arange(members)
    return {
        (f, run, q): np.stack([col] * 3, 1)
        for f in probe.families
        for _, run in probe.methods
        for q in _gap_probe.METRIC
    }


def test_probe_rows_give_each_thesis_number_its_band():
    rows = _gap_probe.probe_rows(PROBE, fake_measure(PROBE, members=11))
    wanted = [n for n in thesis_numbers() if n[1] == "env1" and n[2] in ("delv-compass", "acv", "alv")]
    wanted = [n for n in wanted if n[0] in ("table5_1", "table5_3")]
    assert len(rows) == len(wanted) and {r["source"] for r in rows} == {"Table 5.1", "Table 5.3"}
    for r in rows:
        assert (r["lo"], r["median"], r["hi"], r["members"]) == (5.0, 50.0, 95.0, 11)
        assert r["inside"] == (5.0 <= r["thesis"] <= 95.0)
    assert any(r["inside"] for r in rows) and not all(r["inside"] for r in rows)


def test_the_writer_keeps_the_rows_of_probes_it_did_not_run(tmp_path, monkeypatch):
    monkeypatch.setattr(_gap_probe, "measure", fake_measure)
    path = tmp_path / "probes.json"
    causes_probe.gap_probes(["env3-wide"], 4, 100.0, path=path)
    causes_probe.gap_probes(["env3-near"], 4, 100.0, path=path)
    doc = json.loads(path.read_text())
    assert {r["probe"] for r in doc["rows"]} == {"env3-wide", "env3-near"} and doc["members"] == 4
    assert [r["probe"] for r in doc["rows"]][0] == "env3-wide"  # PROBES' order


def test_the_committed_probe_file_is_consistent():
    """Every row's band is ordered, its `inside` true exactly when the band holds the thesis number, and that number
    is the thesis's (a row whose number changed would name a stale cause)."""
    rows = _gap_probe.load_probes()
    assert rows, "run python -m delvjax.studies.runs.causes_probe --gaps"
    numbers = {(SOURCE_LABEL[s], f, m, k, _gap_probe.QUANTITY[q]): v for s, f, m, k, q, v in thesis_numbers()}
    ids = {p.id for p in _gap_probe.PROBES}
    for r in rows:
        assert r["probe"] in ids and r["lo"] <= r["median"] <= r["hi"]
        assert r["inside"] == (r["lo"] <= r["thesis"] <= r["hi"])
        assert numbers[(r["source"], r["world"], r["method"], r["k"], r["quantity"])] == pytest.approx(r["thesis"])


def test_acv_nearest_agrees_with_acv_near_home_and_differs_far_from_it():
    """With every landmark seen, pairing by the nearest bearing is the best cyclic shift while bearings move little
    (near home); far from home the two pairings part."""
    register_variants()
    try:
        e = env("env1")
        a = delvjax.vector_map(e, method="acv", spacing=100.0, seed=0)
        b = delvjax.vector_map(e, method=ACV_NEAREST, spacing=100.0, seed=0)
    finally:
        unregister_variants()  # the registry's methods live in delvjax/core/methods (tests/test_architecture.py)
    assert ACV_NEAREST not in METHODS
    pts = np.asarray(a.points)
    near = np.hypot(pts[:, 0] - 500.0, pts[:, 1] - 500.0) < 150.0
    ea, eb = np.asarray(a.error_deg), np.asarray(b.error_deg)
    assert near.sum() >= 4 and np.allclose(ea[near], eb[near], atol=1e-3)
    assert np.abs(ea - eb)[~near].max() > 45.0


def test_the_net_gain_counts_the_numbers_both_probes_measured():
    base = {"source": "Table 5.1", "world": "env1", "method": "acv", "quantity": "e>45 %", "thesis": 1.0}
    rows = [
        base | {"probe": "default", "k": 0, "inside": True},
        base | {"probe": "default", "k": 1, "inside": False},
        base | {"probe": "default", "k": 2, "inside": False},
        base | {"probe": "x", "k": 0, "inside": False},
        base | {"probe": "x", "k": 1, "inside": True},
        base | {"probe": "x", "k": 2, "inside": True},
        base | {"probe": "x", "k": 3, "inside": True},  # the default did not measure it: not counted
    ]
    out = {(r["probe"], r["k"]): r for r in _gap_probe.with_net(rows)}
    assert out[("x", 3)]["net"] == 1 and out[("x", 0)]["keeps"] == [2, 1, 3]
    assert out[("default", 0)]["net"] == 0
