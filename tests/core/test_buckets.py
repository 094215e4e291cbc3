"""Shape buckets (issue 54; docs/reproduce.md "Shape buckets"): grids and trial counts of one bucket run
one compiled program, and padding to the bucket changes no number."""

from __future__ import annotations

import contextlib

import jax
import numpy as np

import delvjax
from delvjax import Grid, Rules
from delvjax.core import batching, maps
from delvjax.core.rollouts import release, success
from delvjax.core.rollouts.rules import rollout_keys
from delvjax.core.sensor import Sensor
from delvjax.evaluate import _vector_map
from delvjax.evaluate._vector_map import map_request
from delvjax.options._registry import METHODS

EVENT = "/jax/core/compile/backend_compile_duration"


@contextlib.contextmanager
def compiled_functions():
    """The names of the functions XLA compiles inside the block."""
    names: list[str] = []

    def listen(event: str, duration: float, **kwargs) -> None:
        if event == EVENT:
            names.append(kwargs.get("fun_name", "?"))

    jax.monitoring.register_event_duration_secs_listener(listen)
    try:
        yield names
    finally:
        jax.monitoring.unregister_event_duration_listener(listen)


def test_buckets_are_few_whole_groups_and_never_exceed_the_chunk():
    sizes = {batching.bucket(n, maps.DEFAULT_BATCH) for n in range(1, maps.DEFAULT_BATCH + 1)}
    assert sorted(sizes) == [256, 1024, 4096, 16384]
    assert batching.bucket(1, 1) == batching.WIDTH  # a chunk of one point: one group, as before
    assert batching.bucket(1000, 300) == 1024  # a chunk never holds fewer items than it must
    for n, cap in [(5, 200), (300, 1000), (1600, 3000), (9000, 10000)]:
        size = batching.bucket(n, cap)
        assert n <= size <= batching.padded(cap) and size % batching.WIDTH == 0


def test_two_grid_sizes_in_one_bucket_compile_once_and_give_the_numbers_of_an_unpadded_grid(monkeypatch):
    """DELV (whose near-tied hypotheses show any change of the arithmetic) on 100 and 81 grid points: the
    second map compiles nothing, and the first equals the per-point program run on its 100 points alone."""
    # the grid check's answer is kept (in memory and in the cache folder, `kept_number`): another test may have
    # kept the first map's, so the first map would not run the check's program and the second would compile it
    monkeypatch.setattr(_vector_map, "_CLEAR", {})
    monkeypatch.setattr(_vector_map, "kept_number", lambda what, key, compute: compute())
    env = delvjax.load_env("env1")
    first = delvjax.vector_map(env, method="delv", seed=3, bearing_noise_deg=1.0, grid=Grid(spacing=100.0))
    with compiled_functions() as names:
        second = delvjax.vector_map(env, method="delv", seed=3, bearing_noise_deg=1.0, grid=Grid(spacing=110.0))
    assert first.points.shape[0] == 100 and second.points.shape[0] == 81
    assert names == []  # before: the map program (7 s of CPU for DELV), the grid mask and the grid check
    r = map_request(env, "delv", 100.0, seed=3, bearing_noise_deg=1.0)
    headings = maps.random_headings(r["key"], 100)
    direction, valid = maps.homing_directions(r["env"], first.points, headings, r["key"], r["sensor"], r["method"])
    assert np.array_equal(np.asarray(first.heading), np.asarray(headings))
    assert np.array_equal(np.asarray(first.valid), np.asarray(valid))
    assert np.array_equal(np.asarray(first.direction), np.asarray(direction), equal_nan=True)
    assert np.asarray(valid).sum() > 50


def test_two_trial_counts_draw_their_release_points_in_one_program_and_the_same_points():
    env = delvjax.load_env("env1").arrays()
    key, dist = jax.random.PRNGKey(5), np.asarray([100.0, 300.0], np.float32)
    programs = success._release_bins._cache_size()
    runs = {}
    for trials in (3, 7):
        runs[trials] = success.success_rate_trials(
            env, METHODS["alv"], Sensor(), [100.0, 300.0], trials, key=key, rules=Rules(max_steps=3)
        )
    assert success._release_bins._cache_size() - programs <= 1  # before: one program per trial count
    _, _, k_start = rollout_keys(key)
    alone = release.release_points(env, jax.random.fold_in(k_start, 1), 3, dist[1])  # bin 1, unpadded
    assert np.array_equal(np.asarray(runs[3].start)[1], np.asarray(alone[0]))
    assert np.array_equal(np.asarray(runs[3].heading)[1], np.asarray(alone[1]))
    assert np.array_equal(np.asarray(runs[7].start)[:, :3], np.asarray(runs[3].start))
    assert runs[7].outcome.shape == (2, 7)


def test_a_catchment_of_another_grid_size_in_the_bucket_compiles_nothing():
    delvjax.catchment("env1", method="alv", grid=Grid(spacing=100.0), rules=Rules(max_steps=3))
    with compiled_functions() as names:
        c = delvjax.catchment("env1", method="alv", grid=Grid(spacing=110.0), rules=Rules(max_steps=3))
    assert names == [] and c.outcome.shape == (1, 81)  # before: headings, grid mask, errors, outcome


def test_catchments_of_any_mask_count_share_the_error_program():
    """A catchment's per-mask angular errors run on the masks padded to the rollouts' MASK_ROWS: one
    program for one and two hidden landmarks (4 and 6 masks on env1), where each count compiled its own,
    and the same errors as without the padding."""
    from delvjax.core import metrics

    env = delvjax.load_env("env1")
    delvjax.catchment(env, "alv", occlude=1, grid=Grid(spacing=70))
    before = metrics.angular_error_deg._cache_size()
    two = delvjax.catchment(env, "alv", occlude=2, grid=Grid(spacing=70))
    assert metrics.angular_error_deg._cache_size() == before
    unpadded = metrics.angular_error_deg(two.direction, two.valid, two.points[None], env.home)
    np.testing.assert_array_equal(np.asarray(two.error_deg), np.asarray(unpadded))
