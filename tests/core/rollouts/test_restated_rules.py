"""A run under one rule set restated under another (docs/model.md §5, "Rules from one run"): up to its first
landmark contact a trial is the same under collisions "ignore" and "fail", so `under_collisions` of an
"ignore" run must equal the "fail" run bit for bit (outcomes, steps, end points, invalid moves, the
vector map), with noise and hidden landmarks too; the studies rely on it to run each method once or
twice instead of three times (`studies.runs._common.every_rule`)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core import rollouts
from delvjax.core.sensor import Sensor

NOISE = {"bearing_noise_deg": 2.0, "step_noise": 0.05}


def assert_same(restated, run) -> None:
    """Every array field of two results equal bit for bit (NaN where NaN), and the same rules."""
    assert restated.rules == run.rules
    for f in dataclasses.fields(run):
        a, b = getattr(restated, f.name), getattr(run, f.name)
        if hasattr(b, "shape"):
            a, b = np.asarray(a), np.asarray(b)
            assert a.dtype == b.dtype, f.name
            np.testing.assert_array_equal(a, b, err_msg=f.name)


@pytest.mark.parametrize(("method", "options"), [("delv-compass", NOISE), ("alv", {})])
def test_a_catchment_restated_under_collisions_fail_is_the_fail_run(method, options):
    runs = {
        rule: delvjax.catchment(
            "env1", method, occlude=1, grid=Grid(spacing=80), rules=Rules(collisions=rule), **options
        )
        for rule in rollouts.COLLISIONS
    }
    fail = runs["fail"]
    landmark = np.asarray(fail.outcome) == rollouts.LANDMARK
    assert landmark.sum() >= 3  # the test can fail: trials do end inside a landmark under "fail"
    ignored = np.asarray(runs["ignore"].outcome)[landmark]
    assert (ignored != rollouts.LANDMARK).all() and (ignored == rollouts.SUCCESS).any()  # ...and run on under "ignore"
    assert_same(rollouts.under_collisions(runs["ignore"]), fail)
    # trials that never touch a landmark are the same under both rules
    clear = np.asarray(runs["ignore"].contact) == rollouts.NO_CONTACT
    np.testing.assert_array_equal(np.asarray(runs["ignore"].outcome)[clear], np.asarray(fail.outcome)[clear])
    assert not np.asarray(fail.counted).all()  # NEAR_WALL cells kept their code, restated steps and end


def test_a_success_rate_restated_under_each_rule_is_its_own_run():
    """The success-rate tables: ALV (reads only the current view) once for all three rule sets."""
    runs = {
        (fm, col): delvjax.success_rate(
            "env1", "alv", trials=40, distances=[250, 450], rules=Rules(first_move=fm, collisions=col), **NOISE
        )
        for fm, col in (("homing", "ignore"), ("release", "ignore"), ("release", "fail"))
    }
    assert (np.asarray(runs["release", "fail"].outcome) == rollouts.LANDMARK).any()
    default = rollouts.under_release(runs["homing", "ignore"], delvjax.load_env("env1").arena, Sensor().d)
    assert_same(default, runs["release", "ignore"])
    assert_same(rollouts.under_collisions(default), runs["release", "fail"])


def test_trajectories_restated_end_their_paths_at_the_contact():
    """Paths too: under "fail" a trial's positions stop at its first landmark contact (NaN after it)."""
    env = delvjax.load_env("env1")
    lm = np.asarray(env.landmarks)[np.asarray(env.valid)]
    # release points just beside each landmark, heading into it: the blind first move (d) ends inside
    starts = lm[:, :2] - np.array([lm[:, 2] + 5.0, np.zeros(len(lm))]).T
    runs = {
        rule: delvjax.trajectories(
            env, "delv-compass", starts=starts.tolist(), grid=Grid(heading_deg=0.0), rules=Rules(collisions=rule)
        )
        for rule in rollouts.COLLISIONS
    }
    assert (np.asarray(runs["fail"].outcome) == rollouts.LANDMARK).sum() >= 2
    assert_same(rollouts.under_collisions(runs["ignore"]), runs["fail"])


def test_only_an_ignore_run_is_restated():
    fail = delvjax.success_rate("env1", "alv", trials=4, distances=[250], rules=Rules(collisions="fail"))
    with pytest.raises(delvjax.InputError) as exc:
        rollouts.under_collisions(fail)
    assert exc.value.field == "collisions"


@pytest.mark.parametrize(("method", "runs_made"), [("alv", ["homing"]), ("delv-compass", ["homing", "default"])])
def test_the_studies_run_each_method_once_or_twice_for_three_rule_sets(method, runs_made):
    """`every_rule` (the studies' helper): ALV once, DELV twice, and each rule set's result is its own run's."""
    from delvjax.studies.runs._common import RULES, every_rule

    env, made = delvjax.load_env("env1"), []

    def run(rules: str):
        made.append(rules)
        return delvjax.catchment(env, method, occlude=1, grid=Grid(spacing=80), rules=Rules(**RULES[rules]))

    results = every_rule(run, method, env.arena)
    assert made == runs_made and list(results) == list(RULES)
    for rules, res in results.items():
        assert_same(res, delvjax.catchment(env, method, occlude=1, grid=Grid(spacing=80), rules=Rules(**RULES[rules])))


def test_restating_a_catchment_compiles_nothing():
    """`under_release` is host work: restating a catchment of a grid and mask count seen nowhere else
    compiles no program (an eager `jnp.where` once compiled one per grid and mask count: 2-3 s of a cold
    `reproduce --quick`)."""
    from tests.core.test_buckets import compiled_functions

    env = delvjax.load_env("env1")
    homing = delvjax.catchment(env, "alv", occlude=2, grid=Grid(spacing=70), rules=Rules(first_move="homing"))
    with compiled_functions() as names:
        default = rollouts.under_release(homing, env.arena, Sensor().d)
    assert names == []
    assert_same(default, delvjax.catchment(env, "alv", occlude=2, grid=Grid(spacing=70)))
