"""Where the test suite's time goes: XLA compilation per compiled function and per test file.

The suite is compile-bound (issue: the suite in under 5 minutes on 2 cores; docs/reproduce.md
"Where the targets stand"), so the question that decides what to change is which programs it
compiles, how often and in which files. This script runs the README's test command (or the test
paths given) with an empty compilation cache and itself as a pytest plugin, which listens to JAX's
`/jax/core/compile/backend_compile_duration` events (one per backend compilation, with the jitted
function's name), and prints

  * the suite's wall seconds, the number of compilations and their seconds (summed over workers);
  * the functions that cost most compile seconds: count, seconds, in how many files;
  * for the top functions, the files that compile them;
  * the files that cost most compile seconds;
  * the tests that compile one function again and again (3 times or more): the sign of a Python number
    passed where a traced one would do (each value its own program), the waste this table found first
    (tests/core/methods/test_minwarping.py's fine-search test: 35 s -> under 1 s, 2026-12-05).

    python benchmarks/suite_compiles.py                       # the whole suite (about 20 minutes on 2 cores)
    python benchmarks/suite_compiles.py tests/core -n 0       # a part, one process
    python benchmarks/suite_compiles.py --top 30 --json out.json

Arguments it does not know go to pytest. The numbers are compile seconds as each worker measured them:
two workers compiling at once on 2 cores each take longer than one alone.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import jax

ROOT = Path(__file__).resolve().parents[1]
EVENT = "/jax/core/compile/backend_compile_duration"
_OUT = "SUITE_COMPILES_OUT"  # the folder each worker writes its counts into (set by `main` for the plugin)


# --- the pytest plugin (loaded in each worker with `-p suite_compiles`) ------------------------------
_current = {"test": "(collection)"}
_counts: dict[tuple[str, str], list] = {}


def _listen() -> None:
    def on_duration(event: str, duration: float, **kwargs) -> None:
        if event == EVENT:
            entry = _counts.setdefault((_current["test"], kwargs.get("fun_name", "?")), [0, 0.0])
            entry[0] += 1
            entry[1] += duration

    jax.monitoring.register_event_duration_secs_listener(on_duration)


def pytest_configure(config) -> None:
    if os.environ.get(_OUT):
        _listen()


def pytest_runtest_setup(item) -> None:
    _current["test"] = item.nodeid


def pytest_sessionfinish(session) -> None:
    folder = os.environ.get(_OUT)
    if folder:
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        rows = [[f, name, n, s] for (f, name), (n, s) in _counts.items()]
        (Path(folder) / f"{worker}.json").write_text(json.dumps(rows))


# --- the command ------------------------------------------------------------------------------------
def tables(rows: list, top: int, repeats: int = 3) -> str:
    """The report of `rows` ([test id, function, count, seconds] over every worker) as Markdown tables."""
    pairs = collections.defaultdict(lambda: [0, 0.0])  # (function, file) -> [count, seconds]
    per_test = collections.defaultdict(lambda: [0, 0.0])  # (test, function) -> [count, seconds]
    for test, name, n, s in rows:
        for table, key in ((pairs, (name, test.split("::")[0])), (per_test, (test, name))):
            table[key][0] += n
            table[key][1] += s

    def total(key: int) -> dict:  # function (key 0) or file (key 1) -> [count, seconds, files]
        out = collections.defaultdict(lambda: [0, 0.0, 0])
        for pair, (n, s) in pairs.items():
            out[pair[key]][0] += n
            out[pair[key]][1] += s
            out[pair[key]][2] += 1
        return dict(sorted(out.items(), key=lambda kv: -kv[1][1])[:top])

    funs = total(0)
    lines = ["| function | compilations | seconds | files |", "|---|---|---|---|"]
    lines += [f"| {name} | {n} | {s:.1f} | {k} |" for name, (n, s, k) in funs.items()]
    lines += ["", "| function | file | compilations | seconds |", "|---|---|---|---|"]
    for name in list(funs)[: max(1, top // 3)]:
        per = sorted(((f, n, s) for (fn, f), (n, s) in pairs.items() if fn == name), key=lambda r: -r[2])[:5]
        lines += [f"| {name} | {f} | {n} | {s:.1f} |" for f, n, s in per]
    lines += ["", "| file | compilations | seconds |", "|---|---|---|"]
    lines += [f"| {f} | {n} | {s:.1f} |" for f, (n, s, _) in total(1).items()]
    again = sorted(((t, fn, n, s) for (t, fn), (n, s) in per_test.items() if n >= repeats), key=lambda r: -r[3])
    lines += ["", f"| test compiling one function {repeats}+ times | function | compilations | seconds |"]
    lines += ["|---|---|---|---|"] + [f"| {t} | {fn} | {n} | {s:.1f} |" for t, fn, n, s in again[:top]]
    return "\n".join(lines)


def positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, not {text}")
    return value


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=positive_int, default=20, help="rows per table (default 20)")
    parser.add_argument("--json", type=Path, help="also write every [test id, function, count, seconds] row here")
    args, pytest_args = parser.parse_known_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(
            os.environ,
            DELVJAX_CACHE_DIR=str(Path(tmp) / "cache"),  # empty: every program compiles, as in CI
            PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT / "benchmarks"), os.environ.get("PYTHONPATH")])),
            **{_OUT: tmp},
        )
        t0 = time.perf_counter()
        rc = subprocess.run([sys.executable, "-m", "pytest", "-p", "suite_compiles", *pytest_args], cwd=ROOT, env=env)
        wall = time.perf_counter() - t0
        rows = [row for part in sorted(Path(tmp).glob("*.json")) for row in json.loads(part.read_text())]
    n, seconds = sum(r[2] for r in rows), sum(r[3] for r in rows)
    print(f"\npytest: exit {rc.returncode}, {wall:.0f} s wall; {n} compilations, {seconds:.0f} s of XLA compilation")
    print(tables(rows, args.top))
    if args.json:
        args.json.write_text(json.dumps(rows, indent=0))
    return rc.returncode


if __name__ == "__main__":
    sys.exit(main())
