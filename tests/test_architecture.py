"""The tree keeps its promises (docs/architecture.md): the core never reaches the edge, the edge is
feature packages with a small public surface, no import cycles in the whole tree (studies and
function-local imports included), small modules, tests that mirror the tree, and a method is one
module plus one registry line."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "delvjax"
STUDIES = ROOT / "studies"  # installed as delvjax.studies (pyproject.toml)
# 300 lines of the dense style before ruff format, which spreads the same code over 1.25 x the lines
MAX_LINES = 375
FEATURES = {"cli", "core", "envs", "evaluate", "familiarity", "gradients", "images", "mesh", "options", "outputs",
            "plots", "reproduce", "sweeps"}  # fmt: skip


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    parts = ["delvjax", *parts] if parts[0] == "studies" else parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path: Path) -> set[str]:
    """The delvjax modules `path` imports (absolute and relative, at any depth of the file, function-local
    ones included; not those under `if TYPE_CHECKING:`, which only annotate)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):  # imports under `if TYPE_CHECKING:` are for annotations, not run: not an edge
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            node.body = []
    for node in ast.walk(tree):
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
    """Every module of the installed package: delvjax/ and studies/ (as delvjax.studies)."""
    return {module_name(p): p for folder in (PACKAGE, STUDIES) for p in folder.rglob("*.py")}


def resolve(target: str, modules: dict[str, Path]) -> str | None:
    while target and target not in modules:
        target = target.rsplit(".", 1)[0] if "." in target else ""
    return target or None


def test_the_core_never_imports_the_edge():
    modules = all_modules()
    bad = [
        (m, t)
        for m, p in modules.items()
        if m.startswith("delvjax.core")
        for t in imports_of(p)
        if not t.startswith("delvjax.core")
    ]
    assert not bad, f"core modules importing the edge: {bad}"


