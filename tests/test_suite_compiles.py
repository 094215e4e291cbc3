"""benchmarks/suite_compiles.py: its tables add the workers' counts per function and per file, costliest first."""

from __future__ import annotations

import importlib.util
from pathlib import Path

SPEC = importlib.util.spec_from_file_location(
    "suite_compiles", Path(__file__).resolve().parents[1] / "benchmarks" / "suite_compiles.py"
)
suite_compiles = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(suite_compiles)


def test_the_tables_sum_over_workers_and_files_costliest_first():
    rows = [  # [test id, function, compilations, seconds], as two workers wrote them
        ["tests/a.py::t1", "jit(run_block)", 2, 10.0],
        ["tests/b.py::t2", "jit(run_block)", 1, 4.0],
        ["tests/b.py::t3", "jit(stage)", 30, 1.5],
        ["tests/a.py::t4", "jit(run_block)", 1, 6.0],
        ["tests/a.py::t1", "jit(run_block)", 1, 2.0],
    ]
    text = suite_compiles.tables(rows, top=5)
    functions, per_file, files, again = text.split("\n\n")
    assert functions.splitlines()[2:] == ["| jit(run_block) | 5 | 22.0 | 2 |", "| jit(stage) | 30 | 1.5 | 1 |"]
    assert per_file.splitlines()[2:4] == [
        "| jit(run_block) | tests/a.py | 4 | 18.0 |",
        "| jit(run_block) | tests/b.py | 1 | 4.0 |",
    ]
    assert files.splitlines()[2:] == ["| tests/a.py | 4 | 18.0 |", "| tests/b.py | 31 | 5.5 |"]
    # one test compiling one function 3+ times (its two workers' rows added), costliest first
    assert again.splitlines()[2:] == [
        "| tests/a.py::t1 | jit(run_block) | 3 | 12.0 |",
        "| tests/b.py::t3 | jit(stage) | 30 | 1.5 |",
    ]
