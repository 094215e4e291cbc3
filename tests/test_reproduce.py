"""`delvjax reproduce`: every study at a tiny size, the claims table, the report, resume, bad input.

Compilation dominates, so the whole set of studies runs ONCE (module fixture `run`) on a
5 x 5 grid (spacing 200 cm) with 10 trials per success-rate bin; the other tests reuse that
output folder. Tests that change the folder (force, a crash, a new seed) put it back to
"every study current under TINY" before they end, and run only the cheap `environments` /
`landmark_number` studies. The tests of this file run in file order (pytest's default).
"""

from __future__ import annotations

import base64
import copy
import csv
import json
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from delvjax import reproduce
from delvjax.cli import main

import studies
from studies import claims, thesis
from studies.common import LABEL

TINY = reproduce.Settings(spacing=200.0, trials=10)
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
METHOD_OF_LABEL = {v: k for k, v in LABEL.items()}
VERDICTS = {"holds", "partly", "fails", "n/a"}
# Numbers documented as NaN (JSON null) when their region is empty: e > 45 % inside / outside the
# landmarks' convex hull (studies.common.map_numbers) when no grid point lies there.
MAY_BE_NAN = re.compile(r"^map:[^:]+:delv:gt45_(inside|outside)_hull_pct$")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """Every study once at the tiny size: (output folder, result of reproduce(), seconds)."""
    out = tmp_path_factory.mktemp("reproduce") / "results"
    t0 = time.perf_counter()
    result = reproduce.reproduce(out, settings=TINY, progress=False)
    return out, result, time.perf_counter() - t0


def read_record(out: Path, name: str) -> dict:
    return json.loads((out / name / reproduce.STUDY_FILE).read_text())


def numbers_by_study(out: Path) -> dict[str, dict]:
    return {name: read_record(out, name)["numbers"] for name in studies.STUDIES}


def dot_files(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob(".*"))


# --- 1. every study at the tiny size --------------------------------------------------------

def test_every_study_ran(run):
    out, result, _ = run
    assert result["ran"] == list(studies.STUDIES)
    assert list(result["records"]) == list(studies.STUDIES)
    assert sorted(p.name for p in out.iterdir() if p.is_dir()) == sorted(studies.STUDIES)


@pytest.mark.parametrize("name", studies.STUDIES)
def test_study_record_and_files(run, name):
    out, _, _ = run
    module = reproduce.registry([name])[name]
    rec = read_record(out, name)
    assert rec["name"] == name and rec["title"] == module.TITLE
    assert rec["settings"] == reproduce.settings_record(TINY)
    assert rec["settings"]["rules"]["default"] == {"first_move": "homing", "collisions": "ignore"}
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
        assert csv_rows[0] == list(dict.fromkeys(k for r in t["rows"] for k in r)), \
            f"{name}/{t['file']} does not hold table {t['id']}"
        assert len(csv_rows) == len(t["rows"]) + 1


def test_every_number_is_finite(run):
    out, _, _ = run
    bad = {}
    for name, numbers in numbers_by_study(out).items():
        assert numbers or name == "environments", f"{name} records no number"
        for key, value in numbers.items():
            values = value if isinstance(value, list) else [value]
            ok = bool(values) and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                                      for v in values)
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


@pytest.mark.parametrize("table_id,envs,column,source,field", [
    ("table5_1", ("env1", "env2", "env3"), "thesis e>45 %", thesis.ERROR_POINTS["table5_1"], "gt45"),
    ("table5_1", ("env1", "env2", "env3"), "thesis e>90 %", thesis.ERROR_POINTS["table5_1"], "gt90"),
    ("table5_2", ("ring3", "ring4", "ring5", "ring6"), "thesis e>45 %", thesis.ERROR_POINTS["table5_2"], "gt45"),
    ("table5_3", ("env1", "env2", "env3"), "thesis %", thesis.CATCHMENT["table5_3"], None),
    ("table5_4", ("ring3", "ring4", "ring5", "ring6"), "thesis %", thesis.CATCHMENT["table5_4"], None),
])
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
                assert _leading_number(rows[env_name, method, k][column]) == pytest.approx(value), \
                    f"{table_id} {env_name} {method} k={k}: {rows[env_name, method, k][column]!r} != {value}"
            ks = sorted(k for e, m, k in rows if e == env_name and m == method)
            assert ks == list(range(len(ks))) and len(ks) >= 3


