"""Rollouts, catchment area, success rate, trajectories, occlusion and noise (docs/model.md §5, §2.5).

Analytic cases first (ALV homes from inside a symmetric ring), then agreement with the
per-point NumPy reference rollout on random environments under both rule sets (the
default first_move="homing", collisions="ignore" and the physical agent's "release",
"fail"), then the rules themselves, properties (determinism, lane and block invariance,
occlusion batching, zero noise) and bad input.

Compiled programs are the cost of this file: a rollout program is compiled once per
(method, landmark count, trial block, lanes, record_paths). The tests below reuse a few
shapes on purpose: four landmarks, blocks of 32 (<= 32 trials, lanes 256), 128 (spacing-100
catchments) and 4 (recorded paths, lanes 4). Environments are explicit arrays, not the
built-in presets, unless only a count of points or lines is checked.
"""

import math

import jax
import numpy as np
import pytest

import delvjax
import delvjax.core.rollouts.trials
from delvjax import Grid, Rules
from delvjax.core import rollouts
from delvjax.core.errors import InputError
from delvjax.core.maps import grid_points, random_headings
from delvjax.envs._presets import make_env
from delvjax.options._setup import make_sensor
from tests.cases.rollouts import (
    ARENA,
    DEFAULT,
    FOUR,
    HOME,
    NOISE,
    PHYSICAL,
    RULE_SETS,
    angle_diff,
    random_landmarks,
    run,
)
from tests.twins.rollouts import HomeRecord, reference_rollout, release_direction

# --- analytic -------------------------------------------------------------------------------


@pytest.mark.parametrize("rules", RULE_SETS, ids=["default", "physical"])
def test_alv_homes_from_every_interior_start_of_a_symmetric_ring(rules):
    """ALV converges globally (Möller 2000): every start whose first move stays inside the ring homes
    (with first_move="release" the first move goes along the random release heading)."""
    env = delvjax.load_env("ring6")
    pts = grid_points(env.arena, 25.0)
    inner = pts[np.hypot(*(pts - 500.0).T) < 250.0 - 30.0 - 50.0]  # ring radius - r - d
    heads = np.asarray(random_headings(jax.random.PRNGKey(0), len(inner)))
    res = run(env, inner, heads, "alv", **rules)
    assert len(inner) > 100
    assert np.asarray(res.success).all()


# --- the NumPy twin ---------------------------------------------------------------------------


def test_success_flags_match_the_numpy_reference_rollout():
    """Under both rule sets, >= 98% identical success flags on random environments (float32 vs float64
    paths may part at a pixel edge). The library runs all 20 trials under both rules (one program per
    method); the slow twin checks trials 0.. under the default rules and 10.. under the physical ones."""
    rng = np.random.default_rng(0)
    plan = [("alv", 7), ("acv", 7), ("delv-compass", 7), ("delv", 2)]
    same = [0, 0]
    total = [0, 0]
    landmark_outcomes = [0, 0]
    for e in range(3):
        lms = random_landmarks(rng, 4)
        env = make_env(lms)
        starts, heads, placed = rollouts.release_points(env, jax.random.PRNGKey(e), 20, None, 10.0, 0.0)
        assert np.asarray(placed).all()
        starts, heads = np.asarray(starts), np.asarray(heads)
        record = HomeRecord(lms, ARENA, HOME)
        for method, n in plan:
            for k, rules in enumerate(RULE_SETS):
                res = run(env, starts, heads, method, **rules)
                landmark_outcomes[k] += int(np.sum(np.asarray(res.outcome) == rollouts.LANDMARK))
                for i in range(10 * k, 10 * k + n):
                    outcome, steps, _ = reference_rollout(
                        lms, ARENA, HOME, starts[i], heads[i], method, record=record, **rules
                    )
                    same[k] += (outcome == rollouts.SUCCESS) == bool(res.success[i])
                    total[k] += 1
    for k, rules in enumerate(RULE_SETS):
        assert same[k] >= 0.98 * total[k], f"{rules}: {total[k] - same[k]} of {total[k]} success flags differ"
    assert landmark_outcomes[0] == 0  # collisions="ignore": landmarks are no obstacles
    assert landmark_outcomes[1] > 0  # collisions="fail" is exercised by these trials


# --- the rules ----------------------------------------------------------------------------------


