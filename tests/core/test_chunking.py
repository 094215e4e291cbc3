"""The same numbers however the work is split: lanes, host chunks, devices (docs/reproduce.md "Chunking").

Bitwise: every per-point and per-trial program runs `batching.WIDTH` items at a time, so the
lane count, the chunk size and the number of devices change only how many groups run.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core.rollouts.trials import device_split

FIELDS = ("outcome", "steps", "end", "invalid_steps", "direction", "valid")
SCRIPT = """
import sys, numpy as np, jax, delvjax
assert jax.local_device_count() == 4, jax.local_devices()
c = delvjax.catchment(
    "env1", sys.argv[2], grid=delvjax.Grid(spacing=100.0), rules=delvjax.Rules(lanes=7), seed=3, bearing_noise_deg=1.0
)
vm = delvjax.vector_map(
    "env1", sys.argv[2], grid=delvjax.Grid(spacing=50.0), batch_size=100, seed=3, bearing_noise_deg=1.0
)
np.savez(sys.argv[1], **{f"c_{f}": np.asarray(getattr(c, f)) for f in %r}, v_direction=np.asarray(vm.direction),
         v_valid=np.asarray(vm.valid))
""" % (FIELDS,)


def single_device(method: str, lanes: int = 256) -> dict[str, np.ndarray]:
    c = delvjax.catchment(
        "env1", method=method, seed=3, bearing_noise_deg=1.0, grid=Grid(spacing=100.0), rules=Rules(lanes=lanes)
    )
    return {f"c_{f}": np.asarray(getattr(c, f)) for f in FIELDS}


def assert_same(a: dict, b: dict) -> None:
    for k in a:
        assert np.array_equal(a[k], b[k], equal_nan=True), (k, np.argwhere(~((a[k] == b[k]) | np.isnan(a[k]))))


@pytest.mark.parametrize("method", ["delv"])  # DELV's near-tied hypotheses made the lane count show
def test_catchment_is_bit_identical_for_1_7_and_256_lanes(method):
    ref = single_device(method)
    assert ref["c_steps"].max() > 1 and (ref["c_outcome"] == 0).any()
    for lanes in (1, 7):
        assert_same(ref, single_device(method, lanes))


@pytest.mark.parametrize("method", ["delv", "warping"])
def test_vector_map_is_bit_identical_for_every_chunk_size(method):
    maps = [
        delvjax.vector_map("env1", method=method, batch_size=b, bearing_noise_deg=1.0, grid=Grid(spacing=50.0))
        for b in (16384, 1, 7, 100)
    ]
    for vm in maps[1:]:
        for f in ("direction", "valid", "heading", "error_deg"):
            assert np.array_equal(np.asarray(getattr(vm, f)), np.asarray(getattr(maps[0], f)), equal_nan=True), f


def test_device_split_gives_every_trial_to_one_device_once():
    for n_valid, n_dev, per in [(10, 4, 4), (1, 4, 4), (16, 4, 4), (7, 3, 3), (5, 2, 8)]:
        take, counts, keep = device_split(n_valid, n_dev, per)
        assert take.shape == (n_dev * per,) and counts.sum() == n_valid and len(keep) == n_valid
        assert np.array_equal(take[keep], np.arange(n_valid))  # trial order restored


@pytest.mark.parametrize("method", ["delv"])
def test_four_host_devices_give_the_one_device_numbers(tmp_path: Path, method):
    """`XLA_FLAGS=--xla_force_host_platform_device_count=4`: trials and grid points are split over 4
    devices (`batching.over_devices`); catchment and vector map are bitwise equal (success rates and
    trajectories run the same `run_trials`)."""
    out = tmp_path / "four.npz"
    env = dict(os.environ, XLA_FLAGS="--xla_force_host_platform_device_count=4", JAX_PLATFORMS="cpu")
    run = subprocess.run([sys.executable, "-c", SCRIPT, str(out), method], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-2000:]
    four = dict(np.load(out))
    ref = single_device(method, lanes=256)
    vm = delvjax.vector_map("env1", method=method, seed=3, bearing_noise_deg=1.0, grid=Grid(spacing=50.0))
    ref.update(v_direction=np.asarray(vm.direction), v_valid=np.asarray(vm.valid))
    assert_same(ref, four)