def test_table5_3_shows_both_thesis_numbers_for_env1_delv(run):
    out, _, _ = run
    rows = _rows_by_key(_table(out, "occlusion", "table5_3"))
    for k, (table_value, fig_value) in enumerate(zip(thesis.CATCHMENT["table5_3"]["env1"]["delv-compass"],
                                                     thesis.CATCHMENT["fig5_10"]["env1"]["delv-compass"])):
        cell = str(rows["env1", "delv-compass", k]["thesis %"])
        assert _leading_number(cell) == pytest.approx(table_value)
        assert f"{fig_value:g}" in cell, f"k={k}: Fig 5.10's {fig_value} missing from {cell!r}"
    assert _leading_number(rows["env1", "delv-compass", 0]["thesis %"]) == 92.01


def test_catchment_tables_mirror_the_thesis(run):
    out, _, _ = run
    for study, table_id, column, fig, method in (("no_compass", "catchment_fig4_5", "thesis %", "fig4_5", "delv"),
                                                 ("with_compass", "catchment_fig5_5", "thesis with compass %",
                                                  "fig5_5", "delv-compass")):
        rows = {r["env"]: r for r in _table(out, study, table_id)["rows"]}
        assert set(rows) == {"env1", "env2", "env3"}
        for env_name, row in rows.items():
            assert row[column] == pytest.approx(thesis.CATCHMENT[fig][env_name][method][0])
            ours = [v for c, v in row.items() if c.startswith("ours ") and c.endswith(" %")]
            assert len(ours) == 2 and all(0.0 <= v <= 100.0 for v in ours)


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
        if r["id"] in claims.CHECKS:  # every study ran: a written check must find its numbers
            assert r["verdict"] != "n/a", f"{r['id']}: {r['why']}"
            assert r["ours"], f"{r['id']} shows no number"


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
        {"success:env1:delv": [100.0] * 9, "success:env1:delv:physical": [100.0] * 9}),
    "occlusion_increases_errors": (
        {"occlusion:env1:delv-compass:gt45": [30.0, 20.0, 10.0]},
        {"occlusion:env1:delv-compass:gt45": [5.0, 10.0, 20.0]}),
    "delv_nocompass_catchment_all_envs": (
        {"catchment:env1:delv": 10.0, "catchment:env2:delv": 10.0, "catchment:env3:delv": 50.0},
        {"catchment:env1:delv": 98.0, "catchment:env2:delv": 95.0, "catchment:env3:delv": 78.0}),
}


@pytest.mark.parametrize("claim_id", sorted(FLIPS))
def test_claim_verdict_follows_the_numbers(run, claim_id):
    out, _, _ = run
    assert claim_id in claims.CHECKS and claim_id in {c["id"] for c in thesis.CLAIMS}
    real = numbers_by_study(out)
    before = _verdict(real, claim_id)["verdict"]
    assert before in {"holds", "partly", "fails"}
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


@pytest.mark.parametrize("study,claim_ids", [
    ("occlusion", ("occlusion_increases_errors", "acv_catchment_shrinks_faster")),
    ("image_matching", ("delv_success_over_90", "warping_fails_outside_hull")),
])
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


# --- 3. the report ---------------------------------------------------------------------------

