"""The one metrics table (`delvjax.core.metrics.METRICS`, issue 55 point 4): the error point rates' thresholds
written once, each sweep kind's metrics derived from the table, docs/sweeps.md's table rendered from it, and
the >45/>90 rates of a vector map equal on every path that counts them."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import numpy as np

import delvjax
from delvjax import Grid
from delvjax.core import metrics
from delvjax.core.metrics import CATCHMENT_METRICS, FOLLOWING_METRICS, MAP_METRICS, METRICS, SUCCESS_METRICS
from delvjax.sweeps import run_sweep
from delvjax.sweeps._kinds import KINDS
from delvjax.sweeps._spec import metric_units, parse_sweep

ROOT = Path(__file__).resolve().parents[2]
# every module that counts, sums or describes the error point rates (issue 55: "five homes")
PATHS = ("core/metrics.py", "core/cells.py", "core/rollouts/cells.py", "core/rollouts/catchment.py")
PATHS += ("sweeps/_results.py", "sweeps/_kinds/base.py", "sweeps/_kinds/vector_map.py", "sweeps/_kinds/catchment.py")
KIND_METRICS = {
    "vector-map": MAP_METRICS,
    "catchment": CATCHMENT_METRICS + MAP_METRICS,
    "success-rate": SUCCESS_METRICS,
    "route-following": FOLLOWING_METRICS,
}
START, END = "<!-- metrics -->", "<!-- /metrics -->"


def test_the_thresholds_are_written_once():
    """No number 45 or 90 in the code of the rates' paths but `CLASS_EDGES_DEG` (docstrings and descriptions
    are strings, not numbers). Fails on the old code: core/cells.py and core/rollouts/cells.py compared with
    45.0 and 90.0, error_point_rates too."""
    found = []
    for rel in PATHS:
        tree = ast.parse((ROOT / "delvjax" / rel).read_text())
        edges = [n for n in ast.walk(tree) if isinstance(n, ast.Assign) and ast.unparse(n.targets) == "CLASS_EDGES_DEG"]
        allowed = {id(c) for a in edges for c in ast.walk(a.value)}
        found += [
            f"{rel}:{n.lineno} {n.value!r}"
            for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and type(n.value) in (int, float) and n.value in (45, 90)
            if id(n) not in allowed
        ]
    assert not found, found
    assert metrics.CLASS_EDGES_DEG == tuple(m.edge_deg for m in metrics.RATES) == (45.0, 90.0)
    assert [m.name for m in metrics.RATES] == ["gt45_pct", "gt90_pct"]


def test_each_kinds_metrics_are_the_tables():
    """Each sweep kind's metrics (names, order and descriptions) are the table's, and its `metrics_of` returns
    exactly those names, in the units the results write. Fails when a metric is added to a kind, to the table or
    to `sweeps._results` alone."""
    assert set(KINDS) == set(KIND_METRICS)
    for name, rows in KIND_METRICS.items():
        kind = KINDS[name]
        assert list(kind.metrics) == [m.name for m in rows], name
        over = "first directions (points x masks)" if name == "catchment" else "grid points"
        assert list(kind.metrics.values()) == [
            m.description.replace("grid points", over) if m in MAP_METRICS else m.description for m in rows
        ]
        sums = {f.name: np.array([0, 3, 7]) for f in dataclasses.fields(kind.sums)}
        with np.errstate(all="ignore"):
            assert set(kind.metrics_of(sums)) == set(kind.metrics), name
    assert len(METRICS) == len(MAP_METRICS + CATCHMENT_METRICS + SUCCESS_METRICS + FOLLOWING_METRICS)  # no name twice
    assert {n: metric_units(n) for n in METRICS} == {n: m.unit for n, m in METRICS.items()}


def metrics_markdown() -> str:
    """docs/sweeps.md's metrics table, rendered from the table and the kinds."""
    rows = ["| metric | sweep kinds | units | formula | description |", "|---|---|---|---|---|"]
    for m in METRICS.values():
        kinds = ", ".join(k for k, ms in KIND_METRICS.items() if m in ms)
        rows.append(f"| `{m.name}` | {kinds} | {m.unit} | {m.formula} | {m.description} |")
    return "\n".join(rows)


def test_the_docs_table_is_the_metrics_table():
    """docs/sweeps.md's metrics table is `metrics_markdown()` (on a difference, paste the expected block)."""
    doc = (ROOT / "docs" / "sweeps.md").read_text()
    assert doc.count(START) == doc.count(END) == 1
    block = doc[doc.index(START) + len(START) : doc.index(END)].strip()
    assert block == metrics_markdown(), f"docs/sweeps.md's metrics table should read:\n{metrics_markdown()}"


def test_every_path_counts_the_same_rates():
    """ALV on env1 (100 cm grid, 60 deg of bearing noise: some errors > 45 and > 90): the rates of
    `core.metrics.error_point_rates` (a vector map's summary), of `core.cells.map_cells` (a vector-map sweep) and
    of `core.rollouts.cells.catchment_cells` (a catchment sweep's first directions, one mask) equal a NumPy count
    on the vector map's errors. Fails when one path's threshold or comparison (> vs >=) differs."""
    options = {"spacing": 100, "seed": 3, "bearing_noise_deg": 60.0}
    vm = delvjax.vector_map("env1", "alv", seed=3, bearing_noise_deg=60.0, grid=Grid(spacing=100))
    e = np.asarray(vm.error_deg)[np.asarray(vm.included)]
    expected = {"gt45_pct": 100.0 * np.sum(e > 45) / e.size, "gt90_pct": 100.0 * np.sum(e > 90) / e.size}
    assert 0 < expected["gt90_pct"] < expected["gt45_pct"] < 100
    assert metrics.error_point_rates(vm.error_deg, vm.included) == expected
    axes = "\n".join(f"{k} = [{v}]" for k, v in options.items())
    for kind in ("vector-map", "catchment"):
        text = f'[sweep]\nkind = "{kind}"\nmetrics = ["gt45_pct", "gt90_pct", "points"]\n[axes]\n'
        ds = run_sweep(parse_sweep(f'{text}env = ["env1"]\nmethod = ["alv"]\n{axes}\n'))
        assert int(ds.points) == e.size, kind
        assert {k: float(ds[k]) for k in expected} == expected, kind


def test_an_error_curves_interval_stays_within_the_errors_range():
    """A t interval of three small errors reaches below 0 deg: the curve clips it to 0-180 (a mean angular error
    cannot be negative); a bin of one point keeps NaN."""
    error = np.array([1.0, 2.0, 30.0, 179.0, 179.5, 179.9, 90.0])
    points = np.array([[10.0, 0], [20, 0], [30, 0], [60, 0], [70, 0], [80, 0], [120, 0]])
    rows = metrics.error_curve(error, points, np.zeros(2), np.ones(7, bool), bin_width=50.0)
    raw = [metrics.t_interval(error[s], 0.95) for s in (slice(0, 3), slice(3, 6))]
    assert raw[0][0] - raw[0][1] < 0 and raw[1][0] + raw[1][1] > 180  # what the clip is for
    assert rows[0]["ci_lo_deg"] == 0.0 and rows[0]["ci_hi_deg"] == raw[0][0] + raw[0][1]
    assert rows[1]["ci_hi_deg"] == 180.0 and rows[1]["ci_lo_deg"] == raw[1][0] - raw[1][1]
    assert rows[2]["n"] == 1 and np.isnan(rows[2]["ci_lo_deg"]) and np.isnan(rows[2]["ci_hi_deg"])
