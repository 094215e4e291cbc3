"""The ensemble_maps study's helpers (`studies/runs/_ensemble_maps.py`): the landmarks' hull, error curves and
hull error rates of many worlds as one array program, the visual compass's heading errors of stacked worlds,
and the claims' keys of each sweep, judged over synthetic members."""

from __future__ import annotations

import jax
import numpy as np
import pytest
import xarray as xr

from delvjax.core.maps import grid_points, random_headings
from delvjax.core.methods.heading import visual_compass_errors
from delvjax.core.metrics import error_curve
from delvjax.envs._presets import env_from_dict
from delvjax.options._settings import make_sensor
from delvjax.studies.runs import _ensemble_maps as em
from delvjax.studies.runs import ensemble_maps
from delvjax.studies.runs._common import inside_hull
from delvjax.studies.runs._ensemble_stats import claim_rows
from delvjax.studies.runs.visual_compass import BACKGROUNDS, TRUE, VISUAL

POINTS = grid_points(np.array([0.0, 0.0, 1000.0, 1000.0]), 50.0).astype(float)


def layouts(n: int, seed: int) -> list[dict]:
    """`n` worlds of four landmarks 80-400 cm from home, one per quadrant, bearings jittered (docs/model.md §7
    dictionaries; some surround home, some not)."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        d, r = rng.uniform(80, 400, 4), rng.uniform(8, 20, 4)
        a = rng.uniform(0, 2 * np.pi) + np.arange(4) * rng.uniform(0.6, np.pi / 2) + rng.uniform(-0.2, 0.2, 4)
        lms = [{"x": 500 + dd * np.cos(aa), "y": 500 + dd * np.sin(aa), "r": rr} for dd, aa, rr in zip(d, a, r)]
        out.append({"name": f"w{i}", "arena": [0.0, 0.0, 1000.0, 1000.0], "home": [500.0, 500.0], "landmarks": lms})
    return out


def test_the_hull_of_many_worlds_is_scipys_hull_of_each():
    worlds = layouts(12, seed=2)
    centres = np.array([[[lm["x"], lm["y"]] for lm in w["landmarks"]] for w in worlds])
    valid = np.ones(centres.shape[:2], bool)
    valid[0, 3] = False  # a padded slot: world 0 keeps three landmarks
    centres[0, 3] = (1e9, 1e9)
    inside = em.hull_inside(centres, valid, POINTS)
    for w, world in enumerate(worlds):  # the reference, one world at a time
        e = env_from_dict({**world, "landmarks": world["landmarks"][: 3 if w == 0 else 4]})
        np.testing.assert_array_equal(inside[w], inside_hull(e, POINTS), err_msg=world["name"])
    assert 0 < inside.sum() < inside.size


def test_binned_curves_are_error_curves_of_each_world():
    rng = np.random.default_rng(0)
    errors = rng.uniform(0, 180, (3, len(POINTS)))
    errors[rng.uniform(size=errors.shape) < 0.1] = np.nan  # points not included
    homes = np.array([[500.0, 500.0], [300.0, 650.0], [500.0, 500.0]])
    means, counts = em.binned_curves(errors, POINTS, homes)
    for w in range(3):
        rows = error_curve(np.nan_to_num(errors[w]), POINTS, homes[w], ~np.isnan(errors[w]))
        keep = counts[w] > 0
        np.testing.assert_allclose(means[w][keep], [r["mean_deg"] for r in rows], rtol=1e-12)
        assert counts[w][keep].tolist() == [r["n"] for r in rows]


def test_error_rates_inside_a_region_count_only_its_included_points():
    errors = np.array([[10.0, 50.0, np.nan, 100.0], [1.0, 2.0, 3.0, 4.0]])
    region = np.array([[True, True, True, False], [False, False, False, False]])
    rates = em.rate_in(errors, region)
    assert rates[0] == pytest.approx(50.0) and np.isnan(rates[1])


def test_heading_errors_of_stacked_worlds_are_each_worlds_visual_compass_errors():
    worlds = layouts(2, seed=1)
    envs = em.stacked_env([*worlds, "env3"], pad=4)
    sensors = [make_sensor(background=bg) for bg in BACKGROUNDS]
    stacked = jax.tree.map(lambda *x: np.stack(x), *sensors)
    points = jax.numpy.asarray(grid_points(np.array([0.0, 0.0, 1000.0, 1000.0]), 250.0))
    key = jax.random.PRNGKey(3)
    err, included = em.heading_errors(envs, points, key, stacked)
    headings = random_headings(key, len(points))
    for w in range(3):
        env = jax.tree.map(lambda x: x[w], envs)
        for b, sensor in enumerate(sensors):
            ref = np.degrees(np.asarray(visual_compass_errors(env, points, headings, sensor)))
            np.testing.assert_allclose(np.asarray(err)[w, b], ref, atol=1e-3)
    stats = em.heading_stats(np.asarray(err), np.asarray(included))
    assert stats["heading_error_gt5_pct"].shape == (3, 3)
    assert np.asarray(included).sum(axis=1).min() > 0


def synthetic_worlds(members: int, good: int) -> dict[str, dict]:
    """Every number the study's claims read, from its key functions on synthetic sweeps: members < `good` where
    DELV errs far less than image matching everywhere (claim 7 holds), the others where it errs more."""
    labels = [f"{f}-m{i}" for f in ("env1", "env2", "env3") for i in range(members)]
    methods = ensemble_maps.MAP_METHODS
    rng = np.random.default_rng(1)
    errors = rng.uniform(0, 40, (len(labels), len(methods), 1, 1, len(POINTS)))
    worse = np.array([int(label.rsplit("m", 1)[1]) >= good for label in labels])
    errors[:, methods.index("warping")] += np.where(worse, -30.0, 60.0)[:, None, None, None]
    errors = np.clip(errors, 0, 180)
    lms = np.array([[400.0, 400, 20], [600, 420, 20], [580, 620, 20], [420, 600, 20]])
    res = {
        "errors": errors,
        "points": POINTS,
        "homes": {label: np.array([500.0, 500.0]) for label in labels},
        "landmarks": {label: lms for label in labels},
    }
    worlds: dict[str, dict] = {}
    em.merge(worlds, em.curve_keys(res, methods, labels))
    coords = {"env": labels, "method": list(TRUE), "compass_noise_deg": [0.0, 45.0]}
    shape = (len(labels), 3, 2)
    ds = xr.Dataset(
        {"catchment_pct": (list(coords), np.full(shape, 90.0)), "mean_error_deg": (list(coords), np.full(shape, 9.0))},
        coords=coords,
    )
    em.merge(worlds, em.compass_keys(ds, TRUE, (0.0, 45.0)))
    for bg in BACKGROUNDS:
        coords = {"env": labels, "method": list(VISUAL)}
        values = np.tile([80.0, 60.0, 40.0], (len(labels), 1))
        ds = xr.Dataset(
            {
                "catchment_pct": (["env", "method"], values),
                "catchment_physical_pct": (["env", "method"], values - 1),
                "mean_error_deg": (["env", "method"], np.tile([12.0, 20.0, 30.0], (len(labels), 1))),
            },
            coords=coords,
        )
        em.merge(worlds, em.visual_keys(ds, zip(TRUE, VISUAL), bg, True))
        em.merge(worlds, em.visual_keys(ds, zip(TRUE, VISUAL), bg, False))
        for i in range(members):
            worlds[f"env1-m{i}"][f"visual:{bg}:heading_error_gt5_pct"] = 10.0
    return worlds


def test_every_claim_of_the_study_is_judged_on_the_keys_its_sweeps_record():
    """Claim 7 holds in exactly the 6 of 10 members planted so; every claim the study names finds its keys
    (a key the sweeps do not record would drop the claim)."""
    members = 10
    worlds = synthetic_worlds(members, good=6)
    lay = np.tile(np.array([[400.0, 400, 20], [600, 420, 20], [580, 620, 20], [420, 600, 20]]), (members, 1, 1))
    layouts = {f: lay for f in ("env1", "env2", "env3")}
    ids = ensemble_maps.CLAIMS | ensemble_maps.VISUAL_CLAIMS
    rows = {r["id"]: r for r in claim_rows(worlds, members, layouts, ids=ids)}
    assert set(rows) == ids
    assert rows["delv_smaller_error_than_warping"]["holds %"] == pytest.approx(60.0)
    assert rows["delv_smaller_error_than_warping"]["verdict over worlds"] == "depends on the world"
    assert rows["visual_compass_catchment_order"]["holds %"] == 100.0  # 80 > 60 > 40 in every setting
    assert all(r["members"] == members for r in rows.values())


def test_member_labels_drop_the_layouts_seed():
    assert em.member_label("env1-s3-m7") == "env1-m7" and em.family_of("env2-s0-m12") == "env2"
    assert em.member_label("env1") == "env1" and em.family_of("env1") == "env1"