def test_report_is_self_contained_with_claims_settings_versions(run):
    out, result, _ = run
    html_path, md_path = out / "report.html", out / "report.md"
    assert result["report"] == html_path and html_path.is_file() and md_path.is_file()
    html, md = html_path.read_text(), md_path.read_text()
    sources = re.findall(r'src="([^"]*)"', html)
    n_figures = sum(len(read_record(out, n)["figures"]) for n in studies.STUDIES)
    assert len(sources) == n_figures
    for src in sources:
        assert src.startswith("data:image/png;base64,"), f"report.html points to a file: {src[:80]}"
        assert base64.b64decode(src.split(",", 1)[1])[:8] == PNG_MAGIC
    for link in re.findall(r"\]\(([^)\s]+\.(?:png|csv))\)", md):  # report.md links files beside it
        assert (out / link).is_file(), link
    # the claims table, with the computed counts
    rows = claims.evaluate(numbers_by_study(out))
    counts = {v: sum(r["verdict"] == v for r in rows) for v in VERDICTS}
    summary = f"{counts['holds']} hold, {counts['partly']} partly, {counts['fails']} fail"
    assert f"<strong>{summary}" in html and f"of {len(thesis.CLAIMS)} claims" in html
    assert "Claims of the thesis" in html and "Claims of the thesis" in md
    for claim in thesis.CLAIMS:
        assert claim["section"] in md
    # the settings and the versions
    from delvjax import __version__
    import jax

    assert re.search(rf"<td>seed</td>\s*<td>{TINY.seed}</td>", html)
    assert re.search(r"<td>spacing</td>\s*<td>200(\.0+)?</td>", html)
    assert re.search(rf"<td>trials</td>\s*<td>{TINY.trials}</td>", html)
    assert re.search(rf"<td>version of delvjax</td>\s*<td>{re.escape(__version__)}</td>", html)
    assert re.search(rf"<td>version of jax</td>\s*<td>{re.escape(jax.__version__)}</td>", html)
    for name in studies.STUDIES:  # every study has its section
        assert f"Study <code>{name}</code>" in html


# --- 4. resume ---------------------------------------------------------------------------------

def test_second_run_does_nothing_and_is_fast(run):
    out, first, _ = run
    t0 = time.perf_counter()
    again = reproduce.reproduce(out, settings=TINY, progress=False)
    seconds = time.perf_counter() - t0
    assert again["ran"] == []
    assert seconds < 10.0, f"a run with nothing to do took {seconds:.1f} s"
    assert list(again["records"]) == list(studies.STUDIES)
    for name in studies.STUDIES:  # the records are those of the first run, read back
        assert again["records"][name].hash == first["records"][name].hash
        assert again["records"][name].numbers == read_record(out, name)["numbers"]


def test_force_reruns_the_selected_study(run):
    out, _, _ = run
    before = (out / "environments" / reproduce.STUDY_FILE).stat().st_mtime_ns
    others = {n: (out / n / reproduce.STUDY_FILE).stat().st_mtime_ns for n in studies.STUDIES if n != "environments"}
    result = reproduce.reproduce(out, settings=TINY, only="environments", force=True, progress=False)
    assert result["ran"] == ["environments"]
    assert list(result["records"]) == list(studies.STUDIES)  # the report still shows every study
    assert (out / "environments" / reproduce.STUDY_FILE).stat().st_mtime_ns != before
    assert {n: (out / n / reproduce.STUDY_FILE).stat().st_mtime_ns for n in others} == others


def test_missing_record_or_file_reruns_only_that_study(run):
    out, _, _ = run
    (out / "landmark_number" / reproduce.STUDY_FILE).unlink()  # killed before its study.json
    fig = read_record(out, "step_distance")["figures"][0]["file"]
    (out / "step_distance" / fig).unlink()  # a listed file lost
    result = reproduce.reproduce(out, settings=TINY, progress=False)
    assert result["ran"] == ["step_distance", "landmark_number"]
    assert (out / "landmark_number" / reproduce.STUDY_FILE).is_file()
    assert (out / "step_distance" / fig).read_bytes()[:8] == PNG_MAGIC
    assert reproduce.reproduce(out, settings=TINY, progress=False)["ran"] == []


def test_crash_mid_study_leaves_it_incomplete_then_resumes(run, monkeypatch):
    out, _, _ = run
    module = reproduce.registry(["environments"])["environments"]
    record = out / "environments" / reproduce.STUDY_FILE
    record.unlink()

    def killed(ctx):
        ctx.json("partial.json", {"written": "before the crash"})
        raise RuntimeError("killed mid-way")

    monkeypatch.setattr(module, "run", killed)
    with pytest.raises(RuntimeError, match="killed mid-way"):
        reproduce.reproduce(out, settings=TINY, progress=False)
    assert not record.exists(), "a crashed study must not look complete"
    assert (out / "environments" / "partial.json").is_file()
    assert dot_files(out) == []
    monkeypatch.undo()
    result = reproduce.reproduce(out, settings=TINY, progress=False)
    assert result["ran"] == ["environments"]
    assert reproduce.is_current(out / "environments", reproduce.study_hash(module, TINY))


