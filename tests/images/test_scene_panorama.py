"""Panoramas of a ring scene (docs/images.md §10): the methods that read whole panoramas run on the
ring scenes, with a panorama rendered at every grid point and every rollout step, in vector maps,
catchments and sweeps; the bytes are those of a rendered database of the same world."""

from __future__ import annotations

import subprocess
import sys

import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core.images import Camera
from delvjax.core.images.scene_panorama import scene_panorama
from delvjax.images import render_in_memory
from delvjax.images._render import ImageSettings
from tests.cases.compiled import call

SMALL = {"n_pix": 96, "n_alpha": 32, "n_psi": 32}  # a small hypothesis grid: seconds, not minutes


def test_a_scene_panorama_is_the_database_panorama_of_the_same_pose():
    db = render_in_memory(
        "env1", spacing=200.0, settings=ImageSettings(camera=Camera(rows=48, cols=96), pixel_noise=0.0), panoramas=True
    )
    env = delvjax.load_env("env1")
    render = scene_panorama(96)
    rings = db.rings
    for i in (0, 7, rings.positions.shape[0] - 1):
        mine, elevations = call(render, env, env.valid, rings.positions[i], rings.headings[i])
        assert mine.dtype == np.uint8 and mine.shape == (48, 96)
        np.testing.assert_array_equal(np.asarray(mine), np.asarray(rings.snapshots.panorama[i]))
        np.testing.assert_allclose(np.asarray(elevations), np.asarray(rings.snapshots.elevations[i]))


def test_a_hidden_landmark_is_missing_from_the_panorama_as_from_the_ring():
    env = delvjax.load_env("env1")
    render = scene_panorama(96)
    pos, heading = jnp.array([500.0, 300.0]), jnp.float32(0.3)
    full, _ = call(render, env, env.valid, pos, heading)
    hidden = jnp.array([True, False, True, True])
    occluded, _ = call(render, env, hidden, pos, heading)
    without = delvjax.make_env(np.asarray(env.landmarks)[hidden], home=(500.0, 500.0), arena=(0, 0, 1000, 1000))
    alone, _ = call(render, without, without.valid, pos, heading)
    assert not np.array_equal(np.asarray(full), np.asarray(occluded))
    np.testing.assert_array_equal(np.asarray(occluded), np.asarray(alone))


def test_minwarping_homes_on_a_ring_scene_and_under_occlusion():
    vm = delvjax.vector_map("env1", method="minwarping", grid=Grid(spacing=200.0), **SMALL)
    error = np.asarray(vm.error_deg)
    assert np.asarray(vm.valid).all() and np.median(error) < 10.0, error
    c = delvjax.catchment(
        "env1", method="minwarping", occlude=1, grid=Grid(spacing=200.0), rules=Rules(max_steps=40), **SMALL
    )
    outcome, steps = np.asarray(c.outcome), np.asarray(c.steps)
    assert outcome.shape == (4, 25)
    # a panorama at every step: trials of many moves, most of them home (none undefined on a scene)
    assert (outcome == 0).mean() > 0.6 and steps[outcome == 0].max() > 3, (outcome, steps)


def test_the_hybrid_takes_delv_where_it_converges_on_a_ring_scene():
    kw = {
        "grid": Grid(spacing=100.0),
        "n_alpha": 36,
        "n_psi": 36,
    }  # 360 px rings: DELV's fit converges at some points
    mw = np.asarray(delvjax.vector_map("env1", method="minwarping", **kw).direction)
    hybrid = np.asarray(delvjax.vector_map("env1", method="hybrid", **kw).direction)
    delv = np.asarray(delvjax.vector_map("env1", method="delv", grid=Grid(spacing=100.0)).direction)
    from_delv, from_mw = np.isclose(hybrid, delv), np.isclose(hybrid, mw)
    assert 0.05 < from_delv.mean() < 0.95 and (from_delv | from_mw).all()


@pytest.mark.parametrize("kind", ["vector-map"])
def test_a_sweep_runs_minwarping_on_ring_scenes(tmp_path, kind):
    spec = tmp_path / "mw.toml"
    spec.write_text(
        f'[sweep]\nkind = "{kind}"\nmetrics = ["mean_error_deg", "invalid_pct"]\n\n'
        '[axes]\nenv = ["env1", "env2"]\nmethod = ["minwarping"]\nspacing = [200]\n'
        "n_pix = [96]\nn_alpha = [32]\nn_psi = [32]\n"
    )
    run = subprocess.run(
        [sys.executable, "-m", "delvjax.cli", "sweep", str(spec), "--out", str(tmp_path / "out")],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    rows = (tmp_path / "out" / "sweep.csv").read_text().splitlines()
    assert len(rows) == 3 and all(",minwarping," in r for r in rows[1:])
    assert all(float(r.split(",")[-1]) == 0.0 for r in rows[1:])  # no invalid point
