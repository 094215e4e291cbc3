"""Rollouts, catchment area, success rate, trajectories, occlusion and noise (SPEC §5, §2.5).

Analytic cases first (ALV homes from inside a symmetric ring), then agreement with the
per-point NumPy reference rollout on random environments, then properties (determinism,
chunk invariance, occlusion batching, zero noise) and bad input.
"""

import math
import sys
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from reference_rollouts import HomeRecord, reference_rollout  # noqa: E402

import delvjax  # noqa: E402
from delvjax import rollouts  # noqa: E402
from delvjax.cli import main  # noqa: E402
from delvjax.errors import InputError  # noqa: E402
from delvjax.maps import grid_included, grid_points, random_headings  # noqa: E402
from delvjax.options import make_config  # noqa: E402
from delvjax.scene import make_env  # noqa: E402

ARENA = [0.0, 0.0, 1000.0, 1000.0]
HOME = [500.0, 500.0]
NOISE = dict(bearing_noise_deg=2.0, step_noise=0.05, turn_noise_deg=3.0, odometry_turn_noise_deg=1.0,
             compass_noise_deg=2.0, motion_heading_noise_deg=5.0, motion_step_noise=0.1)


def random_landmarks(rng, n):
    lms = []
    while len(lms) < n:
        r = rng.uniform(20, 40)
        x, y = rng.uniform(150, 850, 2)
        if math.hypot(x - 500, y - 500) < r + 60 or any(math.hypot(x - a, y - b) < r + c + 20 for a, b, c in lms):
            continue
        lms.append((x, y, r))
    return np.array(lms)


def run(env, starts, heads, method, config=None, lanes=64, key=0, masks=None, record_paths=False):
    n = starts.shape[0]
    masks = env.valid[None] if masks is None else masks
    return rollouts.run_trials(env, jnp.asarray(starts), jnp.asarray(heads), jnp.arange(n, dtype=jnp.int32),
                               jnp.zeros(n, jnp.int32), masks, jax.random.PRNGKey(key), config or make_config(),
                               method, lanes=lanes, record_paths=record_paths)


# --- analytic -------------------------------------------------------------------------------

def test_alv_homes_from_every_interior_start_of_a_symmetric_ring():
    """ALV converges globally (Möller 2000): every start whose first move stays inside the ring homes."""
    env = delvjax.load_env("ring6")
    pts = grid_points(env.arena, 25.0)
    inner = pts[np.hypot(*(pts - 500.0).T) < 250.0 - 30.0 - 50.0]  # ring radius - r - d
    heads = np.asarray(random_headings(jax.random.PRNGKey(0), len(inner)))
    res = run(env, inner, heads, "alv")
    assert len(inner) > 100
    assert np.asarray(res.success).all()


# --- the NumPy twin ---------------------------------------------------------------------------

def test_success_flags_match_the_numpy_reference_rollout():
    """>= 98% identical success flags on random environments (float32 vs float64 paths may part at a pixel edge)."""
    rng = np.random.default_rng(0)
    plan = [("alv", 20), ("acv", 20), ("delv-compass", 20), ("delv", 6)]
    same = total = 0
    for e in range(3):
        lms = random_landmarks(rng, 4)
        env = make_env(lms)
        starts, heads, placed = rollouts.release_points(env, jax.random.PRNGKey(e), 20, None, 10.0, 0.0)
        assert np.asarray(placed).all()
        starts, heads = np.asarray(starts), np.asarray(heads)
        record = HomeRecord(lms, ARENA, HOME)
        for method, n in plan:
            res = run(env, starts, heads, method)
            for i in range(n):
                outcome, steps, _ = reference_rollout(lms, ARENA, HOME, starts[i], heads[i], method, record=record)
                same += (outcome == rollouts.SUCCESS) == bool(res.success[i])
                total += 1
    assert same >= 0.98 * total, f"{total - same} of {total} success flags differ"


