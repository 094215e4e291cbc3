"""The default rollout rule (thesis Algorithm 2; docs/model.md §5): a method that needs a unit
movement first moves d along the release heading, the others turn to their first direction at once;
the catchment counts only grid points at least d from every wall under that rule."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core import rollouts
from delvjax.core.tables import catchment_columns
from delvjax.options._registry import get_method
from tests.cases.rollouts import run

STARTS = np.array([[200.0, 300.0], [700.0, 800.0], [850.0, 250.0]], np.float32)
HEADING = 30.0


def first_step(method: str, first_move: str) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors of each trial's first move, and its first (vector-map) direction as a unit vector."""
    env = delvjax.load_env("env1").arrays()
    heads = np.full(len(STARTS), np.radians(HEADING), np.float32)
    tr = run(env, STARTS, heads, method, record_paths=True, first_move=first_move)
    path = np.asarray(tr.path)
    step = path[:, 1] - path[:, 0]
    first = np.asarray(tr.first_direction)
    return step / np.linalg.norm(step, axis=1, keepdims=True), np.stack([np.cos(first), np.sin(first)], 1)


def test_default_rule_is_algorithm_2():
    assert rollouts.DEFAULT_FIRST_MOVE == "release" and rollouts.DEFAULT_RULES["first_move"] == "release"


@pytest.mark.parametrize("method", ["delv", "delv-compass"])
def test_unit_move_methods_first_move_along_the_release_heading(method):
    step, first = first_step(method, "release")
    h = np.radians(HEADING)
    np.testing.assert_allclose(step, np.tile([np.cos(h), np.sin(h)], (len(STARTS), 1)), atol=1e-5)
    assert np.max(np.abs(step - first)) > 0.1  # not the direction computed at the release point
    step_homing, first_homing = first_step(method, "homing")
    np.testing.assert_allclose(step_homing, first_homing, atol=1e-4)  # the earlier rule


@pytest.mark.parametrize("method", ["alv", "acv"])
def test_view_only_methods_turn_at_once(method):
    step, first = first_step(method, "release")
    np.testing.assert_allclose(step, first, atol=1e-4)


def test_catchment_counts_points_at_least_d_from_the_walls():
    c = delvjax.catchment("env1", "alv", grid=Grid(spacing=80))  # cells at 40, 120, ..., 920 cm: 40 cm from two walls
    pts, inc, counted = (np.asarray(a) for a in (c.points, c.included, c.counted))
    margin = np.minimum.reduce([pts[:, 0], pts[:, 1], 1000 - pts[:, 0], 1000 - pts[:, 1]])
    np.testing.assert_array_equal(counted, inc & (margin >= 50))
    assert (inc & ~counted).sum() == 23  # the first row and column of the 12 x 12 grid
    outcome = np.asarray(c.outcome)[0]
    assert np.all(outcome[inc & ~counted] == rollouts.NEAR_WALL)
    assert c.catchment_pct()[0] == pytest.approx(100.0 * np.asarray(c.success)[0][counted].mean())
    columns = catchment_columns(c)
    assert set(columns["outcome"]) >= {"near_wall"}
    # a data frame's mean success is the catchment: near-wall rows are NaN (pandas skips them) and not counted
    np.testing.assert_array_equal(columns["counted"], counted[inc])
    assert np.isnan(columns["success"][~counted[inc]]).all()
    assert 100.0 * np.nanmean(columns["success"]) == pytest.approx(c.catchment_pct()[0])
    summary = rollouts.catchment_summary(c)
    assert summary["catchment_points"] == int(counted.sum()) and summary["points"] == int(inc.sum())
    # under the earlier rule every grid point counts
    h = delvjax.catchment("env1", "alv", grid=Grid(spacing=80), rules=Rules(first_move="homing"))
    np.testing.assert_array_equal(np.asarray(h.counted), inc)


def test_a_step_too_long_for_the_arena_is_refused():
    with pytest.raises(ValueError, match="d"):
        delvjax.catchment("env1", "delv", d=600, grid=Grid(spacing=100))


@pytest.mark.parametrize("method", ["alv", "acv"])
def test_a_view_only_homing_run_restated_under_release_is_the_release_run(method):
    """The occlusion study runs ACV and ALV once for the default and the "homing" rules (`under_release`)."""
    from delvjax.core.sensor import Sensor

    env = delvjax.load_env("env1")
    masks, hidden = rollouts.occlusion_masks(env, 1)
    runs = {
        fm: rollouts.catchment_area(
            env.arrays(),
            get_method(method),
            Sensor(),
            masks=masks,
            hidden=hidden,
            grid=Grid(spacing=80),
            rules=Rules(first_move=fm),
        )
        for fm in ("release", "homing")
    }
    restated = rollouts.under_release(runs["homing"], env.arena, Sensor().d)
    assert restated.first_move == "release"
    for field in ("counted", "outcome", "steps", "end", "invalid_steps", "direction", "valid", "error_deg"):
        np.testing.assert_array_equal(
            np.asarray(getattr(restated, field)), np.asarray(getattr(runs["release"], field)), err_msg=field
        )
    assert (np.asarray(runs["homing"].counted) != np.asarray(restated.counted)).any()  # the wall cells changed
    with pytest.raises(delvjax.InputError) as exc:
        rollouts.under_release(runs["release"], env.arena, Sensor().d)
    assert exc.value.field == "first_move"
