"""The fit of the thesis's unstated settings (`studies/runs/fit.py`, docs/reproduce.md "The fit of the
unstated settings"): its targets and objective, its search on synthetic objectives, and the study's
reduced design end to end."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from delvjax.reproduce import _run as reproduce
from delvjax.studies.runs import (
    _fit_causes as fit_causes,
    _fit_design as fit_design,
    _fit_cells as fit_cells,
    _fit_model as fit_model,
)
from delvjax.studies import thesis
from delvjax.studies.thesis._notes import NOTES


def test_targets_are_the_thesis_numbers_of_the_seven_tables_without_the_copied_rows():
    items = fit_model.targets()
    per_table = {t: sum(i.table == t for i in items) for t in fit_model.TABLES}
    # Figs 4.5, 5.5: three envs; Fig 5.10: k = 0..2; Tables 5.1/5.3: 3 envs x 3 methods x k = 0..2 (5.1: two
    # fields); Tables 5.2/5.4 without ring4: ring3 (k = 0..2) and ring5, ring6 (k = 0..3), 3 methods.
    assert per_table == {
        "fig4_5": 3,
        "fig5_5": 3,
        "fig5_10": 3,
        "table5_1": 54,
        "table5_2": 66,
        "table5_3": 27,
        "table5_4": 33,
    }
    assert not any(i.env == "ring4" for i in items)
    assert {i.field for i in items} == {"catchment", "gt45", "gt90"}
    acv = next(
        i
        for i in items
        if i.table == "table5_2" and i.env == "ring5" and i.method == "acv" and i.field == "gt90" and i.k == 2
    )
    assert acv.value == thesis.ERROR_POINTS["table5_2"]["ring5"]["acv"]["gt90"][2]
    assert len(fit_model.targets(("table5_3",), ("env1",))) == 9
    cells = fit_model.cells(items)
    assert len(cells) == len(set(cells)) == 63  # 3 DELV + 3 methods x (27 env + 33 ring) (env, method, k)


def test_the_objective_is_zero_when_ours_equals_the_thesis_and_the_mean_gap_otherwise():
    items = fit_model.targets()
    exact = np.array([t.value for t in items])
    zero = fit_model.objective(exact, items)
    assert set(zero) == {"overall", *fit_model.TABLES}
    assert all(float(v[0]) == 0.0 for v in zero.values())
    ours = np.stack([exact, exact + 2.0, exact - 3.0])  # three settings
    obj = fit_model.objective(ours, items)
    assert np.allclose(obj["overall"], [0.0, 2.0, 3.0]) and np.allclose(obj["table5_4"], [0.0, 2.0, 3.0])
    one = exact.copy()
    one[[i for i, t in enumerate(items) if t.table == "fig4_5"][0]] += 30.0  # one number of Fig 4.5 off by 30
    obj = fit_model.objective(one, items)
    assert math.isclose(float(obj["fig4_5"][0]), 10.0) and math.isclose(float(obj["overall"][0]), 30.0 / len(items))
    assert float(obj["table5_1"][0]) == 0.0


def test_align_reads_each_target_from_its_cell_and_field():
    items = fit_model.targets(("fig5_10", "table5_1"), ("env1",))
    cells = fit_model.cells(items)
    values = {
        f: np.arange(2 * len(cells), dtype=float).reshape(2, len(cells)) + 1000 * j
        for j, f in enumerate(("catchment", "gt45", "gt90"))
    }
    ours = fit_model.align(values, cells, items)
    assert ours.shape == (2, len(items))
    for i, t in enumerate(items):
        j = cells.index(t.cell)
        assert ours[1, i] == values[t.field][1, j]


GRID = {"a": (0.0, 1.0, 2.0, 3.0), "b": (0.0, 0.5, 1.0), "c": (10.0, 20.0)}
DEFAULT = {"a": 0.0, "b": 0.0, "c": 10.0}


def counting(f):
    calls = []

    def evaluate(points):
        calls.append(len(points))
        return [f(p) for p in points]

    return evaluate, calls


def test_the_search_finds_the_minimiser_of_a_separable_objective_in_two_batches():
    evaluate, calls = counting(lambda p: (p["a"] - 2.0) ** 2 + 3 * (p["b"] - 0.5) ** 2 + 0.01 * (p["c"] - 20.0) ** 2)
    res = fit_model.search(evaluate, GRID, DEFAULT)
    assert res.fitted == {"a": 2.0, "b": 0.5, "c": 20.0}
    assert len(calls) == 2 and calls[0] == 1 + 3 + 2 + 1  # defaults + one setting at a time, then the joint batch
    assert res.joint == ("a", "c")  # the two largest gains on the defaults (4 and 1; b: 0.75)
    assert [v for v, _ in res.profiles["a"]] == [0.0, 1.0, 2.0, 3.0]
    assert min(e["objective"] for e in res.evaluated) == 0.0


def test_the_joint_factorial_finds_an_interaction_one_setting_at_a_time_misses():
    """From the defaults a = 1 looks best and b = 1 too; jointly a = 2, b = 1 is the minimum (an interaction)."""
    table = {
        (0.0, 0.0): 10.0,
        (1.0, 0.0): 8.0,
        (2.0, 0.0): 9.0,
        (3.0, 0.0): 12.0,
        (0.0, 0.5): 11.0,
        (0.0, 1.0): 7.0,
        (1.0, 1.0): 6.0,
        (2.0, 1.0): 1.0,
        (1.0, 0.5): 9.0,
        (2.0, 0.5): 9.0,
    }
    evaluate, calls = counting(lambda p: table.get((p["a"], p["b"]), 50.0) + 0.01 * (p["c"] - 10.0))
    res = fit_model.search(evaluate, GRID, DEFAULT)
    assert res.fitted == {"a": 2.0, "b": 1.0, "c": 10.0}
    assert res.joint == ("b", "a") and len(calls) == 2  # gains 3 and 2 on the defaults; c only loses
    brute = min(
        ((a, b, c) for a in GRID["a"] for b in GRID["b"] for c in GRID["c"]),
        key=lambda x: table.get(x[:2], 50.0) + 0.01 * (x[2] - 10.0),
    )
    assert brute == (2.0, 1.0, 10.0)


def test_the_fitted_point_is_the_best_evaluated_and_never_worse_than_the_defaults():
    rng = np.random.default_rng(5)
    values = {}

    def f(p):
        return values.setdefault(tuple(sorted(p.items())), float(rng.uniform(0, 10)))

    evaluate, _ = counting(f)
    res = fit_model.search(evaluate, GRID, DEFAULT)
    best = min(res.evaluated, key=lambda e: e["objective"])
    assert res.fitted == best["point"] and best["objective"] <= f(DEFAULT)
    assert fit_model.describe(DEFAULT, DEFAULT) == "defaults"
    assert fit_model.describe({**DEFAULT, "a": 2.0, "c": 20.0}, DEFAULT) == "a=2, c=20"


def test_every_unreached_number_gets_the_cause_its_case_calls_for():
    T = fit_model.Target
    assert fit_causes.likely_cause(T("table5_4", "ring5", "delv-compass", 3, "catchment", 2.96), 44.7).endswith(
        "(thesis note table5_4_k3_delv_equal)"
    )
    assert all(note in NOTES for note in fit_causes.NOTED.values())
    assert fit_causes.likely_cause(T("fig5_5", "env3", "delv-compass", 0, "catchment", 84.91), 100.0).startswith(
        "ceiling"
    )
    assert not fit_causes.likely_cause(T("fig5_5", "env3", "delv-compass", 0, "catchment", 84.91), 97.0).startswith(
        "ceiling"
    )  # below the ceiling under the defaults: another cause
    assert "per-choice" in fit_causes.likely_cause(T("table5_3", "env1", "delv-compass", 1, "catchment", 49.11), 75.4)
    # the two env3 numbers of the last full run: the layout probe (studies/runs/causes_probe.py) explains them
    assert fit_causes.likely_cause(T("table5_3", "env3", "delv-compass", 1, "catchment", 69.08), 99.6).startswith(
        "env3's coordinates"
    )
    assert fit_causes.likely_cause(T("table5_1", "env3", "acv", 0, "gt45", 33.33), 57.8).startswith(
        "env3's coordinates"
    )
    assert fit_causes.likely_cause(T("table5_3", "env2", "delv-compass", 1, "catchment", 53.96), 99.0).startswith(
        "not explained: ours keeps >= 95"
    )  # the same case on another layout stays unexplained
    assert "rings" in fit_causes.likely_cause(T("table5_4", "ring6", "acv", 1, "catchment", 77.96), 39.6)
    assert fit_causes.likely_cause(T("table5_1", "env1", "acv", 0, "gt45", 9.8), 40.0).startswith("not explained")


def test_scaled_environments_keep_centres_and_scale_radii():
    e, big = fit_cells.scaled_env("env1", 1.0), fit_cells.scaled_env("env1", 1.5)
    assert big.landmarks.shape == e.landmarks.shape  # padded alike: one program
    lm, lb = np.asarray(e.landmarks)[np.asarray(e.valid)], np.asarray(big.landmarks)[np.asarray(big.valid)]
    assert np.allclose(lb[:, :2], lm[:, :2]) and np.allclose(lb[:, 2], 1.5 * lm[:, 2])
    assert fit_cells.env_key("env1", 1.0) == "env1" and fit_cells.env_key("env1", 0.5) == "env1@r0.5"


@pytest.fixture(scope="module")
def tiny_fit(tmp_path_factory):
    out = tmp_path_factory.mktemp("fit")
    settings = reproduce.Settings(spacing=200.0, trials=10)  # the test suite's tiny grid: the reduced design
    result = reproduce.reproduce(out, settings=settings, only="fit", progress=False)
    return out, result


def test_the_reduced_fit_runs_end_to_end_and_writes_its_tables(tiny_fit):
    out, result = tiny_fit
    assert result["ran"] == ["fit"]
    rec = json.loads((out / "fit" / "study.json").read_text())
    ids = [t["id"] for t in rec["tables"]]
    assert ids == ["fit_sensitivity", "fit_effects", "fit_settings", "fit_tables", "fit_unreached", "fit_cost"]
    with open(out / "fit" / "fit_sensitivity.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["settings"] for r in rows] == ["defaults", "bearing_noise_deg=2"]
    n = rec["numbers"]
    assert (
        n["fit:targets"]
        == len(fit_model.targets(fit_design.QUICK_DESIGN["tables"], fit_design.QUICK_DESIGN["envs"]))
        == 90
    )
    assert n["fit:objective:fitted"] <= n["fit:objective:default"]
    assert 0.0 < n["fit:objective:default"] < 100.0 and n["fit:spacing"] == 200.0
    assert all(f"fit:setting:{s}" in n for s in fit_cells.DEFAULTS)
    cost = {r["item"]: r["value"] for r in rec["tables"][-1]["rows"]}
    assert cost["programs compiled"] <= 1 and cost["settings points evaluated"] == 2  # one program for every cell
    with open(out / "fit" / "fit_targets.csv", newline="") as fh:
        targets = list(csv.DictReader(fh))
    assert len(targets) == 90 and all(0.0 <= float(t["ours_default"]) <= 100.0 for t in targets)


def test_a_fit_cell_equals_the_studies_catchment_under_the_default_rules(tiny_fit):
    """The fit's sweep cell (env1, DELV with a compass, k = 1, defaults) gives the numbers of the studies' own
    catchment call (`common.catchment`, every choice of one hidden landmark) on the same grid and seed."""
    from types import SimpleNamespace

    from delvjax.core.rollouts import catchment_summary
    from delvjax.studies.runs import _common as common

    out, _ = tiny_fit
    with open(out / "fit" / "fit_targets.csv", newline="") as fh:
        ours = {
            (r["table"], r["field"]): float(r["ours_default"])
            for r in csv.DictReader(fh)
            if r["env"] == "env1" and r["method"] == "delv-compass" and r["k"] == "1"
        }
    ctx = SimpleNamespace(settings=reproduce.Settings(spacing=200.0, trials=10))
    s = catchment_summary(common.catchment(ctx, common.env("env1"), "delv-compass", occlude=1))
    # the CSV keeps 6 significant digits (`outputs/_files.py`): 7.291666... is written 7.29167
    for table, field, key in [
        ("table5_3", "catchment", "catchment_pct"),
        ("table5_1", "gt45", "gt45_pct"),
        ("table5_1", "gt90", "gt90_pct"),
    ]:
        assert math.isclose(ours[(table, field)], s[key]["mean"], rel_tol=5e-6, abs_tol=1e-6), (field, s[key])


def test_env3_variants_keep_the_description_and_are_reproducible():
    """The layout probe's env3 variants (studies/runs/causes_probe.py): every landmark east of home, inside the
    arena, no overlaps; the same seed gives the same layouts."""
    from delvjax.studies.runs import causes_probe

    a, b = causes_probe.env3_variants(8, 150.0, seed=1), causes_probe.env3_variants(8, 150.0, seed=1)
    assert 0 < len(a) <= 8 and len(a) == len(b)
    for e, f in zip(a, b):
        lm = np.asarray(e.landmarks)[np.asarray(e.valid)]
        assert np.array_equal(lm, np.asarray(f.landmarks)[np.asarray(f.valid)]) and lm.shape == (4, 3)
        assert np.all(lm[:, 0] >= np.asarray(e.home)[0] + causes_probe.EAST_OF_HOME)
        assert np.all(lm[:, 0] + lm[:, 2] <= 1000.0) and np.all(lm[:, 1] - lm[:, 2] >= 0.0)
    moved = np.asarray(a[0].landmarks)[np.asarray(a[0].valid)]
    assert not np.allclose(moved, np.asarray(fit_cells.scaled_env("env3", 1.0).landmarks)[:4])


def test_the_cause_probe_runs_and_reports_per_layout_numbers():
    """`python -m delvjax.studies.runs.causes_probe` at a tiny size (the README's promise): numbers per layout and
    per ring width, percentages in range; env3 unmoved (jitter 0) gives our env3's values."""
    from delvjax.studies.runs import causes_probe

    lay = causes_probe.env3_layouts(n=2, spacing=250.0, acv_jitter=0.0, delv_jitter=0.0, delv_variants=1)
    assert len(lay["acv_gt45_k0_pct"]) == 2 and len(lay["delv_compass_catchment_k1_pct"]) == 1
    assert lay["acv_gt45_k0_pct"][0] == lay["acv_gt45_k0_pct"][1]  # the same layout twice
    assert all(0.0 <= v <= 100.0 for v in lay["acv_gt45_k0_pct"] + lay["delv_compass_catchment_k1_pct"])
    px = causes_probe.pixels(spacing=250.0, ds=(50.0,), widths=(360,))
    assert set(px["env1_mean_error_deg"][360]) == {"d=50"} and 0.0 <= px["env1_mean_error_deg"][360]["d=50"] < 180.0
    assert px["random3_curve_deg"][360] and all(0.0 <= v <= 180.0 for v in px["random3_curve_deg"][360])
