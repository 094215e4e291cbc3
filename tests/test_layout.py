"""The tree keeps its promises: the core never reaches the edge, no import cycles, small modules,
and a method is one module plus one registry line (docs/architecture.md)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "delvjax"
MAX_LINES = 300


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path: Path) -> set[str]:
    """The delvjax modules `path` imports (absolute and relative, at any depth of the file)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("delvjax")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("delvjax"):
                found.add(target)
                found |= {f"{target}.{a.name}" for a in node.names}
    return found


def all_modules() -> dict[str, Path]:
    return {module_name(p): p for p in PACKAGE.rglob("*.py")}


def resolve(target: str, modules: dict[str, Path]) -> str | None:
    while target and target not in modules:
        target = target.rsplit(".", 1)[0] if "." in target else ""
    return target or None


def test_the_core_never_imports_the_edge():
    modules = all_modules()
    bad = [(m, t) for m, p in modules.items() if m.startswith("delvjax.core")
           for t in imports_of(p) if not t.startswith("delvjax.core")]
    assert not bad, f"core modules importing the edge: {bad}"


def test_no_import_cycles_between_modules():
    modules = all_modules()
    graph = {m: {r for t in imports_of(p) if (r := resolve(t, modules)) and r != m and not m.startswith(r + ".")}
             for m, p in modules.items()}
    # a package __init__ re-exporting its children is not a cycle: drop edges into a module's own parents
    state: dict[str, int] = {}
    cycle: list[str] = []

    def visit(m: str, stack: list[str]) -> bool:
        state[m] = 1
        for n in sorted(graph.get(m, ())):
            if n.startswith(m + "."):
                continue
            if state.get(n) == 1:
                cycle.extend(stack[stack.index(n):] + [n] if n in stack else [m, n])
                return True
            if state.get(n) is None and visit(n, stack + [n]):
                return True
        state[m] = 2
        return False

    for m in sorted(graph):
        if state.get(m) is None and visit(m, [m]):
            break
    assert not cycle, f"import cycle: {' -> '.join(cycle)}"


@pytest.mark.parametrize("folder", ["delvjax", "studies", "tests", "benchmarks"])
def test_no_module_above_300_lines(folder):
    long = {str(p.relative_to(ROOT)): n for p in (ROOT / folder).rglob("*.py")
            if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, f"modules above {MAX_LINES} lines: {long}"


def test_every_registered_method_is_a_module_with_its_own_file():
    from delvjax.core.methods.base import HomingMethod
    from delvjax.registry import DESCRIPTIONS, METHODS

    assert set(METHODS) == set(DESCRIPTIONS)
    for name, method in METHODS.items():
        assert isinstance(method, HomingMethod), name
        source = Path(__import__(type(method).__module__, fromlist=["_"]).__file__)
        assert source.parent == PACKAGE / "core" / "methods", (name, source)


def test_nothing_under_the_core_takes_a_method_name():
    """Names live at the edge: no core module imports the registry or looks a method up by name."""
    for path in (PACKAGE / "core").rglob("*.py"):
        text = path.read_text()
        assert "get_method(" not in text and "METHODS[" not in text and "static_argnames=(\"method" not in text, path
