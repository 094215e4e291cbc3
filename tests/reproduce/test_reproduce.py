"""`delvjax reproduce`: every study at a tiny size, its numbers, tables and the claims table
(the report, resume and bad input: test_runs.py; side by side: test_schedule.py).

Compilation dominates, so the whole set of studies runs ONCE per session (fixture `run`, conftest.py) on a
5 x 5 grid (spacing 200 cm) with 10 trials per success-rate bin; the other tests reuse that
output folder. Tests that change the folder (force, a crash, a new seed) put it back to
"every study current under TINY" before they end, and run only the cheap `environments` /
`landmark_number` studies. The tests of this file run in file order (pytest's default).
"""

from __future__ import annotations

import copy
import csv
import math
import re
from pathlib import Path

import pytest

import delvjax.studies as studies
from delvjax.reproduce import _run as reproduce
from delvjax.studies import claims, thesis
from tests.cases.reproduce import MAY_BE_NAN, METHOD_OF_LABEL, PNG_MAGIC, TINY, VERDICTS, numbers_by_study, read_record

# --- 1. every study at the tiny size --------------------------------------------------------


def test_every_study_ran(run):
    out, result, _ = run
    assert result["ran"] == list(studies.STUDIES)
    assert list(result["records"]) == list(studies.STUDIES)
    assert sorted(p.name for p in out.iterdir() if p.is_dir()) == sorted(studies.STUDIES)


def test_every_figure_of_the_run_passes_a_reviewers_checks(run):
    """No overlapping texts, no label inside another panel, labelled axes (`tests.cases.figures`), on
    every figure every study writes (recorded while the run drew them)."""
    assert run[1]["figure_defects"] == {}


def test_every_verdict_states_its_smallest_sample(run):
    report = (run[0] / "report.md").read_text()
    assert "| smallest sample |" in report
    assert "points in an error-curve bin" in report and "trials per release distance" in report


@pytest.mark.parametrize("name", studies.STUDIES)
def test_study_record_and_files(run, name):
    out, _, _ = run
    module = reproduce.registry([name])[name]
    rec = read_record(out, name)
    assert rec["name"] == name and rec["title"] == module.TITLE
    assert rec["settings"] == reproduce.config_record(TINY)
    assert rec["settings"]["rules"]["default"] == {"first_move": "release", "collisions": "ignore"}
    assert rec["hash"] == reproduce.study_hash(module, TINY)
    assert rec["versions"]["delvjax"] and rec["versions"]["jax"]
    assert rec["seconds"] > 0 and rec["compile_seconds"] >= 0
    assert rec["files"], f"{name} wrote no file"
    for f in rec["files"]:
        assert (out / name / f).is_file(), f"{name}/{f} is listed but missing"
    assert rec["figures"], f"{name} has no figure"
    for fig in rec["figures"]:
        assert fig["file"] in rec["files"] and fig["caption"].strip()
        assert (out / name / fig["file"]).read_bytes()[:8] == PNG_MAGIC, f"{name}/{fig['file']} is not a PNG"
    for t in rec["tables"]:
        assert t["file"] in rec["files"] and t["rows"], f"{name}: table {t['id']} is empty"
        assert set(t["columns"]) <= {k for r in t["rows"] for k in r}


@pytest.mark.parametrize("name", studies.STUDIES)
def test_study_writes_each_file_once(run, name):
    """A file written twice (a table's CSV overwritten by a data file of the same name) loses the first."""
    out, _, _ = run
    rec = read_record(out, name)
    twice = sorted({f for f in rec["files"] if rec["files"].count(f) > 1})
    assert not twice, f"{name} writes {twice} more than once"
    for t in rec["tables"]:  # the report links each table's CSV as its data: it must hold the table
        with open(out / name / t["file"], newline="") as fh:
            csv_rows = list(csv.reader(fh))
        assert csv_rows[0] == list(dict.fromkeys(k for r in t["rows"] for k in r)), (
            f"{name}/{t['file']} does not hold table {t['id']}"
        )
        assert len(csv_rows) == len(t["rows"]) + 1


def test_every_number_is_finite(run):
    out, _, _ = run
    bad = {}
    for name, numbers in numbers_by_study(out).items():
        assert numbers or name == "environments", f"{name} records no number"
        for key, value in numbers.items():
            values = value if isinstance(value, list) else [value]
            ok = bool(values) and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values
            )
            if not ok and not (MAY_BE_NAN.match(key) and value is None):
                bad[f"{name}:{key}"] = value
    assert not bad, f"numbers that are not finite (NaN is written as null): {bad}"