def test_paths_follow_the_rules():
    """First move along the release heading, d long; path NaN after the end; end = last position."""
    env = delvjax.load_env("env1")
    starts = np.array([[100.0, 100.0], [900.0, 500.0], [500.0, 530.0], [20.0, 500.0]], np.float32)
    heads = np.array([0.3, 2.0, 1.0, math.pi], np.float32)
    res = run(env, starts, heads, "alv", record_paths=True)
    path, steps = np.asarray(res.path), np.asarray(res.steps)
    assert res.outcome[2] == rollouts.SUCCESS and steps[2] == 0  # released within home_radius
    assert res.outcome[3] == rollouts.ARENA and steps[3] == 1  # first move leaves the arena
    for t in range(4):
        assert np.allclose(path[t, steps[t]], res.end[t])
        assert np.isnan(path[t, steps[t] + 1:]).all() and np.isfinite(path[t, :steps[t] + 1]).all()
        if steps[t] > 0:
            assert np.allclose(path[t, 1] - path[t, 0], 50.0 * np.array([math.cos(heads[t]), math.sin(heads[t])]),
                               atol=1e-3)
    for t in (0, 1):
        assert res.outcome[t] == rollouts.SUCCESS
        assert np.hypot(*(path[t, steps[t]] - 500.0)) <= 50.0 < np.hypot(*(path[t, steps[t] - 1] - 500.0))


# --- properties ---------------------------------------------------------------------------------

def test_deterministic_and_independent_of_lanes_with_every_noise_source():
    env = make_env(random_landmarks(np.random.default_rng(1), 4))  # shapes of the reference test: one compile less
    starts, heads, _ = rollouts.release_points(env, jax.random.PRNGKey(3), 20, None, 10.0, 0.0)
    noisy = make_config(**NOISE)
    a = run(env, starts, heads, "delv-compass", noisy, lanes=64)
    b = run(env, starts, heads, "delv-compass", noisy, lanes=7)
    c = run(env, starts, heads, "delv-compass", noisy, lanes=64)
    quiet = run(env, starts, heads, "delv-compass", make_config(), lanes=64)
    assert np.asarray(a.success).any()
    for x, y in ((a, b), (a, c)):
        for field in ("outcome", "steps", "end", "invalid_steps"):
            assert np.array_equal(np.asarray(getattr(x, field)), np.asarray(getattr(y, field)))
    assert not np.array_equal(np.asarray(a.end), np.asarray(quiet.end))


def test_zero_noise_reproduces_the_noise_free_results_exactly():
    plain = delvjax.catchment("env1", method="alv", spacing=100.0, seed=1)
    zero = delvjax.catchment("env1", method="alv", spacing=100.0, seed=1, **{k: 0.0 for k in NOISE})
    for field in ("outcome", "steps", "end", "direction"):
        assert np.array_equal(np.asarray(getattr(plain, field)), np.asarray(getattr(zero, field)), equal_nan=True)


def test_occlusion_k0_equals_no_occlusion_and_batched_masks_equal_single_ones():
    kw = dict(method="alv", spacing=100.0, seed=1)
    none = delvjax.catchment("env1", **kw)
    k0 = delvjax.catchment("env1", occlude=0, **kw)
    for field in ("outcome", "steps", "end", "error_deg"):
        assert np.array_equal(np.asarray(getattr(none, field)), np.asarray(getattr(k0, field)), equal_nan=True)
    k1 = delvjax.catchment("env1", occlude=1, **kw)
    assert k1.hidden == ((0,), (1,), (2,), (3,))
    one = delvjax.catchment("env1", hidden=[2], **kw)
    for field in ("outcome", "steps", "error_deg"):
        assert np.array_equal(np.asarray(getattr(k1, field))[2], np.asarray(getattr(one, field))[0])
    summary = rollouts.catchment_summary(k1)
    pct = [row["catchment_pct"] for row in summary["per_mask"]]
    assert summary["catchment_pct"]["min"] == min(pct) and summary["catchment_pct"]["max"] == max(pct)
    assert summary["catchment_pct"]["max"] <= rollouts.catchment_summary(none)["catchment_pct"]["mean"] + 1e-9