def test_paths_follow_the_rules():
    """first_move="release" (Algorithm 2): a DELV agent's first move goes along the release heading, d
    long; path NaN after the end; end = last position."""
    env = make_env(FOUR)
    starts = np.array([[100.0, 100.0], [900.0, 500.0], [500.0, 530.0], [20.0, 500.0]], np.float32)
    heads = np.array([0.3, 2.0, 1.0, math.pi], np.float32)
    res = run(env, starts, heads, "delv-compass", lanes=4, record_paths=True, **PHYSICAL)
    path, steps = np.asarray(res.path), np.asarray(res.steps)
    assert res.outcome[2] == rollouts.SUCCESS and steps[2] == 0  # released within home_radius
    assert res.outcome[3] == rollouts.ARENA and steps[3] == 1  # first move leaves the arena
    for t in range(4):
        assert np.allclose(path[t, steps[t]], res.end[t])
        assert np.isnan(path[t, steps[t] + 1 :]).all() and np.isfinite(path[t, : steps[t] + 1]).all()
        if steps[t] > 0:
            assert np.allclose(
                path[t, 1] - path[t, 0], 50.0 * np.array([math.cos(heads[t]), math.sin(heads[t])]), atol=1e-3
            )
    for t in (0, 1):
        assert res.outcome[t] == rollouts.SUCCESS
        assert np.hypot(*(path[t, steps[t]] - 500.0)) <= 50.0 < np.hypot(*(path[t, steps[t] - 1] - 500.0))


def test_first_move_follows_the_vector_map_direction_at_the_release_point():
    """first_move="homing": the first move goes d along the direction computed from a unit move along the
    release heading that ends at the start (the NumPy twin's vector-map direction); the first direction is
    reported, the same, under either rule. Under "release" (Algorithm 2) ALV, which needs no unit
    movement, turns to that same direction at once (DELV's blind first move: tests/core/rollouts/test_first_move.py)."""
    env = make_env(FOUR)
    starts = np.array([[150.0, 150.0], [850.0, 200.0], [200.0, 850.0], [850.0, 850.0]], np.float32)
    heads = np.array([0.3, 2.0, 4.0, 5.5], np.float32)
    res = run(env, starts, heads, "alv", lanes=4, record_paths=True, first_move="homing")
    rel = run(env, starts, heads, "alv", lanes=4, record_paths=True, first_move="release")
    first, valid = np.asarray(res.first_direction), np.asarray(res.first_valid)
    assert valid.all() and np.array_equal(np.asarray(rel.first_direction), first)
    record = HomeRecord(FOUR, ARENA, HOME)
    twin = [release_direction(record, FOUR, ARENA, starts[t], float(heads[t]), "alv") for t in range(4)]
    assert np.all(angle_diff(first, twin) < 1e-3), (first, twin)
    path, steps = np.asarray(res.path), np.asarray(res.steps)
    assert (steps > 0).all() and np.asarray(res.success).all()
    moves = path[:, 1] - path[:, 0]
    assert np.allclose(moves, 50.0 * np.stack([np.cos(first), np.sin(first)], axis=1), atol=1e-3)
    assert not np.allclose(moves, 50.0 * np.stack([np.cos(heads), np.sin(heads)], axis=1), atol=1.0)
    rel_moves = np.asarray(rel.path)[:, 1] - np.asarray(rel.path)[:, 0]
    assert np.allclose(rel_moves, moves, atol=1e-3)


def test_catchment_first_directions_are_the_vector_map():
    """A catchment's direction/valid/error_deg (its trials' first directions) equal `delvjax.vector_map`'s at
    the same grid points for the same seed, noise included (the vector map's streams)."""
    env = make_env(FOUR)
    noise = {k: v for k, v in NOISE.items() if not k.startswith("motion")}  # the vector map's noise sources
    c = delvjax.catchment(env, method="alv", seed=5, grid=Grid(spacing=100.0), **noise)
    vm = delvjax.vector_map(env, method="alv", seed=5, grid=Grid(spacing=100.0), **noise)
    inc = np.asarray(c.included)
    assert np.array_equal(inc, np.asarray(vm.included)) and inc.sum() > 50
    assert np.array_equal(np.asarray(c.points), np.asarray(vm.points))
    assert np.array_equal(np.asarray(c.heading), np.asarray(vm.heading))
    d_c, d_v = np.asarray(c.direction)[0][inc], np.asarray(vm.direction)[inc]
    assert np.array_equal(np.asarray(c.valid)[0][inc], np.asarray(vm.valid)[inc])
    assert np.array_equal(np.isnan(d_c), np.isnan(d_v)) and np.array_equal(np.isnan(d_v), ~np.asarray(vm.valid)[inc])
    ok = ~np.isnan(d_v)
    assert ok.sum() > 50 and np.array_equal(d_c, d_v, equal_nan=True)  # bitwise: the same per-point program
    assert np.allclose(np.asarray(c.error_deg)[0][inc], np.asarray(vm.error_deg)[inc], atol=1e-2)


# a cylinder (r 45) on the straight way from (500, 900) to home, three more away from it
CROSSED = np.array([[500.0, 700.0, 45.0], [250.0, 350.0, 30.0], [750.0, 350.0, 30.0], [780.0, 780.0, 30.0]])


