"""The claims' minimum-evidence rule (`studies/claims/_common.py` `beyond`): a verdict does not rest on one
grid point (issue 53 point 4: claim 2 "failed" because env2 had e > 45° at 1 of 12 points inside the hull)."""

from __future__ import annotations

from delvjax.studies.claims._common import CANNOT_TELL, at_least, beyond
from tests.cases.claims import E3, fail_hull, hull, merge, verdict


def _inside(points: int, env2_pct: float) -> dict:
    numbers = merge(hull(0.0, 20.0), {"map:env2:delv:gt45_inside_hull_pct": env2_pct})
    return merge(numbers, {f"n:map:{e}:delv:gt45_inside_hull_pct": [points] for e in E3})


def test_a_share_beyond_its_bound_by_one_grid_point_cannot_tell():
    assert beyond(100 / 12, 2.0, 12) is None  # 1 of 12 points: one point the other way gives 0 %
    assert beyond(200 / 12, 2.0, 12) is True  # 2 of 12 points: more than one point beyond
    assert beyond(1.0, 2.0, 12) is False and beyond(100 / 12, 2.0, None) is True  # no count: the share decides
    assert beyond(4 * 100 / 150, 2.0, 150) is None and beyond(5 * 100 / 150, 2.0, 150) is True  # 2.7 %, 3.3 %


def test_the_hull_claim_does_not_fail_on_one_point_of_twelve():
    one = verdict("errors_outside_landmark_hull", _inside(12, 100 / 12))
    assert one["verdict"] == CANNOT_TELL and "one grid point" in one["why"], one
    assert "of 12 points" in one["ours"] and "12 counted grid points in the region" in one["sample"], one
    two = verdict("errors_outside_landmark_hull", _inside(12, 200 / 12))
    assert two["verdict"] != CANNOT_TELL and two["verdict"] != "holds", two  # two points: it decides
    assert verdict("errors_outside_landmark_hull", _inside(150, 100 / 150))["verdict"] == "holds"


def test_a_margin_that_one_grid_point_would_turn_cannot_tell():
    assert at_least(15.0, 10.0, 100) is True and at_least(5.0, 10.0, 100) is False  # 1 point = 1 %
    assert at_least(10.5, 10.0, 100) is None and at_least(9.5, 10.0, 100) is None
    numbers = merge(
        fail_hull(5.0, 20.0, 5.0),  # outside 15 points above inside and DELV: holds on many points
        {"n:fail_inside_hull:env1:warping": [12], "n:fail_outside_hull:env1:warping": [20]},
        {"n:fail_outside_hull:env1:delv": [20]},
    )
    row = verdict("warping_fails_outside_hull", numbers)
    assert row["verdict"] == CANNOT_TELL and "one grid point" in row["why"], row  # 12 and 20 points: 13 % slack
    assert verdict("warping_fails_outside_hull", fail_hull(5.0, 20.0, 5.0))["verdict"] == "holds"  # no counts
