"""A sweep over two processes (`jax.distributed` on 127.0.0.1, docs/sweeps.md "Many machines"): the
merged result written by process 0 equals the one-process result bit for bit."""

from __future__ import annotations

import os
import socket
import subprocess
import sys

import numpy as np
import pytest

import delvjax
from delvjax.cli._main import main

SWEEP = "[axes]\nmethod = ['delv', 'alv']\nd = [30, 60]\nseed = [0, 1]\nspacing = [200]\n"
CATCHMENT = (
    "[sweep]\nkind = 'catchment'\n[axes]\nmethod = ['alv']\nocclude = [0, 1]\nseed = [0, 1, 2]\n"
    "bearing_noise_deg = [4.0]\nspacing = [150]\n"
)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize("text, devices", [(SWEEP, 2), (CATCHMENT, 1)], ids=["vector-map-2x2", "catchment-2x1"])
def test_two_processes_give_the_one_process_numbers(tmp_path, text, devices):
    """One mesh over 2 processes x `devices` forced host devices each."""
    path = tmp_path / "s.toml"
    path.write_text(text)
    assert main(["sweep", str(path), "--out", str(tmp_path / "one")]) == 0
    port, two = free_port(), tmp_path / "two"
    env = dict(
        os.environ,
        JAX_PLATFORMS="cpu",
        DELVJAX_CACHE_DIR="",
        XLA_FLAGS=f"--xla_force_host_platform_device_count={devices}",
    )
    cmd = [
        sys.executable,
        "-m",
        "delvjax.cli",
        "sweep",
        str(path),
        "--out",
        str(two),
        "--coordinator",
        f"127.0.0.1:{port}",
        "--num-processes",
        "2",
        "--process-id",
    ]
    procs = [
        subprocess.Popen(cmd + [str(i)], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        for i in (0, 1)
    ]
    outs = [p.communicate(timeout=240) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], [o[1][-1500:] for o in outs]
    assert "wrote" in outs[0][0] and "wrote" not in outs[1][0]  # process 0 writes, process 1 only computes
    assert f"on 2 process(es), {2 * devices} device(s)" in outs[0][1]  # one mesh over all of them
    one, merged = delvjax.load_sweep(tmp_path / "one"), delvjax.load_sweep(two)
    for name in one.data_vars:
        assert np.array_equal(one[name].values, merged[name].values, equal_nan=True), name


def test_process_options_are_checked_before_any_work(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(SWEEP)
    for extra, field in [
        (["--coordinator", "127.0.0.1:1"], "--coordinator"),
        (["--coordinator", "nohost", "--num-processes", "2", "--process-id", "0"], "--coordinator"),
        (["--coordinator", "h:1", "--num-processes", "2", "--process-id", "2"], "--process-id"),
    ]:
        assert main(["sweep", str(path), "--out", str(tmp_path / "o")] + extra) == 2
        assert capsys.readouterr().err.startswith(
            (f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:")
        )
    assert not (tmp_path / "o").exists()


def test_importing_delvjax_leaves_the_jax_backend_alone():
    """jax.distributed.initialize must run before JAX starts its backend, so importing delvjax (the CLI,
    every method, the studies) must not start it (an optimistix solver built at import time did)."""
    code = (
        "from jax._src import xla_bridge as xb; import delvjax, delvjax.cli, studies; "
        "import sys; sys.exit(1 if xb._backends else 0)"
    )
    assert subprocess.run([sys.executable, "-c", code], env=dict(os.environ, JAX_PLATFORMS="cpu")).returncode == 0


@pytest.mark.parametrize("process_id", ["0", "1"])  # the coordinator waiting for a peer, a peer for it
def test_a_process_whose_peers_never_join_fails_in_one_line(tmp_path, process_id):
    path = tmp_path / "s.toml"
    path.write_text(SWEEP)
    port = free_port()
    argv = ["sweep", str(path), "--out", str(tmp_path / "o"), "--coordinator", f"127.0.0.1:{port}"]
    argv += ["--num-processes", "2", "--process-id", process_id, "--connect-timeout", "2"]
    run = subprocess.run(
        [sys.executable, "-m", "delvjax.cli", *argv],
        env=dict(os.environ, JAX_PLATFORMS="cpu"),
        capture_output=True,
        text=True,
        timeout=120,
    )
    err = run.stderr.strip().splitlines()
    assert run.returncode == 2 and len(err) == 1, run.stderr[-2000:]  # not SIGABRT after 5 minutes
    assert err[0].startswith("delvjax: error: --coordinator:") and f"127.0.0.1:{port}" in err[0]
    assert not (tmp_path / "o").exists()
