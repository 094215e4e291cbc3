"""Issue 54's speed targets ("How good"), every ratio from one run, in one table.

Runs each benchmark behind a target once, in turn, as a subprocess with `--json PATH` (the script's own
tables print as they are), takes each ratio from that machine-readable output, and prints one table:
target, threshold, measured, met or not met, the command that re-measures it. The suite's row is not
run here (about 20 minutes): it reads the `tests` entry of benchmarks/readme_times.json (written by
`python benchmarks/readme_times.py --tests`) against 480 s, with that entry's date. Writes
benchmarks/speed_targets.json: the rows, every script's output (the raw numbers), the date, the machine
(as readme_times.json records it), the git commit and the load average before and after.
`--write-readme` rewrites the README's block between `<!-- speed_targets -->` and `<!-- /speed_targets -->`
from that file, which tests/test_speed_targets.py checks against it.

    python benchmarks/speed_targets.py [--write-readme] [--beside "what else ran"]   # about 15 minutes
    python benchmarks/speed_targets.py --smoke        # each script's --smoke (1-2 minutes), into a temporary file
    python benchmarks/speed_targets.py --from-json benchmarks/speed_targets.json --out /tmp/t.json
                                                      # the table again from saved outputs, nothing run
"""

from __future__ import annotations

import argparse
import datetime
import json
import operator
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from readme_times import README, RESULTS, ROOT, machine

OUT = ROOT / "benchmarks" / "speed_targets.json"
BLOCK = re.compile(r"(<!-- speed_targets -->)(.*?)(<!-- /speed_targets -->)", re.S)
OPS = {"<": operator.lt, "<=": operator.le, ">=": operator.ge}
SUITE_LIMIT_S = 480.0  # the README's test command, empty cache, 2 CPU cores: under 8 minutes

# each benchmark run once: (script, options of the full run, options of --smoke)
RUNS = {
    "buckets": ("bench_buckets.py", [], ["--smoke"]),
    "startup": ("bench_startup.py", ["--runs", "5"], ["--smoke"]),
    "sweep": ("bench_sweep.py", ["--versus-only", "--kinds", "vector-map", "--repeats", "1"], ["--smoke"]),
    "cores": ("bench_cores.py", ["--rounds", "1", "--reps", "3"], ["--smoke"]),
    "delv": ("bench_delv_landmarks.py", ["--landmarks", "8", "32"], ["--smoke"]),
}


def _get(*keys: str):
    """A reader of a script's output: the value at `keys`, None where the run did not measure it."""

    def read(data: dict):
        for k in keys:
            if not isinstance(data, dict) or data.get(k) is None:
                return None
            data = data[k]
        return data

    return read


# (target, run, reader of the ratio, op, threshold, unit)
TARGETS = [
    ("A second vector map of another grid size (DELV env1, 25 then 30 cm): its compile, % of the first's",
     "buckets", _get("vector_map", "pct"), "<", 10.0, "%"),
    ('`delvjax vector-map env1 --method delv`, warm compilation cache / `python -c "import jax"`, wall',
     "startup", _get("ratio_wall"), "<", 2.0, "x"),
    ("Sweep of 100 DELV vector-map cells against 100 `vector_map` calls, compile included: loop / sweep, CPU",
     "sweep", _get("versus", "vector-map delv", "first_cpu_ratio"), ">=", 1.5, "x"),
    ("The same, ALV", "sweep", _get("versus", "vector-map alv", "first_cpu_ratio"), ">=", 1.5, "x"),
    ("DELV vector map, 10 000 points: 1 core / every core (2; the command's default, 1 device), first call"
     " (compile included), wall", "cores", _get("works", "map", "first_ratio"), ">=", 1.6, "x"),
    ("The same map, warm", "cores", _get("works", "map", "warm_ratio"), ">=", 1.6, "x"),
    ("ALV catchment, 1600 rollouts: 1 core / every core (default: a device per core), first call, wall",
     "cores", _get("works", "catchment", "first_ratio"), ">=", 1.6, "x"),
    ("The same catchment, warm", "cores", _get("works", "catchment", "warm_ratio"), ">=", 1.6, "x"),
    ("DELV success rate, 9 x 100 trials: 1 core / every core (default: 1 device), first call, wall",
     "cores", _get("works", "success", "first_ratio"), ">=", 1.6, "x"),
    ("The same success rate, warm", "cores", _get("works", "success", "warm_ratio"), ">=", 1.6, "x"),
    ("Catchment sweep, 20 cells: 1 core / every core (default: a device per core), first call, wall",
     "cores", _get("works", "sweep", "first_ratio"), ">=", 1.6, "x"),
    ("The same sweep, warm", "cores", _get("works", "sweep", "warm_ratio"), ">=", 1.6, "x"),
    ("DELV without a compass: time a point at L = 32 / L = 8, CPU",
     "delv", _get("ratio_cpu"), "<=", 20.0, "x"),
]  # fmt: skip


def ratios(run: str, output: dict) -> dict[str, float | None]:
    """The values one run's output gives its targets (None: not measured at the sizes it ran)."""
    return {target: read(output) for target, r, read, *_ in TARGETS if r == run}


def met(op: str, value: float | None, threshold: float) -> bool | None:
    """Whether `value op threshold` holds (None: not measured)."""
    return None if value is None else bool(OPS[op](value, threshold))


