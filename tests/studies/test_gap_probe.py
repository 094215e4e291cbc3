"""The gap probe (`studies/runs/_gap_probe.py`, `causes_probe --gaps`, the method variants of `_gap_methods`): its
bands per thesis number, the committed file's consistency, the writer's merge, and ACV's nearest-bearing variant."""

from __future__ import annotations

import json

import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.options import METHODS
from delvjax.studies.runs import _gap_probe, causes_probe
from delvjax.studies.runs._common import env
from delvjax.studies.runs._ensemble_stats import SOURCE_LABEL, thesis_numbers
from delvjax.studies.runs._gap_methods import ACV_AGENT, ACV_NEAREST, ALV_MEAN, register_variants, unregister_variants

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
        a = delvjax.vector_map(e, method="acv", seed=0, grid=Grid(spacing=100.0))
        b = delvjax.vector_map(e, method=ACV_NEAREST, seed=0, grid=Grid(spacing=100.0))
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


def test_alv_mean_is_alv_with_every_landmark_and_recovers_env3_with_one_hidden():
    """Averaged and summed unit vectors point alike where the view holds every landmark as its own blob; with one of
    env3's four landmarks hidden the sum loses a whole unit vector (error points everywhere), the average only its
    share (the thesis's 4.87 %, Table 5.1)."""
    register_variants()
    try:
        e = env("env3")
        rates = {}
        for m in ("alv", ALV_MEAN):
            vm = [delvjax.vector_map(e, method=m, seed=0, hidden=h, grid=Grid(spacing=100.0)) for h in (None, [1])]
            rates[m] = [100.0 * float((np.asarray(v.error_deg)[np.asarray(v.included)] > 45.0).mean()) for v in vm]
    finally:
        unregister_variants()
    assert ALV_MEAN not in METHODS
    assert rates[ALV_MEAN][0] == 0.0 and rates["alv"][0] > 5.0  # merged blobs: the sum errs, the average not
    assert rates[ALV_MEAN][1] < 10.0 < 30.0 < rates["alv"][1]


def test_acv_agent_is_acv_with_every_landmark_and_differs_with_one_hidden():
    """With every landmark seen a cyclic shift only relabels the pairs, so the agent-frame list gives ACV's direction
    wherever the view holds as many blobs as home (inside env2's square, where no two landmarks merge; beyond it,
    on a diagonal, two do); with one hidden the list's wrap point moves and they part."""
    register_variants()
    try:
        e = env("env2")
        a = [delvjax.vector_map(e, method="acv", seed=0, hidden=h, grid=Grid(spacing=100.0)) for h in (None, [0])]
        b = [delvjax.vector_map(e, method=ACV_AGENT, seed=0, hidden=h, grid=Grid(spacing=100.0)) for h in (None, [0])]
    finally:
        unregister_variants()
    pts = np.asarray(a[0].points)
    inc = np.asarray(a[0].included) & (np.abs(pts - 500.0).max(axis=1) < 170.0)
    full = [np.asarray(v.error_deg)[inc] for v in (a[0], b[0])]
    assert inc.sum() >= 9 and np.allclose(full[0], full[1], atol=1e-3)
    hid = [np.asarray(v.error_deg)[inc] for v in (a[1], b[1])]
    assert np.abs(hid[0] - hid[1]).max() > 45.0


def test_probes_run_each_family_up_to_its_own_k():
    probe = _gap_probe.Probe("t", "c", "h", ("ring3", "ring5", "ring6", "env1"))
    assert _gap_probe.k_groups(probe) == {2: ("ring3", "env1"), 3: ("ring5", "ring6")}
    assert "occlude = [0, 1, 2, 3]" in _gap_probe.sweep_text(probe, ["x"], 100.0, 0, 3)
    short = _gap_probe.Probe("t", "c", "h", ("ring5",), k_max=2)
    assert _gap_probe.k_groups(short) == {2: ("ring5",)}


def test_a_probe_band_one_grid_point_short_still_names_its_cause_after_those_that_hold_it():
    row = {"source": "Table 5.2", "world": "ring5", "method": "acv", "k": 0, "quantity": "e>90 %", "thesis": 7.1}
    near = row | {"probe": "a", "inside": False, "lo": 0.0, "hi": 6.5, "net": 2}
    holds = row | {"probe": "b", "inside": True, "lo": 0.0, "hi": 8.0, "net": 0}
    far = row | {"probe": "c", "inside": False, "lo": 0.0, "hi": 5.0, "net": 5}
    assert [p["probe"] for p in _gap_probe.matching(row, [near, holds, far], step=1.0)] == ["b", "a"]
    assert _gap_probe.matching(row, [near, far]) == []


def test_one_choice_bands_run_from_the_worst_choice_to_the_best():
    """A one-choice probe's catchment band: the 5th percentile of the members' worst mask to the 95th of their best
    (one choice lies between its world's two); no rate rows (a sweep pools them over the masks: the default's
    band, no alternative's); the sweep asks for both metrics."""
    probe = _gap_probe.Probe("t", "c", "h", ("env1",), k_max=2, choice=True)
    measured = fake_measure(probe, members=11)
    for (f, run, q), v in list(measured.items()):
        if q == "catchment":
            measured[(f, run, "catchment_min")] = v - 5.0
            measured[(f, run, "catchment_max")] = v + 5.0
    rows = _gap_probe.probe_rows(probe, measured)
    catch = [r for r in rows if r["quantity"] == "catchment %"]
    rates = [r for r in rows if r["quantity"] != "catchment %"]
    assert catch and all((r["lo"], r["median"], r["hi"]) == (0.0, 50.0, 100.0) for r in catch)
    assert not rates
    assert '"catchment_min_pct", "catchment_max_pct"' in _gap_probe.sweep_text(probe, ["x"], 100.0, 0)
    assert "catchment_min_pct" not in _gap_probe.sweep_text(PROBE, ["x"], 100.0, 0)


def test_choice_maps_give_each_member_its_mean_worst_and_best_choice():
    probe = _gap_probe.Probe("t", "c", "h", ("ring3",), methods=(("alv", "alv"),), k_max=1, choice=True)
    out = causes_probe.choice_maps(probe, members=2, spacing=200.0)
    mean, lo, hi = (out[("ring3", "alv", "gt45" + s)] for s in ("", "_min", "_max"))
    assert mean.shape == (2, 2) and np.all(lo <= mean) and np.all(mean <= hi)
    assert np.array_equal(lo[:, 0], hi[:, 0])  # k = 0: one choice
    rows = _gap_probe.probe_rows(probe, out)
    assert {r["quantity"] for r in rows} == {"e>45 %", "e>90 %"} and all(r["world"] == "ring3" for r in rows)
