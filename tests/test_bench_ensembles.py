"""benchmarks/bench_ensembles.py runs (a smoke size: one member, a 5 x 5 grid; no timing is asserted)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_the_ensemble_benchmark_runs_at_a_smoke_size():
    out = subprocess.run(
        [sys.executable, "benchmarks/bench_ensembles.py", "--members", "1", "--spacing", "200", "--families", "env1"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert "9 cells" in out.stdout and "rollouts/s" in out.stdout and "cold (compilation included)" in out.stdout