def rows(outputs: dict, suite: dict | None) -> list[dict]:
    """The table's rows from the scripts' outputs and the `tests` entry of readme_times.json (`suite`)."""
    out = []
    for target, run, read, op, threshold, unit in TARGETS:
        script, options, _ = RUNS[run]
        value = read(outputs.get(run, {}))
        command = " ".join(["python", f"benchmarks/{script}", *options])
        out.append({"target": target, "op": op, "threshold": threshold, "unit": unit, "value": value,
                    "met": met(op, value, threshold), "command": command})  # fmt: skip
    seconds = None if suite is None else suite["seconds"]
    out.append({
        "target": "The README's test command, empty compilation cache, 2 CPU cores"
        + ("" if suite is None else f" (measured {suite.get('date', '?')})"),
        "op": "<", "threshold": SUITE_LIMIT_S, "unit": "s", "value": seconds,
        "met": met("<", seconds, SUITE_LIMIT_S), "command": "python benchmarks/readme_times.py --tests",
    })  # fmt: skip
    return out


def _number(value: float | None, unit: str) -> str:
    if value is None:
        return "not measured"
    return {"%": f"{value:.1f} %", "x": f"{value:.2f}x", "s": f"{value:.0f} s"}[unit]


def _verdict(m: bool | None) -> str:
    return "-" if m is None else "met" if m else "not met"


def table(data: dict) -> str:
    """The rows as a Markdown table (the terminal's and the README's)."""
    note = ["(--smoke: the scripts' smoke sizes, not the targets')", ""] if data.get("smoke") else []
    lines = [*note, "| target | threshold | measured | | re-measure |", "| --- | --- | --- | --- | --- |"]
    for r in data["rows"]:
        threshold = f"{r['op']} {_number(r['threshold'], r['unit'])}"
        value, verdict = _number(r["value"], r["unit"]), _verdict(r["met"])
        lines.append(f"| {r['target']} | {threshold} | {value} | {verdict} | `{r['command']}` |")
    return "\n".join(lines)


def render(data: dict) -> str:
    """The README's block: one sentence saying where and when, then the table."""
    m, hits = data["machine"], [r["met"] for r in data["rows"] if r["met"] is not None]
    beside = data.get("beside") or "nothing else noted"
    return (
        f"\nIssue 54's speed targets, {sum(hits)} of {len(hits)} met: every ratio from one run of "
        f"`python benchmarks/speed_targets.py` on {m['cores']} CPU cores ({m['cpu']}), {data['date']}, commit "
        f"{data['commit']}, load average {data['load'][0]:.1f} before and {data['load'][1]:.1f} after "
        f"(beside it: {beside}); the suite's row is benchmarks/readme_times.json's.\n\n{table(data)}\n\n"
    )


def write_readme(data: dict) -> None:
    text = README.read_text()
    if not BLOCK.search(text):
        raise SystemExit(f"{README} has no <!-- speed_targets --> block")
    README.write_text(BLOCK.sub(lambda b: b[1] + render(data) + b[3], text))


def run_all(smoke: bool, folder: Path) -> dict:
    """Each script once, in turn, with --json into `folder`; their outputs by run name."""
    outputs = {}
    for name, (script, options, smoke_options) in RUNS.items():
        path = folder / f"{name}.json"
        cmd = [sys.executable, str(ROOT / "benchmarks" / script), *(smoke_options if smoke else options)]
        print(f"\n$ {' '.join(cmd[1:])}", flush=True)
        subprocess.run([*cmd, "--json", str(path)], cwd=ROOT, check=True)
        outputs[name] = json.loads(path.read_text())
    return outputs


def commit() -> str:
    """HEAD's short hash, and whether the code measured differs from it."""
    git = ["git", "-C", str(ROOT)]
    head = subprocess.run([*git, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    code = ["--", "delvjax", "benchmarks"]  # what runs; other agents' docs and studies may be mid-edit
    dirty = subprocess.run(
        [*git, "status", "--porcelain", "--untracked-files=no", *code], capture_output=True, text=True
    )
    return head + (" with uncommitted changes to delvjax/ or benchmarks/" if dirty.stdout.strip() else "")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--smoke", action="store_true", help="each script's --smoke; writes a temporary file")
    ap.add_argument("--from-json", metavar="PATH", help="take the scripts' outputs from a saved speed_targets.json")
    ap.add_argument("--out", metavar="PATH", help=f"where to write (default {OUT.relative_to(ROOT)})")
    ap.add_argument("--beside", default="", help="what else ran on the machine, for the README's sentence")
    ap.add_argument("--write-readme", action="store_true", help="rewrite the README's block from the result")
    a = ap.parse_args()
    if a.smoke and a.write_readme:
        raise SystemExit("--smoke measures nothing worth quoting: no --write-readme")
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        saved = json.loads(Path(a.from_json).read_text()) if a.from_json else None
        outputs = saved["outputs"] if saved else run_all(a.smoke, Path(tmp))
        out = Path(a.out) if a.out else None if a.smoke else OUT  # a smoke run keeps nothing unless asked
        suite = json.loads(RESULTS.read_text())["times"].get("tests")  # today's, also --from-json
        data = {
            "date": saved["date"] if saved else datetime.date.today().isoformat(),
            "commit": saved["commit"] if saved else commit(),
            "machine": saved["machine"] if saved else machine(),
            "load": saved["load"] if saved else [load, os.getloadavg()[0]],
            "beside": a.beside or (saved or {}).get("beside", ""),
            "smoke": a.smoke or bool(saved and saved.get("smoke")),
            "rows": rows(outputs, suite),
            "outputs": outputs,
            "suite": suite,
        }
        if out:
            out.write_text(json.dumps(data, indent=1) + "\n")
    print(f"\n{table(data)}\n{f'wrote {out}' if out else 'kept nothing (--smoke)'}")
    if a.write_readme:
        write_readme(data)
        print(f"rewrote the speed_targets block of {README}")


if __name__ == "__main__":
    main()
