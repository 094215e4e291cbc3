"""The ensemble_robot study (`studies/runs/ensemble_robot.py`): its members are robot-family layouts rendered where
they stand; a claim held in exactly k of n synthetic members gets that share; the batched program over members
gives each member the rings and the DELV map that rendering it alone (`render_in_memory`, `image_map`) gives."""

from __future__ import annotations

import math

import numpy as np
import pytest

from delvjax.envs._ensembles import violations
from delvjax.images import render_in_memory
from delvjax.studies.runs import _ensemble_robot as er
from delvjax.studies.runs import ensemble_robot as study
from delvjax.studies.runs._images_common import CAMERA_NOISE, image_map, numbers


@pytest.fixture(scope="module")
def batch():
    """Two members rendered in one program, member 1 under another camera-noise seed."""
    layouts = er.robot_layouts(2, 0)
    worlds = er.member_worlds(layouts, ["robot-m0", "robot-m1"])
    return layouts, worlds, er.render_members(worlds, [0, 3])


def test_members_are_the_family_rendered_where_they_stand(batch):
    layouts, worlds, m = batch
    assert all(violations("robot", lay) == [] for lay in layouts)
    np.testing.assert_allclose(m.cylinders, layouts, atol=1e-4)  # the rendered cylinders are the member's
    for w, lay in zip(worlds, layouts):
        np.testing.assert_allclose(np.asarray(w.obstacles()["cylinders"]), lay, atol=1e-4)
    # the home image sees a red blob towards every cylinder (bearing from home, heading 0)
    snaps = m.rings.snapshots
    for w in range(len(layouts)):
        h = m.home_index[w]
        seen = np.asarray(snaps.bearing[w, h])[np.asarray(snaps.valid[w, h])]
        rel = layouts[w, :, :2] - m.points[h]
        want = np.arctan2(rel[:, 1], rel[:, 0])
        gap = np.abs((seen[None] - want[:, None] + math.pi) % (2 * math.pi) - math.pi)
        assert np.degrees(gap.min(1)).max() < 6.0
    # a point within r + 10 cm of a cylinder has no snapshot
    dx = m.points[None, :, None, 0] - layouts[:, None, :, 0]
    dy = m.points[None, :, None, 1] - layouts[:, None, :, 1]
    near = np.hypot(dx, dy) < layouts[:, None, :, 2] + 10
    assert not (m.kept & near.any(-1)).any() and m.kept.sum(1).min() > 60


def synthetic(n: int, k: int) -> dict[str, dict]:
    """n members; claims 14-16 hold in the first k, fail in the others; the built-in world as member 0."""
    worlds = {}
    for i in range(n):
        good = i < k
        worlds[f"robot-m{i}"] = {
            "robot_images:delv:mean_error_deg": 20.0,
            "robot_images:delv:ideal_mean_error_deg": 15.0 if good else 20.0,
            "robot_images:delv:catchment_pct": 90.0 if good else 50.0,
            "robot_images:warping:mean_error_deg": 30.0 if good else 10.0,
            "robot_images:warping:catchment_pct": 80.0,
            **{f"robot_images:delv:Q{q}:mean_error_deg": 22.0 if good else 45.0 for q in study.LEVELS},
        }
    worlds["robot"] = dict(worlds["robot-m0"])
    return worlds


@pytest.mark.parametrize("n, k", [(10, 6), (10, 0), (12, 12)])
def test_claims_hold_in_exactly_k_of_n_members(n, k):
    layouts = np.repeat(er.robot_layouts(1, 0), n, axis=0)
    rows = {r["id"]: r for r in study.robot_claim_rows(synthetic(n, k), n, layouts)}
    assert set(rows) == set(study.CLAIM_IDS)
    for r in rows.values():
        assert r["members"] == n and r["holds %"] == pytest.approx(100.0 * k / n)
        assert r["built-in robot world"] == ("holds" if k else "fails")
        expect = "holds" if k == n else "fails" if k == 0 else "depends on the world"
        assert r["verdict over worlds"] == expect


def test_batched_members_equal_one_member_rendered_alone(batch):
    layouts, worlds, m = batch
    alone = render_in_memory(worlds[1], seed=3, settings=CAMERA_NOISE)  # the whole panorama, one world
    kept = m.kept[1]
    np.testing.assert_array_equal(np.asarray(m.rings.snapshots.mask[1])[kept], np.asarray(alone.rings.snapshots.mask))
    # the gray ring: a few band pixels round to a neighbouring grey level (the same rays, another XLA fusion)
    gray = np.abs(np.asarray(m.rings.snapshots.gray[1])[kept] - np.asarray(alone.rings.snapshots.gray))
    assert gray.max() <= 3.01 / 255 / 10 and np.mean(gray > 1e-6) < 1e-3
    assert m.home_index[1] == np.flatnonzero(kept).tolist()[alone.home_index]
    batched = er.map_numbers(er.image_maps(m, "delv"))["mean_error_deg"]
    assert batched[1] == pytest.approx(numbers(image_map(alone, "delv"))["mean_error_deg"], abs=1e-4)
    assert abs(batched[0] - batched[1]) > 0.1  # two layouts: the comparison could have failed