def test_a_figure_that_fails_leaves_its_study_incomplete(run, monkeypatch):
    """Figures are drawn on a second thread and study.json is written after them: a figure that
    cannot be drawn raises from reproduce(), and its study has no study.json (it runs again)."""
    import matplotlib.pyplot as plt

    out, _, _ = run
    module = reproduce.registry(["environments"])["environments"]
    record = out / "environments" / reproduce.STUDY_FILE
    record.unlink()

    def broken_figure(ctx):
        fig, _ = plt.subplots()

        def fail(*args, **kwargs):
            raise RuntimeError("cannot draw")

        fig.savefig = fail
        ctx.figure("broken.png", fig, "a figure that fails")

    monkeypatch.setattr(module, "run", broken_figure)
    with pytest.raises(RuntimeError, match="cannot draw"):
        reproduce.reproduce(out, settings=TINY, progress=False)
    assert not record.exists()
    assert not (out / "environments" / "broken.png").exists()
    assert dot_files(out) == []
    monkeypatch.undo()
    assert reproduce.reproduce(out, settings=TINY, progress=False)["ran"] == ["environments"]


def test_changed_settings_rerun(run):
    out, _, _ = run
    other = reproduce.Settings(spacing=TINY.spacing, trials=TINY.trials, seed=TINY.seed + 1)
    result = reproduce.reproduce(out, settings=other, only="environments", progress=False)
    assert result["ran"] == ["environments"]
    assert read_record(out, "environments")["settings"]["seed"] == TINY.seed + 1
    assert list(result["records"]) == ["environments"]  # records of other settings are not reported
    assert re.search(rf"<td>seed</td>\s*<td>{TINY.seed + 1}</td>", (out / "report.html").read_text())
    back = reproduce.reproduce(out, settings=TINY, only="environments", progress=False)
    assert back["ran"] == ["environments"]
    assert list(back["records"]) == list(studies.STUDIES)
    assert reproduce.reproduce(out, settings=TINY, progress=False)["ran"] == []


# --- 5. atomic writes ----------------------------------------------------------------------------

def test_no_temporary_files_are_left(run):
    out, _, _ = run
    assert (out / "report.html").is_file()
    assert dot_files(out) == [], "io.atomic_path left temporary files"


# --- 6. bad input --------------------------------------------------------------------------------

def _error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert err[0].startswith("delvjax: error: ")
    return err[0]


def test_unknown_study_is_rejected_before_any_work(tmp_path, capsys):
    target = tmp_path / "x"
    assert main(["reproduce", "--only", "nosuch", "--out", str(target)]) == 2
    line = _error_line(capsys)
    assert "nosuch" in line and "--only" in line
    assert not target.exists()
    assert main(["reproduce", "--only", "environments,nosuch2", "--out", str(target)]) == 2
    assert "nosuch2" in _error_line(capsys)
    assert not target.exists()
    assert main(["reproduce", "--only", " , ", "--out", str(target)]) == 2
    assert "--only" in _error_line(capsys)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("mode", [0o644, 0o755])
def test_out_under_a_file_is_rejected(tmp_path, capsys, mode):
    blocker = tmp_path / "file.txt"
    blocker.write_text("not a folder")
    blocker.chmod(mode)  # 0o755: root's os.access(X_OK) is true for an executable file
    for out in (blocker / "sub", blocker / "sub" / "deeper"):
        assert main(["reproduce", "--only", "environments", "--out", str(out)]) == 2
        line = _error_line(capsys)
        assert "--out" in line and str(out) in line
    assert main(["reproduce", "--only", "environments", "--out", str(blocker)]) == 2
    assert "--out" in _error_line(capsys)
    assert [p.name for p in tmp_path.iterdir()] == ["file.txt"] and blocker.read_text() == "not a folder"


def test_list_prints_every_study(capsys):
    assert main(["reproduce", "--list"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert [line.split()[0] for line in lines] == list(studies.STUDIES)
    for line, module in zip(lines, reproduce.registry().values()):
        assert module.TITLE in line


# --- 7. importable from outside the repository ---------------------------------------------------

def test_studies_importable_outside_the_repo(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    proc = subprocess.run([sys.executable, "-c", "import studies, delvjax.reproduce as r; print(list(r.registry()))"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    printed = proc.stdout.strip().splitlines()[-1]
    for name in studies.STUDIES:
        assert repr(name) in printed