def test_no_import_cycles_in_the_whole_tree():
    modules = all_modules()
    graph = {
        m: {r for t in imports_of(p) if (r := resolve(t, modules)) and r != m and not m.startswith(r + ".")}
        for m, p in modules.items()
    }
    # a package __init__ re-exporting its children is not a cycle: drop edges into a module's own parents
    state: dict[str, int] = {}
    cycle: list[str] = []

    def visit(m: str, stack: list[str]) -> bool:
        state[m] = 1
        for n in sorted(graph.get(m, ())):
            if n.startswith(m + "."):
                continue
            if state.get(n) == 1:
                cycle.extend(stack[stack.index(n) :] + [n] if n in stack else [m, n])
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
def test_no_module_above_the_line_limit(folder):
    long = {
        str(p.relative_to(ROOT)): n
        for p in (ROOT / folder).rglob("*.py")
        if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert not long, f"modules above {MAX_LINES} lines: {long}"


def test_every_registered_method_is_a_module_with_its_own_file():
    from delvjax.core.methods.base import HomingMethod
    from delvjax.options._registry import DESCRIPTIONS, METHODS

    assert set(METHODS) == set(DESCRIPTIONS)
    for name, method in METHODS.items():
        assert isinstance(method, HomingMethod), name
        source = Path(__import__(type(method).__module__, fromlist=["_"]).__file__)
        assert source.parent == PACKAGE / "core" / "methods", (name, source)


def test_nothing_under_the_core_takes_a_method_name():
    """Names live at the edge: no core module imports the registry or looks a method up by name."""
    for path in (PACKAGE / "core").rglob("*.py"):
        text = path.read_text()
        assert "get_method(" not in text and "METHODS[" not in text and 'static_argnames=("method' not in text, path


def test_the_edge_is_feature_packages():
    """No flat edge module: delvjax/ holds only its __init__ and one package per feature."""
    flat = sorted(p.name for p in PACKAGE.glob("*.py") if p.name != "__init__.py")
    packages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    assert not flat, f"flat modules at the top of delvjax/: {flat}"
    assert packages == FEATURES, packages ^ FEATURES


@pytest.mark.parametrize("feature", sorted(FEATURES - {"core"}))
def test_a_feature_keeps_its_modules_private_and_reexports_its_surface(feature):
    """Modules inside a feature package are private (`_name.py`); its __init__ re-exports the public
    names as `X as X` (the equinox and optimistix convention) and defines nothing else."""
    folder = PACKAGE / feature
    public = sorted(p.name for p in folder.glob("*.py") if not p.name.startswith("_"))
    assert not public, f"{feature}: public module files {public}"
    tree = ast.parse((folder / "__init__.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.ImportFrom):
            assert node.level == 1 and all(a.asname == a.name for a in node.names), ast.unparse(node)
        else:
            assert isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant), ast.unparse(node)


def test_nothing_imports_studies_by_its_bare_name():
    """The studies install as delvjax.studies; `import studies` would load a second copy."""
    bad = []
    for folder in ("delvjax", "studies", "tests", "benchmarks"):
        for path in (ROOT / folder).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                names = (
                    [a.name for a in node.names]
                    if isinstance(node, ast.Import)
                    else [node.module or ""]
                    if isinstance(node, ast.ImportFrom) and not node.level
                    else []
                )
                bad += [f"{path.relative_to(ROOT)}: {n}" for n in names if n.split(".")[0] == "studies"]
    assert not bad, bad


def test_tests_mirror_the_tree():
    """Every test file sits in a folder named after what it tests (a package of delvjax or studies),
    and no test file is named after an issue."""
    allowed = {"tests", "twins", "cases", *FEATURES, "methods", "rollouts", "studies", "examples"}
    for path in (ROOT / "tests").rglob("test_*.py"):
        folders = path.relative_to(ROOT).parts[:-1]
        assert set(folders) <= allowed, path
        assert (path.parent / "__init__.py").is_file(), path  # collected as a package: no sys.path edits
    issue_words = ("hardening", "outputs", "option_scope", "issue")
    assert not [p for p in (ROOT / "tests").rglob("test_*.py") if any(w in p.stem for w in issue_words)]
    assert "sys.path" not in "".join(
        p.read_text() for p in (ROOT / "tests").rglob("*.py") if p.name != Path(__file__).name
    )


def test_import_delvjax_loads_no_figures_tables_or_images():
    code = "import sys, delvjax; print(sorted(m for m in ('matplotlib', 'xarray', 'PIL') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]", out


def test_the_architecture_doc_maps_every_module():
    """Every module is in the index, but the file of a registered method: the API page lists those,
    made from the registry when the site is built (docs/_ext/generated.py), so a new method edits no page."""
    from delvjax.options import public_classes

    methods = {ROOT / (cls.__module__.replace(".", "/") + ".py") for cls in public_classes().values()}
    doc = (ROOT / "docs" / "architecture.md").read_text()
    modules = [p for folder in (PACKAGE, STUDIES) for p in folder.rglob("*.py") if p.name != "__main__.py"]
    missing = [str(p.relative_to(ROOT)) for p in modules if f"`{p.relative_to(ROOT)}`" not in doc and p not in methods]
    assert not missing, f"modules missing from docs/architecture.md's module index: {missing}"
    assert len(methods) >= 10 and all(p.is_file() for p in methods)


LATE = (
    "matplotlib",
    "xarray",
    "pandas",
    "PIL",
    "yaml",
    "markdown",
    "tqdm",
    "scipy",
    "optimistix",
    "jax.experimental",
    "importlib",
    "delvjax.plots",
    "delvjax.studies",
    "delvjax.cli._main",
)  # what may load inside a function


def test_function_local_imports_are_heavy_optional_and_say_why():
    """Imports inside functions only for heavy or optional dependencies, each with a comment why."""
    bad = []
    for path, name in ((p, module_name(p)) for p in all_modules().values()):
        lines = path.read_text().splitlines()
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for fn in ast.walk(ast.parse(path.read_text())):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if not isinstance(node, (ast.Import, ast.ImportFrom)):
                    continue
                if isinstance(node, ast.Import):
                    target = node.names[0].name
                elif node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                text = "\n".join(lines[node.lineno - 1 : node.end_lineno])
                late = any(target == t or target.startswith(t + ".") for t in LATE)
                if not late or ("#" not in text and target != "importlib"):
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno} {target}")
    assert not bad, bad
