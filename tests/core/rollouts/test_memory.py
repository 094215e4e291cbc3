"""Rollout memory does not grow with max_steps unless the paths are kept (docs/reliability.md): past
`trials.SHARED_PATH_STEPS` positions a catchment or success-rate block records no path (below it every block
keeps them, at most 8 MB, and the three commands share one program); trajectories record every position,
and their size is refused before any work above its limit."""

from __future__ import annotations

from functools import partial

import jax
import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core.errors import InputError
from delvjax.core.rollouts import trials
from delvjax.core.rollouts.rules import TIMEOUT

HUGE = 100_000  # max_steps: the paths of one block would be 16384 x 100001 x 2 float32 = 13 GB


class Stop(Exception):
    """Raised by the spy once it has seen the block's shapes: nothing is compiled or run."""


KW = {
    "catchment": dict(grid=Grid(spacing=200.0)),
    "success_rate": dict(distances=[100.0], trials=4),
}  # trajectories: STARTS
STARTS = dict(starts=[(300.0, 300.0)])
RUN_BLOCK = trials.run_block  # the real one (a spy replaces it during a test)


def block_of(monkeypatch, command: str, **options) -> tuple:
    """The first block `delvjax.<command>("env1", ...)` would run, from a spy on `run_block` that stops before
    any compilation: (starts shape, lanes, record_paths, the path's shape)."""
    seen = []

    def spy(rollout, starts, headings, n_valid, lanes, path_length=1):
        shapes = jax.eval_shape(
            partial(RUN_BLOCK, lanes=lanes, path_length=path_length),
            rollout,
            starts,
            headings,
            n_valid,
        )
        seen.append((starts.shape, lanes, path_length > 1, shapes.path.shape))  # whether it records paths
        raise Stop

    monkeypatch.setattr(trials, "run_block", spy)
    with pytest.raises(Stop):
        getattr(delvjax, command)("env1", **KW.get(command, STARTS), **options)
    return seen[0]


@pytest.mark.parametrize("command", ["catchment", "success_rate", "trajectories"])
def test_only_trajectories_record_paths(monkeypatch, command):
    (block, *_), _, _, path = block_of(monkeypatch, command, rules=Rules(max_steps=HUGE))
    assert path == ((block, HUGE + 1, 2) if command == "trajectories" else (block, 1, 2))


def test_trajectories_that_would_not_fit_are_refused_with_the_estimate():
    with pytest.raises(InputError) as exc:
        delvjax.trajectories("env1", n_starts=24, rules=Rules(max_steps=2_000_000_000))
    assert exc.value.field == "max_steps" and "path point" in str(exc.value)


@pytest.mark.parametrize(
    "command, kw",
    [("catchment", dict(grid=Grid(spacing=25.0))), ("success_rate", dict(distances=[100.0, 200.0], trials=500))],
)
def test_rollouts_that_could_run_for_hours_are_refused_with_the_estimate(command, kw):
    with pytest.raises(InputError) as exc:
        getattr(delvjax, command)("env1", rules=Rules(max_steps=HUGE), **kw)
    assert exc.value.field == "max_steps" and "moves" in str(exc.value) and " on 2 CPU cores" in str(exc.value)


def test_catchments_success_rates_and_trajectories_share_one_program(monkeypatch):
    """With the default max_steps every block keeps its paths (trials.SHARED_PATH_STEPS), so the three
    commands call run_block with the same static arguments and shapes: one compilation serves them."""
    seen = {c: block_of(monkeypatch, c, method="alv") for c in ("catchment", "success_rate", "trajectories")}
    assert len(set(seen.values())) == 1, seen
    ((starts, _, kept, path),) = set(seen.values())
    assert kept and path == (starts[0], trials.SHARED_PATH_STEPS, 2)  # the buffer; users get MAX_STEPS + 1


def test_rollouts_of_every_short_max_steps_share_one_program_and_stop_where_the_longer_run_was():
    """max_steps is traced (`Rollout.max_steps`; the path buffer is `trials.path_length` long): 20 and 40
    moves run one compiled block program, and the 20-move run is the 40-move run cut at move 20: the same
    path up to there, the same outcome where the trial ended by then, a time-out where it did not."""
    starts = [(250.0, 250.0), (750.0, 300.0), (500.0, 850.0), (150.0, 600.0), (820.0, 780.0)]
    kw = dict(method="delv-compass", starts=starts, bearing_noise_deg=4.0, step_noise=0.1)
    before = trials.run_block._cache_size()
    long, short = (delvjax.trajectories("env1", rules=Rules(max_steps=m), **kw) for m in (40, 20))
    assert trials.run_block._cache_size() - before <= 1  # one program (none where another test compiled it)
    assert long.path.shape == (5, 41, 2) and short.path.shape == (5, 21, 2)
    steps, outcome = np.asarray(long.steps), np.asarray(long.outcome)
    ended = steps <= 20  # home, a landmark or the arena by move 20
    assert ended.any() and (~ended).any()  # both kinds of trial, so the comparison can fail
    assert np.array_equal(np.asarray(short.path), np.asarray(long.path)[:, :21], equal_nan=True)
    assert np.array_equal(np.asarray(short.outcome)[ended], outcome[ended])
    assert np.all(np.asarray(short.outcome)[~ended] == TIMEOUT) and np.all(np.asarray(short.steps)[~ended] == 20)
