"""Run a measurement in a fresh Python process (its own peak memory, device flags, compile cache)."""

from __future__ import annotations

import json
import os
import subprocess
import sys


def run_child(code: str, *args, **env: str) -> dict:
    """`python -c code args...` with extra environment variables; the JSON object of its last line."""
    out = subprocess.run(
        [sys.executable, "-c", code, *map(str, args)], env={**os.environ, **env}, capture_output=True, text=True
    )
    if out.returncode != 0:
        raise SystemExit(out.stderr[-3000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def save_json(path: str | None, data: dict) -> None:
    """Write a script's ratio(s) and the raw numbers behind them to `path` (its `--json PATH`; None: nothing),
    for benchmarks/speed_targets.py."""
    if path:
        with open(path, "w") as f:
            json.dump(data, f, indent=1)
            f.write("\n")
