"""`delvjax reproduce` side by side (`--workers`) and the studies of `--quick`; the session fixture `run`
(tests/conftest.py) ran with the default workers."""

from __future__ import annotations

import json
import time

import pytest

import delvjax.studies as studies
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.reproduce import _run as reproduce
from delvjax.reproduce._report import config_section
from delvjax.reproduce._study import RunConfig, versions
from tests.cases.reproduce import TINY, read_record

CHEAP = ["environments", "step_distance", "landmark_number", "with_compass"]


def _tables_and_numbers(out, name):
    rec = read_record(out, name)
    return (
        rec["numbers"],
        [t["rows"] for t in rec["tables"]],
        {f: (out / name / f).read_bytes() for f in rec["files"] if f.endswith(".csv")},
    )


@pytest.mark.parametrize("workers", [1, 3])
def test_workers_do_not_change_a_number(run, tmp_path, workers):
    out, _, _ = run  # the default workers (one per core, at most 4)
    other = tmp_path / f"w{workers}"
    result = reproduce.reproduce(other, config=TINY, progress=False, only=",".join(CHEAP), workers=workers)
    assert result["ran"] == [n for n in studies.STUDIES if n in CHEAP]  # registry order, however they finished
    for name in CHEAP:
        assert _tables_and_numbers(other, name) == _tables_and_numbers(out, name), name


def test_quick_leaves_the_studies_beyond_the_thesis_to_a_full_run():
    everything = list(studies.STUDIES)
    assert reproduce.select(None) == everything
    quick = reproduce.select(None, quick=True)
    assert quick == [n for n in everything if n not in studies.FULL_RUN_ONLY]
    assert set(studies.FULL_RUN_ONLY) < set(everything) and "occlusion" in quick and "sensitivity" not in quick
    assert reproduce.select("sensitivity,robot_images", quick=True) == [
        "sensitivity",
        "robot_images",
    ]  # --only runs what it names


def test_only_takes_a_list_of_names_as_the_python_api_is_called(untyped):
    """`reproduce(only=[...])` as a Python user writes it, in registry order; a list of something else,
    an empty one or an unknown name is refused naming --only (it used to fail on `list.split`)."""
    assert reproduce.select(["robot_images", " sensitivity"]) == ["sensitivity", "robot_images"]
    for bad, why in (
        ([["sensitivity", 3]], "study names"),
        ([5], "study names"),
        ([[]], "at least one"),
        ([("sensitivity", "x")], "unknown"),
    ):
        with pytest.raises(InputError, match=why) as err:
            reproduce.select(*bad)
        assert err.value.field == "--only"


def test_quick_report_says_what_it_left_out():
    text = config_section(RunConfig.make(quick=True), versions(), {}, 1.0, [])
    assert "A preview (`--quick`)" in text
    for name in studies.FULL_RUN_ONLY:
        assert f"`{name}`" in text
    assert "A preview" not in config_section(TINY, versions(), {}, 1.0, [])


def test_schedule_starts_every_study_side_by_side_longest_first():
    order = reproduce.schedule(list(studies.STUDIES))
    assert sorted(order) == sorted(studies.STUDIES)
    seconds = [reproduce.registry([n])[n].COST for n in order]  # each study's own (studies/runs/*.py)
    assert seconds == sorted(seconds, reverse=True) and order[-1] == "environments"
    assert order.index("occlusion") < order.index("image_matching")


def test_every_study_declares_its_title_and_cost():
    """A study module says what it is and roughly how long a full run of it takes (the order studies start)."""
    for name, module in reproduce.registry().items():
        assert isinstance(module.TITLE, str) and module.TITLE, name
        assert isinstance(module.COST, (int, float)) and module.COST > 0, name


def test_a_failure_side_by_side_stops_what_has_not_started():
    called = []

    def fn(name):
        called.append(name)
        if name == "a":
            raise RuntimeError("study a broke")
        time.sleep(0.3)

    with pytest.raises(RuntimeError, match="study a broke"):
        reproduce._side_by_side(fn, ["a", "b", "c", "d"], workers=2)
    assert called[0] == "a" and set(called) <= {"a", "b"}  # b only if it had started before a broke


def test_workers_below_one_is_refused_before_any_work(tmp_path, capsys):
    target = tmp_path / "x"
    assert main(["reproduce", "--only", "environments", "--workers", "0", "--out", str(target)]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(err) == 1 and "--workers" in err[0] and "0" in err[0]
    assert not target.exists()
    with pytest.raises(reproduce.InputError, match="workers"):
        reproduce.reproduce(target, config=TINY, progress=False, only="environments", workers=0)
    assert not target.exists()


def test_compile_seconds_are_counted_per_thread(run):
    out, _, _ = run  # the first study to need the shared rollout program compiles it; the others wait for it
    recs = {name: read_record(out, name) for name in studies.STUDIES}
    assert max(r["compile_seconds"] for r in recs.values()) > 0
    assert all(json.dumps(r["compile_seconds"]) for r in recs.values())
    assert sum(r["compile_seconds"] for r in recs.values()) <= sum(r["seconds"] for r in recs.values())


def test_two_threads_that_need_one_new_program_compile_it_once():
    """What `schedule` relies on: every study starts side by side, and two studies that need the same new
    program (the shared rollout program) wait for one compilation instead of making two."""
    import threading

    import jax
    import jax.numpy as jnp

    @jax.jit
    def program(x):
        return jax.lax.fori_loop(0, 3, lambda i, y: jnp.sin(y) @ y + jnp.cos(y).T, x)

    x = jax.block_until_ready(jnp.full((40, 40), 0.01, jnp.float32))
    barrier, out, compiles = threading.Barrier(2), [], []

    def listen(event, seconds, **kw):
        if event == "/jax/core/compile/backend_compile_duration":
            compiles.append(seconds)

    def study():
        barrier.wait()
        out.append(program(x))

    jax.monitoring.register_event_duration_secs_listener(listen)
    try:
        threads = [threading.Thread(target=study) for _ in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        jax.monitoring.unregister_event_duration_listener(listen)
    assert len(out) == 2 and len(compiles) == 1
