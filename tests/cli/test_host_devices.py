"""Every core by default (issue 54): a `delvjax catchment` or `sweep` process
asks XLA for one CPU device per core (`cli._entry.host_devices`), unless XLA_FLAGS sets the count or
DELVJAX_DEVICES names one; the files it writes are byte for byte those of one device."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from delvjax.cli._entry import DEVICE_FLAG, DEVICES_ENV, EVERY_CORE, host_devices, split_command
from delvjax.cli._entry import main as entry

CORES = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1

# the process's device count as the command would see it: the entry point runs, the command does not
PROBE = (
    "import sys, types, jax; m = sys.modules['delvjax.cli._main'] = types.ModuleType('delvjax.cli._main'); "
    "m.main = lambda argv, **k: print('devices', jax.device_count()) or 0; "
    "from delvjax.cli._entry import main; sys.argv = ['delvjax', *sys.argv[1:]]; main()"
)


def devices_seen(command: str, **env: str) -> int:
    clean = {k: v for k, v in os.environ.items() if k not in ("XLA_FLAGS", DEVICES_ENV)}
    out = subprocess.run(
        [sys.executable, "-c", PROBE, command],
        env={**clean, "JAX_PLATFORMS": "cpu", **env},
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return int(out.stdout.split("devices")[-1])


def test_the_default_asks_for_every_core_for_the_commands_that_gain():
    assert EVERY_CORE == {"catchment", "sweep"}
    assert host_devices("catchment", {}) == CORES
    assert host_devices("vector-map", {}) == 0  # its kept program is one device's
    assert host_devices("success-rate", {}) == 0  # compile-bound: the partitioned program compiles longer
    assert host_devices("reproduce", {}) == 0  # its studies run side by side in threads
    assert host_devices("catchment", {"XLA_FLAGS": f"{DEVICE_FLAG}=3"}) == 0  # the user's count stands
    assert host_devices("vector-map", {DEVICES_ENV: "3"}) == 3
    assert host_devices("catchment", {DEVICES_ENV: "1"}) == 1
    assert split_command(["sweep", "s.toml", "--out", "d"]) == "sweep"
    assert split_command(["sweep", "s.toml", "--num-processes", "2", "--process-id", "0"]) is None  # cores shared
    for bad in ("0", "two", "-1"):
        with pytest.raises(ValueError, match=DEVICES_ENV):
            host_devices("catchment", {DEVICES_ENV: bad})


def test_a_bad_device_count_is_one_line_and_exit_2(monkeypatch, capsys):
    monkeypatch.setenv(DEVICES_ENV, "none")
    monkeypatch.setattr(sys, "argv", ["delvjax", "catchment", "env1"])
    assert entry() == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_the_process_has_one_device_per_core_and_the_overrides_hold():
    assert devices_seen("catchment") == CORES
    assert devices_seen("vector-map") == 1
    assert devices_seen("catchment", XLA_FLAGS=f"{DEVICE_FLAG}=3") == 3
    assert devices_seen("catchment", **{DEVICES_ENV: "1"}) == 1


def test_every_core_writes_the_bytes_of_one_device(tmp_path: Path):
    """A catchment on every core (the default; on a one-core machine 2 forced devices) writes the CSV of
    one device."""
    clean = {k: v for k, v in os.environ.items() if k not in ("XLA_FLAGS", DEVICES_ENV)}
    written = []
    for devices in ({} if CORES > 1 else {DEVICES_ENV: "2"}, {DEVICES_ENV: "1"}):
        out = tmp_path / f"c{len(written)}.csv"
        cmd = [sys.executable, "-m", "delvjax.cli", "catchment", "env1", "--method", "alv", "--spacing", "100"]
        env = {**clean, **devices, "JAX_PLATFORMS": "cpu"}
        run = subprocess.run([*cmd, "--seed", "3", "--out", str(out)], env=env, capture_output=True, text=True)
        assert run.returncode == 0, run.stderr[-2000:]
        written.append(out.read_bytes())
    assert written[0] == written[1] and len(written[0]) > 100
