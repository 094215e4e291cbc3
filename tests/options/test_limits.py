"""Runs too large for the machine are refused before any work, with an estimate; large grids run in
host-side chunks (issue "hardening" item 2; docs/reproduce.md "Large grids")."""

from __future__ import annotations

import re
import time

import jax
import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core import maps
from delvjax.core.errors import InputError
from delvjax.options._limits import MAX_POINTS, duration, grid_count


def refused(capsys, argv, field) -> str:
    t = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - t < 5.0  # refused before any work
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"delvjax: error: --{field.replace('_', '-')}:"), err
    return err[0]


@pytest.mark.parametrize(
    "argv, field",
    [
        (["vector-map", "env1", "--spacing", "0.01"], "spacing"),  # 1e10 points: MemoryError traceback before
        (["vector-map", "env1", "--spacing", "0.1"], "spacing"),  # 1e8 points: sat at 7.6 GB before
        (["catchment", "env1", "--spacing", "0.5"], "spacing"),
        (["catchment", "env1", "--spacing", "5", "--occlude", "1"], "spacing"),  # 4e4 points x 3 masks > limit 1e5
        (["success-rate", "env1", "--trials", "100000000"], "trials"),
        (["trajectories", "env1", "--max-steps", "200000000"], "max_steps"),
        (["trajectories", "env1", "--n-starts", "2000000"], "n_starts"),
    ],
)
def test_a_run_above_max_points_is_refused_with_an_estimate(tmp_path, capsys, argv, field):
    out = tmp_path / "r.csv"
    extra = ["--max-points", "100000"] if "--occlude" in argv else []
    line = refused(capsys, argv + extra + ["--out", str(out)], field)
    assert "max_points" in line and "GB" in line and re.search(r"up to [0-9.]+ (s|min|h|days) on 2 CPU", line)
    assert not out.exists()


def test_max_points_is_the_users_to_raise(tmp_path, capsys):
    out = tmp_path / "r.csv"
    refused(capsys, ["vector-map", "env1", "--spacing", "100", "--max-points", "99", "--out", str(out)], "spacing")
    assert main(["vector-map", "env1", "--spacing", "100", "--max-points", "100", "--out", str(out)]) == 0
    assert out.exists()
    with pytest.raises(InputError, match="max_points"):
        delvjax.vector_map("env1", max_points=99, grid=Grid(spacing=100.0))
    assert MAX_POINTS == 1_000_000


@pytest.mark.parametrize(
    "arena, spacing",
    [
        ((0, 0, 1000, 1000), 25.0),
        ((0, 0, 1000, 1000), 30.0),
        ((-7.5, 3.0, 333.3, 99.9), 0.7),
        ((0, 0, 1, 1), 2.0),
        ((0, 0, 1e4, 10), 0.1),
        ((5, 5, 6, 7), 1e-3),
    ],
)
def test_the_grid_count_is_known_before_the_grid_is_built(arena, spacing):
    n = grid_count(arena, spacing)
    built = maps.grid_points(np.asarray(arena), spacing).shape[0]
    assert built <= n <= built + 2 * np.sqrt(max(n, 1)) + 1


def test_a_grid_in_many_chunks_reports_progress_and_gives_the_one_chunk_numbers():
    calls = []
    vm = delvjax.vector_map("env1", batch_size=100, grid=Grid(spacing=50.0))
    env = delvjax.load_env("env1")
    chunked = maps.vector_map(
        env,
        delvjax.DELV(),
        delvjax.Sensor(),
        spacing=50.0,
        key=jax.random.PRNGKey(0),
        batch_size=128,
        progress=lambda n, total: calls.append((n, total)),
    )
    assert [t for _, t in calls] == [400] * 4 and [n for n, _ in calls] == [128] * 3 + [16]  # chunks of 128, then 16
    assert np.array_equal(np.asarray(chunked.direction), np.asarray(vm.direction), equal_nan=True)


def test_recorded_paths_stay_within_their_budget_and_the_usual_block_is_shared():
    from delvjax.core.rollouts.trials import PATH_BUDGET, TRIAL_BLOCK, trial_block

    assert trial_block(8, 50, True) == trial_block(10**6) == TRIAL_BLOCK  # one program for every rollout
    for n, steps in [(6, 100_000), (10**6, 5_000), (1, 10**7)]:
        block = trial_block(n, steps, True)
        assert block % 128 == 0 and (block * (steps + 1) <= PATH_BUDGET or block == 128)


@pytest.mark.parametrize(
    "seconds, text",
    [(0.5, "0.5 s"), (40, "40 s"), (200, "3 min"), (10800, "3 h"), (3600 * 2.5, "2.5 h"), (3 * 86400, "3 days")],
)
def test_durations_read_as_a_person_says_them(seconds, text):
    assert duration(seconds) == text
