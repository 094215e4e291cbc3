"""Catchment and success-rate sweeps (docs/sweeps.md "Rollout sweeps"): every cell equals the
single run of `delvjax.catchment` / `delvjax.success_rate` with the same options, occlusion counts
share one program, and the metrics are computed right."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax.core.errors import InputError
from delvjax.core.rollouts import catchment_summary, wilson_interval_pct
from delvjax.sweep_results import wilson_pct
from delvjax.sweep_spec import EXAMPLES, KINDS, parse_sweep
from delvjax.sweeps import run_sweep

CATCHMENT = """
[sweep]
kind = "catchment"
[axes]
method = ["delv", "alv"]
occlude = [0, 1]
first_move = ["homing", "release"]
collisions = ["fail"]
bearing_noise_deg = [3.0]
seed = [4]
spacing = [100]
"""
SUCCESS = """
[sweep]
kind = "success-rate"
distances = [100, 250]
trials = 12
[axes]
method = ["alv"]
occlude = [0, 1]
motion_heading_noise_deg = [15.0]
seed = [2]
"""


@pytest.fixture(scope="module")
def catchments():
    return run_sweep(parse_sweep(CATCHMENT))


def test_a_catchment_cell_equals_the_catchment_run_with_its_options(catchments):
    ds = catchments
    assert ds.attrs["programs_compiled"] == 2  # one per method: occlusion counts and rules share it
    for method in ("delv", "alv"):
        for occlude in (0, 1):
            for first_move in ("homing", "release"):
                ref = catchment_summary(delvjax.catchment(
                    "env1", method, spacing=100, seed=4, occlude=occlude or None, first_move=first_move,
                    collisions="fail", bearing_noise_deg=3.0))
                cell = ds.sel({"method": method, "occlude": occlude, "first_move": first_move}).squeeze()
                where = (method, occlude, first_move)
                assert int(cell.points) == ref["points"], where
                for name in ("catchment", "gt45", "gt90"):
                    assert float(cell[f"{name}_pct"]) == pytest.approx(ref[f"{name}_pct"]["mean"], abs=1e-9), where
                assert float(cell.catchment_min_pct) == pytest.approx(ref["catchment_pct"]["min"], abs=1e-9), where
                assert float(cell.catchment_max_pct) == pytest.approx(ref["catchment_pct"]["max"], abs=1e-9), where
                rows = ref["per_mask"]
                landmark = sum(r["landmark_count"] for r in rows) / (ref["points"] * len(rows))
                assert float(cell.landmark_pct) == pytest.approx(100 * landmark, abs=1e-9), where
    # the rules reach the cells: the first move along the release heading changes the outcomes
    homing, release = (ds.sel({"method": "alv", "first_move": m}).catchment_pct.values for m in ("homing", "release"))
    assert not np.array_equal(homing, release)


def test_a_success_rate_cell_equals_the_runs_under_each_hidden_landmark():
    ds = run_sweep(parse_sweep(SUCCESS))
    assert ds.sizes["distance_cm"] == 2 and ds.attrs["trials_per_distance"] == 12
    kw = dict(distances=[100, 250], trials=12, seed=2, motion_heading_noise_deg=15.0)
    full = delvjax.success_rate("env1", "alv", **kw).table()
    cell = ds.sel({"occlude": 0}).squeeze()
    assert cell.placed.values.tolist() == [r["placed"] for r in full]
    assert np.allclose(cell.success_pct.values, [r["success_pct"] for r in full])
    # occlude = 1: the same release points under each of the 4 masks, pooled
    hidden = [delvjax.success_rate("env1", "alv", hidden=[i], **kw).table() for i in range(4)]
    successes = np.sum([[r["successes"] for r in t] for t in hidden], axis=0)
    placed = np.sum([[r["placed"] for r in t] for t in hidden], axis=0)
    cell = ds.sel({"occlude": 1}).squeeze()
    assert cell.placed.values.tolist() == placed.tolist()
    assert np.allclose(cell.success_pct.values, 100 * successes / placed)
    lo, hi = wilson_pct(successes, placed)
    assert np.allclose(cell.success_ci95_lo_pct.values, lo) and np.allclose(cell.success_ci95_hi_pct.values, hi)


@pytest.mark.parametrize("k, n", [(0, 1), (3, 10), (7, 10), (10, 10), (50, 100), (0, 0)])
def test_the_vectorised_wilson_interval_is_scipys(k, n):
    lo, hi = wilson_pct(np.array([k]), np.array([n]))
    ref = wilson_interval_pct(k, n)
    assert np.allclose([lo[0], hi[0]], [ref["ci_lo_pct"], ref["ci_hi_pct"]], equal_nan=True)


@pytest.mark.parametrize("kind", KINDS)
def test_every_example_file_is_a_valid_sweep_of_its_kind(kind):
    spec = parse_sweep(EXAMPLES[kind])
    assert spec.kind == kind and spec.n_cells >= 8


@pytest.mark.parametrize("text, field", [
    ("[sweep]\nkind = 'catchment'\n[axes]\nocclude = [9]", "cell (occlude=9, env=env1, method=delv, spacing=25.0, seed=0)"),
    ("[sweep]\nkind = 'catchment'\n[axes]\nfirst_move = ['walk']", "cell (first_move=walk, env=env1, method=delv, "
                                                                   "spacing=25.0, seed=0)"),
    ("[sweep]\nkind = 'success-rate'\ndistances = [5000]", "cell (env=env1, method=delv, seed=0)"),
    ("[sweep]\nkind = 'catchment'\n[axes]\nmax_steps = [0]", "cell (max_steps=0, env=env1, method=delv, spacing=25.0, "
                                                             "seed=0)"),
])
def test_an_impossible_rollout_cell_is_refused_before_any_work(text, field):
    with pytest.raises(InputError) as exc:
        run_sweep(parse_sweep(text))
    assert exc.value.field == field
