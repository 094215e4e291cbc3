"""The `ensemble_hull` study's arithmetic (studies/runs/ensemble_hull.py): each member's counted release points split
by its own landmark hull, claim 10 judged per member, and a member whose hull holds no counted point cannot tell."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.envs import ensemble_envs
from delvjax.studies.runs._ensemble_stats import claim_rows
from delvjax.studies.runs.ensemble_hull import CLAIM_IDS, METHODS, hull_numbers

IDS = set(CLAIM_IDS)
POINTS = np.array([[x, y] for y in (100.0, 300.0, 500.0, 700.0, 900.0) for x in (100.0, 300.0, 500.0, 700.0, 900.0)])
SQUARE = np.array([[200.0, 200.0, 20.0], [800.0, 200.0, 20.0], [800.0, 800.0, 20.0], [200.0, 800.0, 20.0]])
INSIDE = (np.abs(POINTS[:, 0] - 500) < 300) & (np.abs(POINTS[:, 1] - 500) < 300)  # the 9 central points


def layouts(n: int) -> dict:
    return {
        "env1": np.array([[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in ensemble_envs("env1", n, 0)])
    }


def member(wi: float, wo: float, do: float) -> dict:
    """A member's claim-10 numbers: image matching's failures inside / outside the hull, DELV's outside."""
    return {
        "fail_inside_hull:env1:warping": wi,
        "fail_outside_hull:env1:warping": wo,
        "fail_inside_hull:env1:delv": 0.0,
        "fail_outside_hull:env1:delv": do,
    }


def outcomes(landmarks: list[np.ndarray], ok: np.ndarray, counted: np.ndarray | None = None) -> dict:
    """A hand-made `point_outcomes` result of len(landmarks) worlds x METHODS, one mask: `ok` (W, M, P) in 0/1."""
    w, p = len(landmarks), len(POINTS)
    shape = (w, len(METHODS), 1, 1, p)  # env, method, spacing, seed, points
    counted = np.ones((w, len(METHODS), p), bool) if counted is None else counted
    return {
        "successes": ok.reshape(shape).astype(np.int32),
        "untouched": ok.reshape(shape).astype(np.int32),
        "trials": np.ones(shape, np.int32),
        "counted": counted.reshape(shape),
        "points": POINTS,
        "landmarks": {f"env1-s0-m{i}": lm for i, lm in enumerate(landmarks)},
    }


def test_the_claim_holds_in_exactly_the_members_built_to_hold():
    n, k = 10, 6
    holding = [member(2.0, 45.0, 5.0)] * k  # outside >= inside + 10 and >= DELV + 10
    failing = [member(30.0, 35.0, 0.0), member(2.0, 45.0, 40.0), member(50.0, 20.0, 60.0), member(2.0, 8.0, 0.0)]
    worlds = {f"env1-m{i}": nums for i, nums in enumerate(holding + failing)}
    (row,) = claim_rows(worlds, n, layouts(n), ids=IDS)
    assert row["id"] == "warping_fails_outside_hull"
    assert row["holds %"] == 100.0 * k / n and row["members"] == n and row["cannot tell %"] == 0.0
    assert row["partly %"] == 100.0 * 2 / n  # one part holds in two of the four others, none in the last two
    lo, hi = (float(v) for v in row["95 % interval"].split("-"))
    assert lo < 60.0 < hi


def test_a_members_release_points_are_split_by_its_own_hull():
    ok = np.ones((1, len(METHODS), len(POINTS)), bool)
    warping = METHODS.index("warping")
    ok[0, warping, np.flatnonzero(INSIDE)[:3]] = False  # 3 of the 9 inside points fail
    ok[0, warping, np.flatnonzero(~INSIDE)[:12]] = False  # 12 of the 16 outside
    counted = np.ones_like(ok)
    counted[:, :, np.flatnonzero(~INSIDE)[-4:]] = False  # 4 outside points not counted (they succeed anyway)
    nums = hull_numbers(outcomes([SQUARE], ok, counted), ["env1-s0-m0"])["env1-m0"]
    assert nums["n:fail_inside_hull:env1:warping"] == [9] and nums["n:fail_outside_hull:env1:warping"] == [12]
    assert nums["fail_inside_hull:env1:warping"] == 100.0 * 3 / 9
    assert nums["fail_outside_hull:env1:warping"] == 100.0  # the 12 counted outside points are the failures
    assert nums["fail_outside_hull:env1:delv"] == 0.0 and nums["fail_inside_hull:env1:delv"] == 0.0
    triangle = SQUARE[[0, 1, 3]]  # another world: half the square (its diagonal's points on the hull)
    other = hull_numbers(outcomes([triangle], ok, counted), ["env1-s0-m0"])["env1-m0"]
    assert other["n:fail_inside_hull:env1:warping"] == [6]


def test_a_member_without_a_counted_point_inside_its_hull_cannot_tell():
    tiny = np.array(
        [[180.0, 180.0, 5.0], [220.0, 180.0, 5.0], [200.0, 220.0, 5.0], [210.0, 200.0, 5.0]]
    )  # no grid point
    ok = np.ones((3, len(METHODS), len(POINTS)), bool)
    ok[:, METHODS.index("warping"), ~INSIDE] = False  # image matching fails outside every hull
    worlds = hull_numbers(outcomes([SQUARE, tiny, SQUARE], ok), [f"env1-s0-m{i}" for i in range(3)])
    assert np.isnan(worlds["env1-m1"]["fail_inside_hull:env1:warping"])
    assert worlds["env1-m1"]["n:fail_inside_hull:env1:warping"] == [0]
    (row,) = claim_rows(worlds, 3, layouts(3), ids=IDS)
    assert row["holds %"] == pytest.approx(100.0 * 2 / 3)  # the two square worlds hold
    assert (
        row["cannot tell %"] == pytest.approx(100.0 / 3) and row["partly %"] == 0.0
    )  # the empty hull: cannot tell, not fails
