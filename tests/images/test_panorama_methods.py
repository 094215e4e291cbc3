"""MinWarping, 2D-Warping and the hybrid through the CLI and the database API (tests/cases/panorama_methods.py,
tests/cases/hybrid_methods.py), run in a pytest process of their own: three CI runs lost a worker to an
XLA abort in an unrelated compile after these had run in it (docs/model.md §4.7), so they no longer
share a process with the rest of the suite."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("cases", ["panorama_methods.py", "hybrid_methods.py"])
def test_in_a_process_of_their_own(cases):
    argv = [sys.executable, "-m", "pytest", "-n", "0", "-p", "no:cacheprovider", f"tests/cases/{cases}"]
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-3000:]
