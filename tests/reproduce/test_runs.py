"""`delvjax reproduce` as a run: the report, resume after a crash or a change, bad input. The session
fixture `run` (tests/conftest.py) is one run of the studies per test session, copied per pytest-xdist
worker; tests that change the folder put it back to "every study current under TINY" before they end."""

from __future__ import annotations

import base64
import json
import os
import re
import subprocess
import sys
import time

import pytest

import delvjax.studies as studies
from delvjax.cli._main import main
from delvjax.reproduce import _run as reproduce
from delvjax.studies import claims, thesis
from tests.cases.reproduce import PNG_MAGIC, TINY, VERDICTS, dot_files, numbers_by_study, read_record

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
    # a table of contents whose every anchor resolves, and no table left as raw text
    anchors = re.findall(r'<a href="#([^"]+)"', html)
    ids = set(re.findall(r'id="([^"]+)"', html))
    assert len(anchors) >= 10 and set(anchors) <= ids and "[TOC]" not in md
    text = re.sub(r"<[^>]+>", "", html)
    assert not re.search(r"^\s*\|.*\|\s*$", text, re.M), "a table rendered as raw pipes"
    assert "A quick preview" not in md  # TINY is not --quick
    for claim in thesis.CLAIMS:
        assert claim["section"] in md
    # the settings and the versions
    import jax

    from delvjax import __version__

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
    again = reproduce.reproduce(out, config=TINY, progress=False)
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
    result = reproduce.reproduce(out, config=TINY, only="environments", force=True, progress=False)
    assert result["ran"] == ["environments"]
    assert list(result["records"]) == list(studies.STUDIES)  # the report still shows every study
    assert (out / "environments" / reproduce.STUDY_FILE).stat().st_mtime_ns != before
    assert {n: (out / n / reproduce.STUDY_FILE).stat().st_mtime_ns for n in others} == others


def test_missing_record_or_file_reruns_only_that_study(run):
    out, _, _ = run
    (out / "landmark_number" / reproduce.STUDY_FILE).unlink()  # killed before its study.json
    fig = read_record(out, "step_distance")["figures"][0]["file"]
    (out / "step_distance" / fig).unlink()  # a listed file lost
    result = reproduce.reproduce(out, config=TINY, progress=False)
    assert result["ran"] == ["step_distance", "landmark_number"]
    assert (out / "landmark_number" / reproduce.STUDY_FILE).is_file()
    assert (out / "step_distance" / fig).read_bytes()[:8] == PNG_MAGIC
    assert reproduce.reproduce(out, config=TINY, progress=False)["ran"] == []


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
        reproduce.reproduce(out, config=TINY, progress=False)
    assert not record.exists(), "a crashed study must not look complete"
    assert (out / "environments" / "partial.json").is_file()
    assert dot_files(out) == []
    monkeypatch.undo()
    result = reproduce.reproduce(out, config=TINY, progress=False)
    assert result["ran"] == ["environments"]
    assert reproduce.is_current(out / "environments", reproduce.study_hash(module, TINY))


def test_a_source_edited_during_the_run_leaves_the_study_stale(run, monkeypatch):
    """The hash a record gets is that of the code that ran, taken before the first study: a source
    edited mid-run (here: the hash changes while `environments` runs) makes the study run again next
    time instead of stamping the old results with the new code's hash."""
    out, _, _ = run
    module = reproduce.registry(["environments"])["environments"]
    real_hash, real_run, edited = reproduce.study_hash, module.run, []
    monkeypatch.setattr(reproduce, "study_hash", lambda m, s: real_hash(m, s) + ("-edited" if edited else ""))

    def edit_then_run(ctx):
        edited.append(True)  # the sources change on disk while the study computes
        real_run(ctx)

    monkeypatch.setattr(module, "run", edit_then_run)
    assert reproduce.reproduce(out, only="environments", force=True, config=TINY, progress=False)["ran"] == [
        "environments"
    ]
    assert read_record(out, "environments")["hash"] == real_hash(module, TINY)  # the code that ran
    assert not reproduce.is_current(out / "environments", reproduce.study_hash(module, TINY))  # stale for the edit
    monkeypatch.undo()
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
        reproduce.reproduce(out, config=TINY, progress=False)
    assert not record.exists()
    assert not (out / "environments" / "broken.png").exists()
    assert dot_files(out) == []
    monkeypatch.undo()
    assert reproduce.reproduce(out, config=TINY, progress=False)["ran"] == ["environments"]


def test_changed_settings_rerun(run):
    out, _, _ = run
    other = reproduce.RunConfig(spacing=TINY.spacing, trials=TINY.trials, seed=TINY.seed + 1)
    result = reproduce.reproduce(out, config=other, only="environments", progress=False)
    assert result["ran"] == ["environments"]
    assert read_record(out, "environments")["settings"]["seed"] == TINY.seed + 1
    assert list(result["records"]) == ["environments"]  # records of other settings are not reported
    assert re.search(rf"<td>seed</td>\s*<td>{TINY.seed + 1}</td>", (out / "report.html").read_text())
    back = reproduce.reproduce(out, config=TINY, only="environments", progress=False)
    assert back["ran"] == ["environments"]
    assert list(back["records"]) == list(studies.STUDIES)
    assert reproduce.reproduce(out, config=TINY, progress=False)["ran"] == []


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
    proc = subprocess.run(
        [sys.executable, "-c", "import delvjax.studies, delvjax.reproduce._run as r; print(list(r.registry()))"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    printed = proc.stdout.strip().splitlines()[-1]
    for name in studies.STUDIES:
        assert repr(name) in printed


BAD_RECORDS = [  # parse as JSON, but no delvjax wrote them (issue 53 point 13)
    [],
    {"name": "environments", "files": "fig.png"},
    {"name": "environments", "seconds": "12"},
    {"name": "environments", "numbers": []},
    {"name": "environments", "tables": [{"id": 3}]},
    {
        "name": "environments",
        "tables": [{"id": "t", "title": "", "source": "", "note": "", "file": "t.csv", "columns": [], "rows": [1]}],
    },
    {"name": "environments", "figures": ["a.png"]},
    {"name": "environments", "files": [1]},
    {"name": "environments", "colour": "red"},
]


@pytest.mark.parametrize("bad", BAD_RECORDS, ids=range(len(BAD_RECORDS)))
def test_a_record_of_wrong_types_is_not_read(bad):
    with pytest.raises(TypeError):
        reproduce.StudyRecord.from_json(bad)


def test_a_record_of_wrong_types_makes_its_study_run_again(run, capsys):
    out, _, _ = run
    record = out / "environments" / reproduce.STUDY_FILE
    good = record.read_text()
    record.write_text('{"name": "environments", "title": "x", "hash": "h", "tables": [{"id": 3}], "files": "abc"}')
    result = reproduce.reproduce(out, config=TINY, progress=False)
    assert result["ran"] == ["environments"]
    assert "cannot be read (TypeError)" in capsys.readouterr().err
    assert reproduce.StudyRecord.from_json(json.loads(record.read_text())).name == "environments"
    assert reproduce.StudyRecord.from_json(json.loads(good)).name == "environments"