def _table(out: Path, study: str, table_id: str) -> dict:
    tables = {t["id"]: t for t in read_record(out, study)["tables"]}
    assert table_id in tables, f"{study} has no table {table_id} (has {sorted(tables)})"
    return tables[table_id]


def _leading_number(cell):
    """A thesis cell: a number, or text that starts with it ("92.01 (Fig 5.10: 92.01)")."""
    if isinstance(cell, (int, float)):
        return float(cell)
    m = re.match(r"\s*(-?\d+(?:\.\d+)?)", str(cell))
    return float(m.group(1)) if m else None


def _rows_by_key(table: dict) -> dict[tuple, dict]:
    rows = {}
    for r in table["rows"]:
        key = (r["env"].split()[0], METHOD_OF_LABEL[r["method"]], r["k"])
        assert key not in rows, f"{table['id']}: two rows for {key}"
        rows[key] = r
    return rows


@pytest.mark.parametrize(
    "table_id,envs,column,source,field",
    [
        ("table5_1", ("env1", "env2", "env3"), "thesis e>45 %", thesis.ERROR_POINTS["table5_1"], "gt45"),
        ("table5_1", ("env1", "env2", "env3"), "thesis e>90 %", thesis.ERROR_POINTS["table5_1"], "gt90"),
        ("table5_2", ("ring3", "ring4", "ring5", "ring6"), "thesis e>45 %", thesis.ERROR_POINTS["table5_2"], "gt45"),
        ("table5_3", ("env1", "env2", "env3"), "thesis %", thesis.CATCHMENT["table5_3"], None),
        ("table5_4", ("ring3", "ring4", "ring5", "ring6"), "thesis %", thesis.CATCHMENT["table5_4"], None),
    ],
)
def test_occlusion_tables_mirror_the_thesis(run, table_id, envs, column, source, field):
    out, _, _ = run
    table = _table(out, "occlusion", table_id)
    assert column in table["columns"]
    rows = _rows_by_key(table)
    assert {e for e, _, _ in rows} == set(envs)
    for env_name in envs:
        for method in ("delv-compass", "acv", "alv"):
            values = source[env_name][method]
            values = values[field] if field else values
            for k, value in enumerate(values):  # every thesis cell has its row, with the thesis's number
                assert (env_name, method, k) in rows, f"{table_id}: no row {env_name} {method} k={k}"
                assert _leading_number(rows[env_name, method, k][column]) == pytest.approx(value), (
                    f"{table_id} {env_name} {method} k={k}: {rows[env_name, method, k][column]!r} != {value}"
                )
            ks = sorted(k for e, m, k in rows if e == env_name and m == method)
            assert ks == list(range(len(ks))) and len(ks) >= 3


def test_table5_3_shows_both_thesis_numbers_for_env1_delv(run):
    out, _, _ = run
    rows = _rows_by_key(_table(out, "occlusion", "table5_3"))
    for k, (table_value, fig_value) in enumerate(
        zip(thesis.CATCHMENT["table5_3"]["env1"]["delv-compass"], thesis.CATCHMENT["fig5_10"]["env1"]["delv-compass"])
    ):
        cell = str(rows["env1", "delv-compass", k]["thesis %"])
        assert _leading_number(cell) == pytest.approx(table_value)
        assert f"{fig_value:g}" in cell, f"k={k}: Fig 5.10's {fig_value} missing from {cell!r}"
    assert _leading_number(rows["env1", "delv-compass", 0]["thesis %"]) == 92.01


def test_catchment_tables_mirror_the_thesis(run):
    out, _, _ = run
    for study, table_id, column, fig, method in (
        ("no_compass", "catchment_fig4_5", "thesis %", "fig4_5", "delv"),
        ("with_compass", "catchment_fig5_5", "thesis with compass %", "fig5_5", "delv-compass"),
    ):
        rows = {r["env"]: r for r in _table(out, study, table_id)["rows"]}
        assert set(rows) == {"env1", "env2", "env3"}
        for env_name, row in rows.items():
            assert row[column] == pytest.approx(thesis.CATCHMENT[fig][env_name][method][0])
            ours = [v for c, v in row.items() if c.startswith("ours ") and c.endswith(" %")]
            assert len(ours) == 3 and all(0.0 <= v <= 100.0 for v in ours)


