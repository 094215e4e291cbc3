"""Benchmark: start-up of the command line against `python -c "import jax"` (issue 54).

    python benchmarks/bench_startup.py [--runs 7] [--method delv] [--spacing 25] [--smoke]

Times, as whole processes run in turn (A, B, C, A, B, C, ...: a loaded machine slows each alike),
`python -c "import jax"`, `delvjax --help` and a warm-cache `delvjax vector-map env1 --method delv
--out FILE` (`python -m delvjax.cli`), after one cold run of the vector map into a fresh compilation
cache (DELVJAX_CACHE_DIR, a temporary folder), with Python's bytecode kept (PYTHONPYCACHEPREFIX in
that folder; --no-bytecode: as the environment says). Prints the median wall and CPU seconds (user + system,
of the child) of each, and the ratio the issue asks for: warm vector map / import jax, target < 2x.
To measure another checkout, run this file with PYTHONPATH pointing there (the children inherit it and
run in the temporary folder, so the working folder's delvjax is not the one imported).
--smoke: one run of each on a 200 cm grid: that it runs, not how fast (tests/test_benchmarks_smoke.py).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from child import save_json

TARGET = 2.0  # warm vector map / import jax (issue 54)


def timed(cmd: list[str], env: dict, cwd: str) -> tuple[float, float]:
    """(wall s, CPU s of the child: user + system) of one process run in `cwd`; exits on a failure."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=cwd)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}\n{out.stderr[-3000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def commands(out: Path, method: str, spacing: float) -> dict[str, list[str]]:
    cli = [sys.executable, "-m", "delvjax.cli"]
    return {
        "import jax": [sys.executable, "-c", "import jax"],
        "delvjax --help": [*cli, "--help"],
        f"vector-map {method} (warm)": [
            *cli, "vector-map", "env1", "--method", method, "--spacing", f"{spacing:g}", "--out", str(out / "vm.csv")
        ],
    }  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=7, help="runs of each command (default 7)")
    ap.add_argument("--method", default="delv")
    ap.add_argument("--spacing", type=float, default=25.0, help="grid spacing, cm (default 25: 1600 cells)")
    ap.add_argument("--smoke", action="store_true", help="one run of each on a 200 cm grid: that it runs")
    ap.add_argument(
        "--no-bytecode",
        action="store_true",
        help="keep PYTHONDONTWRITEBYTECODE as set (default: every child may keep bytecode, as an installed "
        "package has; delvjax's 128 modules compiled from source cost about 0.1 s a run)",
    )
    ap.add_argument("--json", metavar="PATH", help="also write the ratio(s) and raw numbers here (speed_targets.py)")
    a = ap.parse_args()
    runs, spacing = (1, 200.0) if a.smoke else (a.runs, a.spacing)
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "DELVJAX_CACHE_DIR": str(Path(tmp) / "cache")}
        if not a.no_bytecode:  # as installed: Python's bytecode kept (here in the temporary folder), for all alike
            env.pop("PYTHONDONTWRITEBYTECODE", None)
            env["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "pycache")
        cmds = commands(Path(tmp), a.method, spacing)
        vm = list(cmds)[-1]
        cold = timed(cmds[vm], env, tmp)  # fills the compilation cache
        times: dict[str, list[tuple[float, float]]] = {name: [] for name in cmds}
        for _ in range(runs):  # interleaved
            for name, cmd in cmds.items():
                times[name].append(timed(cmd, env, tmp))
    print(
        f"start-up, {runs} run(s) each, interleaved; medians (python {sys.version.split()[0]}, {os.cpu_count()} CPUs)"
    )
    print(f"{'command':28s} {'wall s':>8} {'CPU s':>8}")
    print(f"{vm.replace('warm', 'cold'):28s} {cold[0]:8.2f} {cold[1]:8.2f}")
    wall = {n: statistics.median(w for w, _ in t) for n, t in times.items()}
    cpu = {n: statistics.median(c for _, c in t) for n, t in times.items()}
    for name in cmds:
        print(f"{name:28s} {wall[name]:8.2f} {cpu[name]:8.2f}")
    ratio, ratio_cpu = wall[vm] / wall["import jax"], cpu[vm] / cpu["import jax"]
    verdict = "met" if ratio < TARGET else "missed"
    save_json(a.json, {
        "runs": runs, "method": a.method, "spacing": spacing, "cold": {"wall": cold[0], "cpu": cold[1]},
        "wall": wall, "cpu": cpu, "vector_map": vm, "ratio_wall": ratio, "ratio_cpu": ratio_cpu,
    })  # fmt: skip
    print(
        f"warm vector map / import jax: {ratio:.2f}x wall, {ratio_cpu:.2f}x CPU (target < {TARGET:g}x wall: {verdict})"
    )


if __name__ == "__main__":
    main()
