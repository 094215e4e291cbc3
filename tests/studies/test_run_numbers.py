"""Numbers the studies compute from a catchment, on synthetic catchments (no rollout runs)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from delvjax.studies.runs._common import hull_failures


def test_hull_failures_are_over_the_counted_points():
    """Issue 52: image matching's failure rates inside and outside the landmarks' hull are over the
    points the catchment counts, as `catchment_pct` is. Over `included`, DELV with a 100 % catchment
    showed 'fail outside hull 22.21 %': exactly the near-wall points, never released, so never a success."""
    c = SimpleNamespace(
        included=np.ones(6, bool),
        counted=np.array([True, True, True, True, False, False]),  # the last two: within d of a wall
        success=np.array([[True, True, True, False, False, False]]),
    )
    hull = np.array([True, True, False, False, False, False])
    f = hull_failures(c, hull)
    assert f == {"inside": 0.0, "n_inside": 2, "outside": 50.0, "n_outside": 2}
    none_inside = hull_failures(c, np.zeros(6, bool) | ~np.asarray(c.counted))
    assert np.isnan(none_inside["inside"]) and none_inside["n_inside"] == 0 and none_inside["outside"] == 25.0
