"""The README's time and memory claims, measured (issue: honest numbers). Runs, each in a fresh process:

  help          `delvjax --help`, median of 3 (start-up: nothing heavy is imported)
  quick_first   `delvjax reproduce --quick` with an empty compilation cache (a first run after install)
  quick_cached  the same again with --force and the cache it left (every study recomputed, no compiling)
  tests         the README's test command, `python -m pytest`, with an empty compilation cache (--tests;
                without tests/test_readme_times.py, which checks this script's own output)

wall seconds and peak resident memory (of the process and the children it waited for), with the
machine (CPU model, cores, memory), the date and the versions, into benchmarks/readme_times.json;
`--write-readme` then rewrites the README's generated sentences (between `<!-- readme_times: KEY -->`
and `<!-- /readme_times -->`), which tests/test_readme_times.py checks against the JSON: the README
states no time of these commands that this script has not produced.

    python benchmarks/readme_times.py [--tests] [--write-readme]
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "readme_times.json"
README = ROOT / "README.md"
BLOCK = re.compile(r"<!-- readme_times: (\w+) -->(.*?)<!-- /readme_times -->", re.S)


def measure(command: list[str], env: dict | None = None, cwd: Path = ROOT) -> dict:
    """Wall seconds and peak RSS (MB) of one run of `command` (which must succeed)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(command, cwd=cwd, env={**os.environ, **(env or {})}, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    seconds = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"{' '.join(command)} failed (exit {os.waitstatus_to_exitcode(status)})")
    return {"seconds": round(seconds, 1), "peak_mb": round(usage.ru_maxrss / 1024)}


def machine() -> dict:
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "")
    memory = next((int(line.split()[1]) for line in open("/proc/meminfo") if line.startswith("MemTotal")), 0)
    from importlib.metadata import version

    return {
        "cpu": cpu or platform.processor(),
        "cores": os.cpu_count(),
        "memory_gb": round(memory / 2**20),
        "python": platform.python_version(),
        "jax": version("jax"),
        "delvjax": version("delvjax"),
        "date": datetime.date.today().isoformat(),
    }


def render(key: str, data: dict) -> str:
    """The README's sentence for `key`, from the measured numbers only."""
    m, t = data["machine"], data["times"]

    def where(entry: dict) -> str:  # each time with the date it was measured (a run without --tests keeps the tests')
        return f"{m['cores']} CPU cores ({m['cpu']}), {entry.get('date', m['date'])}"

    if key == "quick":
        first, cached, help_ = t["quick_first"], t["quick_cached"], t["help"]
        return (
            f"{first['seconds']:.0f} s on a first run with an empty compilation cache, {cached['seconds']:.0f} s "
            f"with the cache warm (peak memory {first['peak_mb'] / 1024:.1f} GB); `delvjax --help` answers in "
            f"{help_['seconds']:.1f} s; measured by `python benchmarks/readme_times.py` on {where(first)}"
        )
    if key == "tests":
        tests = t["tests"]
        return (
            f"{tests['seconds'] / 60:.0f} minutes ({tests['seconds']:.0f} s with an empty compilation cache, peak "
            f"memory {tests['peak_mb'] / 1024:.1f} GB), measured by `python benchmarks/readme_times.py --tests` "
            f"on {where(tests)}"
        )
    raise KeyError(key)


def write_readme(data: dict) -> None:
    text = README.read_text()
    new = BLOCK.sub(lambda m: f"<!-- readme_times: {m[1]} -->{render(m[1], data)}<!-- /readme_times -->", text)
    README.write_text(new)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tests", action="store_true", help="also time the test command (about 10 minutes)")
    ap.add_argument("--write-readme", action="store_true", help="rewrite the README's generated sentences")
    args = ap.parse_args()
    data = json.loads(RESULTS.read_text()) if RESULTS.is_file() else {"times": {}}
    times = data["times"]
    delvjax = [str(Path(sys.executable).parent / "delvjax")]  # the console script the README runs
    times["help"] = {
        "seconds": round(statistics.median(measure([*delvjax, "--help"])["seconds"] for _ in range(3)), 1),
        "peak_mb": measure([*delvjax, "--help"])["peak_mb"],
    }
    with tempfile.TemporaryDirectory() as tmp:
        cache = {"DELVJAX_CACHE_DIR": str(Path(tmp) / "cache")}
        out = str(Path(tmp) / "results")
        today = datetime.date.today().isoformat()
        times["quick_first"] = {**measure([*delvjax, "reproduce", "--quick", "--out", out], cache), "date": today}
        times["quick_cached"] = {
            **measure([*delvjax, "reproduce", "--quick", "--force", "--out", out], cache),
            "date": today,
        }
        if args.tests:
            own = "--ignore=tests/test_readme_times.py"  # it reads the file this run writes
            times["tests"] = {
                **measure([sys.executable, "-m", "pytest", own], {"DELVJAX_CACHE_DIR": str(Path(tmp) / "c2")}),
                "date": today,
            }
    data["machine"] = machine()
    RESULTS.write_text(json.dumps(data, indent=1) + "\n")
    print(f"{'what':14s} {'seconds':>8s} {'peak MB':>8s}")
    for name, row in times.items():
        print(f"{name:14s} {row['seconds']:8.1f} {row['peak_mb']:8d}")
    print(json.dumps(data["machine"]))
    if args.write_readme:
        write_readme(data)
        print(f"rewrote the generated sentences of {README}")


if __name__ == "__main__":
    main()