def test_collisions_fail_ends_inside_a_landmark_and_ignore_passes_through():
    env = make_env(CROSSED)
    starts = [[500.0, 900.0], [150.0, 150.0], [850.0, 150.0], [150.0, 850.0]]
    fail = delvjax.trajectories(
        env, method="alv", starts=starts, grid=Grid(heading_deg=-90.0), rules=Rules(collisions="fail")
    )
    ignore = delvjax.trajectories(env, method="alv", starts=starts, grid=Grid(heading_deg=-90.0))
    assert fail.rules == {"first_move": "release", "collisions": "fail"} and ignore.rules == DEFAULT

    def inside(p):
        return np.hypot(p[0] - 500.0, p[1] - 700.0) < 45.0

    n = int(fail.steps[0])
    assert fail.outcome[0] == rollouts.LANDMARK and inside(np.asarray(fail.path)[0, n])
    assert ignore.outcome[0] == rollouts.SUCCESS and int(ignore.steps[0]) > n
    assert np.array_equal(np.asarray(ignore.path)[0, : n + 1], np.asarray(fail.path)[0, : n + 1])  # through it
    for t in range(1, 4):  # trials that meet no landmark do not depend on the rule
        assert fail.outcome[t] == ignore.outcome[t] == rollouts.SUCCESS and fail.steps[t] == ignore.steps[t]

    # a whole catchment: no LANDMARK outcome under "ignore"; the same trials as "fail" wherever "fail" met none
    c_fail = delvjax.catchment(env, method="alv", grid=Grid(spacing=100.0), rules=Rules(collisions="fail"))
    c_ignore = delvjax.catchment(env, method="alv", grid=Grid(spacing=100.0))
    s_fail, s_ignore = rollouts.catchment_summary(c_fail), rollouts.catchment_summary(c_ignore)
    assert s_ignore["rules"] == DEFAULT and s_fail["rules"] == {"first_move": "release", "collisions": "fail"}
    assert [row["landmark_count"] for row in s_ignore["per_mask"]] == [0]
    assert s_fail["per_mask"][0]["landmark_count"] > 0
    hit = np.asarray(c_fail.outcome) == rollouts.LANDMARK
    for field in ("outcome", "steps", "end"):
        assert np.array_equal(
            np.asarray(getattr(c_fail, field))[~hit], np.asarray(getattr(c_ignore, field))[~hit], equal_nan=True
        )
    assert s_ignore["catchment_pct"]["mean"] >= s_fail["catchment_pct"]["mean"]


# --- properties ---------------------------------------------------------------------------------


def test_deterministic_and_independent_of_lanes_with_every_noise_source():
    env = make_env(random_landmarks(np.random.default_rng(1), 4))  # shapes of the reference test: one compile less
    starts, heads, _ = rollouts.release_points(env, jax.random.PRNGKey(3), 20, None, 10.0, 0.0)
    noisy = make_sensor(**NOISE)
    a = run(env, starts, heads, "delv-compass", noisy)
    b = run(env, starts, heads, "delv-compass", noisy, lanes=7)  # lanes refilled from the queue
    c = run(env, starts, heads, "delv-compass", noisy)
    quiet = run(env, starts, heads, "delv-compass", make_sensor())
    assert np.asarray(a.success).any()
    for x, y in ((a, b), (a, c)):
        for field in ("outcome", "steps", "end", "invalid_steps", "first_direction", "first_valid"):
            assert np.array_equal(np.asarray(getattr(x, field)), np.asarray(getattr(y, field)), equal_nan=True)
    assert not np.array_equal(np.asarray(a.end), np.asarray(quiet.end))


def test_results_do_not_depend_on_the_trial_blocks(monkeypatch):
    """120 noisy trials in one block (padded to TRIAL_BLOCK) or in four blocks of 32 (the last one padded):
    every trial keeps its own noise stream, so the results are identical (collisions="fail" for a mix of
    outcomes)."""
    env = make_env(CROSSED)
    starts, heads, placed = rollouts.release_points(env, jax.random.PRNGKey(7), 120, None, 10.0, 0.0)
    assert np.asarray(placed).all()
    noisy = make_sensor(**NOISE)
    assert rollouts.trial_block(120) == rollouts.TRIAL_BLOCK
    whole = run(env, starts, heads, "alv", noisy, collisions="fail")
    monkeypatch.setattr(delvjax.core.rollouts.trials, "TRIAL_BLOCK", 32)
    assert rollouts.trial_block(120) == 32
    blocks = run(env, starts, heads, "alv", noisy, collisions="fail")
    outcome = np.asarray(whole.outcome)
    assert outcome.shape == (120,) and (outcome == rollouts.SUCCESS).any() and (outcome != rollouts.SUCCESS).any()
    for field in ("outcome", "steps", "end", "invalid_steps", "first_direction", "first_valid"):
        assert np.array_equal(np.asarray(getattr(whole, field)), np.asarray(getattr(blocks, field)), equal_nan=True)


