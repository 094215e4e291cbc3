"""Fault injection for tests/cli/test_kills.py: a `delvjax` command in a child process that kills itself
(SIGKILL or SIGTERM) at the n-th file it publishes, either with that file half written under its
temporary name ("during") or whole but not yet renamed ("before-rename"), or, for render-db, at the n-th
chunk of images."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

CHILD = r"""
import os, signal, sys
from delvjax.outputs import _files
from delvjax.images import _writer
import delvjax.sweeps._run as sweep_run

how, sig, n, argv = sys.argv[1], getattr(signal, sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
sweep_run.CELL_CHUNK = 2  # several chunks in a small sweep: kills between them
calls = [0]

def fault(tmp=None):
    calls[0] += 1
    if calls[0] != n:
        return
    if how == "during" and tmp is not None:
        size = os.path.getsize(tmp)
        with open(tmp, "r+b") as fh:
            fh.truncate(max(1, size // 2))
    os.kill(os.getpid(), sig)

publish = _files._publish
def _publish(tmp, target):
    fault(tmp)
    return publish(tmp, target)
_files._publish = _publish

add = _writer.DatabaseWriter.add
def _add(self, *args, **kwargs):
    add(self, *args, **kwargs)
    if how == "chunk":
        fault()
_writer.DatabaseWriter.add = _add

from delvjax.cli._main import main
sys.exit(main(argv, own_process=True))
"""


def run_killed(how: str, signal: str, n: int, argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    """Run `delvjax argv` in a child that kills itself at the n-th publish (or chunk, how="chunk")."""
    return subprocess.run(
        [sys.executable, "-c", CHILD, how, signal, str(n), *argv],
        cwd=cwd,
        env=dict(os.environ, JAX_PLATFORMS="cpu"),
        capture_output=True,
        text=True,
        timeout=600,
    )


def temporaries(folder: Path) -> list[str]:
    """Every hidden file or folder under `folder` but the sweep's chunk store: a temporary left behind."""
    return sorted(str(p) for p in folder.rglob(".*") if p.name != ".cells")


def contents(folder: Path) -> dict[str, bytes]:
    """Every file under `folder` (the sweep's chunk store left out), by relative path."""
    return {
        str(p.relative_to(folder)): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and ".cells" not in p.parts
    }


def fake_sweep(folder: Path) -> Path:
    """A sweep folder as `delvjax sweep` leaves it, without running one (plot-sweep reads sweep.nc)."""
    folder.mkdir()
    import xarray as xr

    ds = xr.Dataset(
        {"mean_error_deg": (("d", "seed"), np.arange(4.0).reshape(2, 2))}, coords={"d": [30.0, 60.0], "seed": [0, 1]}
    )
    ds.to_netcdf(folder / "sweep.nc", engine="scipy")
    (folder / "sweep.csv").write_text("d,seed,mean_error_deg\n30,0,0\n30,1,1\n60,0,2\n60,1,3\n")
    (folder / "sweep.toml").write_text("[axes]\nd = [30, 60]\nseed = [0, 1]\n")
    return folder
