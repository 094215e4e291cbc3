"""Time `delvjax reproduce`: a cold run (empty compilation cache), a second run with nothing
changed, per-study wall and compile seconds, and peak memory (issue targets: full < 5 min,
--quick < 60 s, second run < 10 s, peak < 4 GB on 2 CPU cores).

Run: python benchmarks/bench_reproduce.py [--quick] [--out DIR] [--workers N] [--without STUDY[,STUDY]]
(--workers 1 against the default, one run after the other, shows what studies side by side save;
--without ensemble_settings measures the run without that study, as the full-run target once left
out the fit it replaced: the run is then `reproduce --only` every other study.)
Each run is a subprocess (`python -m delvjax.cli reproduce`); peak memory is the largest
resident set of those children (getrusage). This is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from delvjax.studies import FULL_RUN_ONLY, STUDIES


def run(out: Path, quick: bool, cache: str, workers: int | None = None, only: list[str] | None = None) -> float:
    cmd = [sys.executable, "-m", "delvjax.cli", "reproduce", "--out", str(out)] + (["--quick"] if quick else [])
    cmd += [] if workers is None else ["--workers", str(workers)]
    cmd += [] if only is None else ["--only", ",".join(only)]
    env = {**os.environ, "DELVJAX_CACHE_DIR": cache}
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, env=env, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", default=None, help="output folder (default: a temporary one)")
    p.add_argument("--workers", type=int, default=None, help="studies side by side (default: reproduce's)")
    p.add_argument("--without", default="", help="studies to leave out, comma-separated (e.g. ensemble_settings)")
    a = p.parse_args()
    only = None
    if a.without:
        left_out = set(a.without.split(","))
        unknown = sorted(left_out - set(STUDIES))
        if unknown:
            p.error(f"--without: unknown studies {unknown} (choose from {', '.join(STUDIES)})")
        only = [s for s in STUDIES if s not in left_out and not (a.quick and s in FULL_RUN_ONLY)]
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(a.out or Path(tmp) / "results")
        cold = run(out, a.quick, cache="", workers=a.workers, only=only)  # no persistent cache: all compiles
        again = run(out, a.quick, cache="", workers=a.workers, only=only)
        peak_gb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024**2
        print(
            f"reproduce{' --quick' if a.quick else ''}{' without ' + a.without if a.without else ''} "
            f"(workers {a.workers or 'default'}): cold {cold:.1f} s, second run {again:.1f} s, "
            f"peak RSS {peak_gb:.2f} GB"
        )
        print(f"{'study':16s} {'wall s':>8s} {'compile s':>10s}")
        for f in sorted(out.glob("*/study.json")):
            d = json.loads(f.read_text())
            print(f"{d['name']:16s} {d['seconds']:8.1f} {d['compile_seconds']:10.1f}")


if __name__ == "__main__":
    main()