def test_success_rate_bins_and_seeding():
    kw = dict(method="alv", distances=[50.0, 250.0, 450.0], trials=12, seed=2)
    a = delvjax.success_rate("ring4", **kw)
    b = delvjax.success_rate("ring4", **kw)
    assert np.array_equal(np.asarray(a.outcome), np.asarray(b.outcome))
    dist = np.hypot(*(np.asarray(a.start) - 500.0).transpose(2, 0, 1))
    assert np.allclose(dist[np.asarray(a.placed)], np.repeat([50.0, 250.0, 450.0], 12).reshape(3, 12)[np.asarray(a.placed)], atol=1e-2)
    rows = a.table()
    assert rows[0]["success_pct"] == 100.0 and rows[0]["mean_steps_success"] == 0.0  # released at home_radius
    assert rows[1]["placed"] == 12  # starts inside a landmark's clearance were redrawn


# --- CLI and bad input --------------------------------------------------------------------------------

def test_cli_catchment_success_rate_trajectories(tmp_path):
    out = tmp_path / "c.csv"
    assert main(["catchment", "env1", "--method", "alv", "--spacing", "100", "--out", str(out), "--occlude", "1",
                 "--summary", str(tmp_path / "c.json")]) == 0
    header = out.read_text().splitlines()[0].split(",")
    assert header[:5] == ["x", "y", "heading_deg", "success", "steps"] and "hidden" in header
    env = delvjax.load_env("env1")
    n_points = int(np.sum(np.asarray(grid_included(env, jnp.asarray(grid_points(env.arena, 100.0)), 10.0))))
    assert len(out.read_text().splitlines()) == 1 + 4 * n_points
    assert main(["success-rate", "ring4", "--method", "alv,acv", "--trials", "12", "--distances", "50", "250", "450",
                 "--seed", "2", "--out", str(tmp_path / "s.csv")]) == 0
    assert len((tmp_path / "s.csv").read_text().splitlines()) == 1 + 2 * 3
    assert main(["trajectories", "env1", "--method", "alv", "--start", "100", "100", "--start", "800", "300",
                 "--out", str(tmp_path / "t.csv"), "--plot", str(tmp_path / "t.png")]) == 0
    assert (tmp_path / "t.png").stat().st_size > 0


@pytest.mark.parametrize("argv, field", [
    (["catchment", "env1", "--occlude", "5"], "occlude"),
    (["catchment", "env1", "--bearing-noise-deg", "-1"], "bearing_noise_deg"),
    (["catchment", "env1", "--max-steps", "0"], "max_steps"),
    (["success-rate", "env1", "--motion-step-noise", "-0.1"], "motion_step_noise"),
    (["success-rate", "env1", "--trials", "0"], "trials"),
    (["trajectories", "env1", "--start", "330", "640"], "starts[0]"),
    (["trajectories", "env1", "--home-radius", "0"], "home_radius"),
])
def test_bad_input_exits_2_without_output(tmp_path, capsys, argv, field):
    out = tmp_path / "o.csv"
    assert main(argv + ["--out", str(out)]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.startswith("delvjax: error: ") and field in last
    assert not out.exists()


def test_api_bad_input_raises_input_error():
    with pytest.raises(InputError, match="occlude"):
        delvjax.catchment("ring3", occlude=4)
    with pytest.raises(InputError, match="occlude"):
        delvjax.catchment("env1", occlude=1, hidden=[0])
    with pytest.raises(InputError, match="max_steps"):
        delvjax.success_rate("env1", max_steps=0)
    with pytest.raises(InputError, match="distances"):
        delvjax.success_rate("env1", distances=[])