def test_methods_sharing_one_program_give_the_same_numbers_as_their_own_programs():
    """`method_set=`: a traced index picks the method (lax.switch) and ALV skips the start snapshot
    (lax.cond): bitwise the same results, with noise, under occlusion, for a method that reads
    the start snapshot (DELV) and one that does not (ALV)."""
    env = make_env(random_landmarks(np.random.default_rng(1), 4))
    starts, heads, _ = rollouts.release_points(env, jax.random.PRNGKey(3), 20, None, 10.0, 0.0)
    masks = np.array([[True, True, True, True], [True, False, True, True]])
    noisy = make_sensor(**NOISE)
    family = ("delv", "delv-compass", "alv", "acv")
    for method in ("delv-compass", "alv"):
        own = run(env, starts, heads, method, noisy, masks=masks)
        shared = run(env, starts, heads, method, noisy, masks=masks, method_set=family)
        assert np.asarray(own.success).any()
        for field in ("outcome", "steps", "end", "invalid_steps", "first_direction", "first_valid"):
            assert np.array_equal(np.asarray(getattr(own, field)), np.asarray(getattr(shared, field)), equal_nan=True)


@pytest.mark.parametrize("method_set", [("alv", "acv"), ("delv-compass", "nope"), "delv-compass", (), 3])
def test_a_method_set_must_hold_known_methods_including_the_one_run(method_set, untyped):
    env = make_env(FOUR)
    with pytest.raises(InputError, match="method_set"):
        delvjax.catchment(env, method="delv-compass", method_set=method_set, grid=Grid(spacing=100.0))


def test_zero_noise_reproduces_the_noise_free_results_exactly():
    env = make_env(FOUR)
    plain = delvjax.catchment(env, method="alv", seed=1, grid=Grid(spacing=100.0))
    zero = delvjax.catchment(env, method="alv", seed=1, grid=Grid(spacing=100.0), **{k: 0.0 for k in NOISE})
    for field in ("outcome", "steps", "end", "direction"):
        assert np.array_equal(np.asarray(getattr(plain, field)), np.asarray(getattr(zero, field)), equal_nan=True)


def test_occlusion_k0_equals_no_occlusion_and_batched_masks_equal_single_ones():
    env = make_env(FOUR)
    kw = dict(method="alv", grid=Grid(spacing=200.0), seed=1)  # 25 points: one mask is a block of 32, four of 128
    none = delvjax.catchment(env, **kw)
    k0 = delvjax.catchment(env, occlude=0, **kw)
    for field in ("outcome", "steps", "end", "error_deg"):
        assert np.array_equal(np.asarray(getattr(none, field)), np.asarray(getattr(k0, field)), equal_nan=True)
    k1 = delvjax.catchment(env, occlude=1, **kw)
    assert k1.hidden == ((0,), (1,), (2,), (3,))
    one = delvjax.catchment(env, hidden=[2], **kw)
    for field in ("outcome", "steps", "error_deg"):
        assert np.array_equal(np.asarray(getattr(k1, field))[2], np.asarray(getattr(one, field))[0])
    summary = rollouts.catchment_summary(k1)
    pct = [row["catchment_pct"] for row in summary["per_mask"]]
    assert summary["catchment_pct"]["min"] == min(pct) and summary["catchment_pct"]["max"] == max(pct)
    assert summary["catchment_pct"]["max"] <= rollouts.catchment_summary(none)["catchment_pct"]["mean"] + 1e-9


def test_success_rate_bins_and_seeding():
    kw = dict(method="alv", distances=[50.0, 250.0, 450.0], trials=10, seed=2)  # 30 trials: a block of 32
    a = delvjax.success_rate("ring4", **kw)
    b = delvjax.success_rate("ring4", **kw)
    assert a.rules == DEFAULT
    assert np.array_equal(np.asarray(a.outcome), np.asarray(b.outcome))
    dist = np.hypot(*(np.asarray(a.start) - 500.0).transpose(2, 0, 1))
    placed = np.asarray(a.placed)
    assert np.allclose(dist[placed], np.repeat([50.0, 250.0, 450.0], 10).reshape(3, 10)[placed], atol=1e-2)
    rows = a.table()
    assert rows[0]["success_pct"] == 100.0 and rows[0]["mean_steps_success"] == 0.0  # released at home_radius
    assert rows[1]["placed"] == 10  # starts inside a landmark's clearance were redrawn


# --- CLI and bad input --------------------------------------------------------------------------------
