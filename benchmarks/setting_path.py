"""Which files a setting crosses from the command line to the core (issue 55; docs/architecture.md
"How a setting travels").

Runs one small command in process under `sys.setprofile`, collects the delvjax functions it calls
(module bodies not counted), and lists the files whose called functions read the setting by name (an
identifier, attribute, keyword or parameter `name`; docstrings and comments do not count, nor an attribute
of numpy, JAX or math such as `np.spacing`):

    python benchmarks/setting_path.py max_steps catchment env1 --max-steps 20 --spacing 200
    python benchmarks/setting_path.py levels vector-map env1 --levels 3 --spacing 200

Prints the files crossed, those that read the setting, and their counts. A check script, not a test.
"""

from __future__ import annotations

import argparse
import ast
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def functions_called(argv: list[str]) -> dict[Path, set[int]]:
    """The delvjax functions (studies excluded) that run during `delvjax <argv>`: file -> first lines."""
    from delvjax.cli._main import main

    package = str(ROOT / "delvjax")
    seen: dict[Path, set[int]] = {}

    def profile(frame, event, arg):
        if event == "call" and frame.f_code.co_name != "<module>":
            name = frame.f_code.co_filename
            if name.startswith(package):
                seen.setdefault(Path(name), set()).add(frame.f_code.co_firstlineno)

    sys.setprofile(profile)
    try:
        code = main(argv)
    finally:
        sys.setprofile(None)
    if code != 0:
        raise SystemExit(f"delvjax {' '.join(argv)} exited with {code}")
    return seen


def reads(path: Path, first_lines: set[int], name: str) -> int:
    """How often the called functions of `path` (by their first line, decorators included) name `name`:
    identifiers, attributes, keywords and parameters."""
    count = 0
    defs = [
        n
        for n in ast.walk(ast.parse(path.read_text()))
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
        and min([n.lineno, *(d.lineno for d in getattr(n, "decorator_list", []))]) in first_lines
    ]
    for node in (x for d in defs for x in ast.walk(d)):
        count += (
            (isinstance(node, ast.Name) and node.id == name)
            or (isinstance(node, ast.Attribute) and node.attr == name and not _of_a_library(node))
            or (isinstance(node, ast.keyword) and node.arg == name)
            or (isinstance(node, ast.arg) and node.arg == name)
        )
    return count


LIBRARIES = ("np", "jnp", "jax", "math")  # `np.spacing` is numpy's function, not the setting


def _of_a_library(node: ast.Attribute) -> bool:
    return isinstance(node.value, ast.Name) and node.value.id in LIBRARIES


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("setting", help="the name the code uses (max_steps, levels, ...)")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="a delvjax command line, without --out")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        called = functions_called([*args.command, "--out", str(Path(tmp) / "out.csv")])
    rows = sorted((str(p.relative_to(ROOT)), reads(p, lines, args.setting)) for p, lines in called.items())
    reading = [(f, n) for f, n in rows if n]
    print(f"{len(rows)} delvjax files run; {len(reading)} read {args.setting}:")
    for f, n in reading:
        print(f"  {f}: {n}")


if __name__ == "__main__":
    main()