def test_numbers_the_claims_read_are_present(run):
    out, _, _ = run
    flat = {k: v for numbers in numbers_by_study(out).values() for k, v in numbers.items()}
    for e in ("env1", "env2", "env3"):
        assert 0.0 <= flat[f"catchment:{e}:delv"] <= 100.0
    for m in ("delv-compass", "acv", "alv"):
        for e in ("env1", "env2", "env3", "ring3", "ring5", "ring6"):
            series = flat[f"occlusion:{e}:{m}:catchment"]
            assert len(series) == {"env1": 3, "env3": 3, "ring3": 3}.get(e, 4)
            assert all(0.0 <= v <= 100.0 for v in series)
    assert len(flat["success:env1:delv"]) == 9  # release distances 50..450 cm


# --- 2. the claims table ---------------------------------------------------------------------


def test_claims_are_evaluated_on_the_real_numbers(run):
    out, _, _ = run
    rows = claims.evaluate(numbers_by_study(out))
    assert [r["id"] for r in rows] == [c["id"] for c in thesis.CLAIMS]
    for r in rows:
        assert r["verdict"] in VERDICTS
        assert r["section"] and r["quote"] and r["statement"]
        if r["id"] in claims.CHECKS and r["id"] not in AWAITING_NUMBERS:  # every study ran: a check finds its numbers
            assert r["verdict"] != "n/a", f"{r['id']}: {r['why']}"
            assert r["ours"], f"{r['id']} shows no number"


# claims whose check reads numbers that no study records yet (n/a until a study provides them)
AWAITING_NUMBERS: set[str] = (
    set()
)  # (delvjax.studies.runs.landmark_number now records error_curve:random{3,4,5}:warping)


def _set(numbers: dict, key: str, value) -> dict:
    numbers = copy.deepcopy(numbers)
    for study_numbers in numbers.values():
        if key in study_numbers:
            study_numbers[key] = value
            return numbers
    raise AssertionError(f"no study records {key}")


def _verdict(numbers: dict, claim_id: str) -> dict:
    return next(r for r in claims.evaluate(numbers) if r["id"] == claim_id)


# claim -> (the numbers that make it fail, the numbers that make it hold)
FLIPS = {
    "delv_success_over_90": (
        {"success:env1:delv": [10.0] * 9},
        {
            "success:env1:delv": [100.0, 100.0, 100.0, 99.0, 98.0, 97.0, 96.0, 94.0, 92.0],  # lowest far away
            "success:env1:delv:physical": [100.0, 100.0, 100.0, 99.0, 98.0, 97.0, 96.0, 94.0, 92.0],
        },
    ),
    "occlusion_increases_errors": (
        {"occlusion:env1:delv-compass:gt45": [30.0, 20.0, 10.0]},
        {"occlusion:env1:delv-compass:gt45": [5.0, 10.0, 20.0]},
    ),
    "delv_nocompass_catchment_all_envs": (
        {"catchment:env1:delv": 10.0, "catchment:env2:delv": 10.0, "catchment:env3:delv": 50.0},
        {"catchment:env1:delv": 98.0, "catchment:env2:delv": 95.0, "catchment:env3:delv": 78.0},
    ),
}


@pytest.mark.parametrize("claim_id", sorted(FLIPS))
def test_claim_verdict_follows_the_numbers(run, claim_id):
    out, _, _ = run
    assert claim_id in claims.CHECKS and claim_id in {c["id"] for c in thesis.CLAIMS}
    real = numbers_by_study(out)
    before = _verdict(real, claim_id)["verdict"]
    assert before in {"holds", "partly", "fails", "cannot tell"}
    breaking, making = FLIPS[claim_id]
    broken, made = real, real
    for key, value in breaking.items():
        broken = _set(broken, key, value)
    for key, value in making.items():
        made = _set(made, key, value)
    assert _verdict(broken, claim_id)["verdict"] == "fails"
    assert _verdict(made, claim_id)["verdict"] == "holds"
    flipped = broken if before in ("holds", "partly") else made
    assert _verdict(flipped, claim_id)["verdict"] != before
    assert numbers_by_study(out) == real  # evaluate() read copies


@pytest.mark.parametrize(
    "study,claim_ids",
    [
        ("occlusion", ("occlusion_increases_errors", "acv_catchment_shrinks_faster")),
        ("image_matching", ("delv_success_over_90", "warping_fails_outside_hull")),
    ],
)
def test_claim_without_its_study_is_not_applicable(run, study, claim_ids):
    out, _, _ = run
    numbers = numbers_by_study(out)
    del numbers[study]
    rows = {r["id"]: r for r in claims.evaluate(numbers)}
    for claim_id in claim_ids:
        assert rows[claim_id]["verdict"] == "n/a", rows[claim_id]
        assert "needs" in rows[claim_id]["why"]
    full = {r["id"]: r["verdict"] for r in claims.evaluate(numbers_by_study(out))}
    assert all(full[c] != "n/a" for c in claim_ids)
