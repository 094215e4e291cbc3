"""Sweep kinds as a package (issue 55 point 3): the modules of delvjax/sweeps import each other without a cycle
(type-only imports counted), each kind is one class registered in `KINDS`, and each cell of a sweep is validated
once (its API's request called once per cell, where before a cell of a shared program was validated twice and a
per-point sweep validated every cell again for its chunks)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import delvjax.evaluate._rollouts as api_rollouts
import delvjax.evaluate._vector_map as api
from delvjax.core.errors import InputError
from delvjax.sweeps import parse_sweep, point_errors, run_sweep

SWEEPS = Path(__file__).resolve().parents[2] / "delvjax" / "sweeps"


def module_of(path: Path) -> str:
    parts = ["delvjax", *path.relative_to(SWEEPS.parent).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def sweep_imports() -> dict[str, set[str]]:
    """module -> the delvjax.sweeps modules it imports anywhere (`if TYPE_CHECKING:` and functions too), an
    `__init__` re-exporting its own children aside (not a cycle)."""
    modules = {module_of(p): p for p in SWEEPS.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
                target = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module
                for alias in node.names:
                    found.add(f"{target}.{alias.name}" if f"{target}.{alias.name}" in modules else target)
            elif isinstance(node, ast.Import):
                found |= {a.name for a in node.names}
        graph[name] = {m for m in found if m in modules and m != name and not m.startswith(name + ".")}
    return graph


def test_the_sweep_modules_import_each_other_without_a_cycle():
    """Fails on the old code: `_kind` imported `_kinds`, which imported `_kind` for its types (and `_results` ->
    `_spec` -> `_kind` -> `_results`)."""
    graph = sweep_imports()
    assert "delvjax.sweeps._kinds.base" in graph and len(graph) >= 12
    done: set[str] = set()

    def visit(m: str, stack: tuple[str, ...]) -> None:
        assert m not in stack, f"import cycle: {' -> '.join(stack[stack.index(m) :] + (m,))}"
        if m not in done:
            for n in sorted(graph[m]):
                visit(n, stack + (m,))
            done.add(m)

    for m in sorted(graph):
        visit(m, ())


def test_each_kind_is_one_class_in_the_registry():
    """`KINDS` holds one instance of each kind's class, equal to its name, in a module of its own."""
    from delvjax.sweeps._kinds import KINDS, SweepKind

    modules = {type(k).__module__ for k in KINDS.values()}
    assert sorted(KINDS) == ["catchment", "route-following", "success-rate", "vector-map"] and len(modules) == 4
    for name, kind in KINDS.items():
        assert isinstance(kind, SweepKind) and kind == name and type(kind).name == name
        assert type(kind).__module__ == f"delvjax.sweeps._kinds.{name.replace('-', '_')}"


def counting(monkeypatch, module, name: str) -> list:
    calls: list = []
    real = getattr(module, name)
    monkeypatch.setattr(module, name, lambda *a, **k: calls.append(k.get("method")) or real(*a, **k))
    return calls


SHARED = "[axes]\nmethod = ['delv', 'alv']\nspacing = [200]\n"  # two landmark methods: one shared MethodSet


def test_a_sweep_validates_each_cell_once(monkeypatch):
    """Two cells of a vector-map sweep whose landmark methods share one program, run and then as per-point
    errors: `map_request` is called once per cell each time. Fails on the old code: 4 calls for the run (the
    method alone, then as the MethodSet) and 20 for the per-point errors (`_plan`, then again for each row of the
    chunks, padding included)."""
    spec = parse_sweep(SHARED)
    calls = counting(monkeypatch, api, "map_request")
    run_sweep(spec)
    assert calls == ["delv", "alv"]
    calls.clear()
    point_errors(spec)
    assert calls == ["delv", "alv"]


def test_a_rollout_sweep_validates_each_cell_once(monkeypatch):
    text = '[sweep]\nkind = "success-rate"\ndistances = [50]\ntrials = 2\n' + SHARED.replace("spacing = [200]\n", "")
    calls = counting(monkeypatch, api_rollouts, "rollout_request")
    run_sweep(parse_sweep(text), lanes=4)
    assert calls == ["delv", "alv"]


@pytest.mark.parametrize("axis", ["levels = [2]", "channel = ['mask']"])
def test_in_a_shared_program_another_methods_setting_stays_an_error(axis):
    """Validated once as a `MethodSet` of delv and alv, a setting (or the image channel) that alv does not read is
    still refused for alv's cells, naming the setting."""
    from delvjax.sweeps._kinds import cell_setup
    from delvjax.sweeps._run import _envs

    spec = parse_sweep(SHARED + axis + "\n")
    envs = _envs(spec)
    cells = list(spec.cells())
    with pytest.raises(InputError) as exc:
        cell_setup(spec, envs, next(c for c in cells if c["method"] == "alv"), 10_000)
    assert exc.value.expected.startswith(axis.split(" ")[0] + ": is")
    if axis.startswith("levels"):
        cell_setup(spec, envs, next(c for c in cells if c["method"] == "delv"), 10_000)
