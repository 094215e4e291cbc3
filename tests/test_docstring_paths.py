"""Docstrings and comments name today's modules (issue 55): every module path (`core/maps.py`,
`sweeps/_kinds.py`, `_load.py`) and every dotted module name (`core.maps`, `delvjax.core.maps`,
`options._registry`, `maps.vector_map`) a docstring or comment in delvjax/, studies/, tests/, benchmarks/ or
examples/ names exists: a module file or package, and in `module.name` forms a name the module binds (a
function, class, constant, re-export or submodule). Read statically (ast and tokenize): nothing is imported."""

from __future__ import annotations

import ast
import functools
import importlib
import io
import re
import sys
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = ("delvjax", "studies", "tests", "benchmarks", "examples")
FILES = sorted(p for folder in FOLDERS for p in (ROOT / folder).rglob("*.py") if p != Path(__file__).resolve())
# a path ending in .py, not inside a longer path or URL (`https://.../x.py` starts after a `/`)
PATH = re.compile(r"(?<![\w./-])((?:[A-Za-z_][\w-]*/)*[A-Za-z_]\w*\.py)(?!\w)")
# a package folder (`core/images/`, `delvjax/sweeps/`): checked where its first part is a package or a
# folder of the repository (`out/`, an output folder, is not)
FOLDER = re.compile(r"(?<![\w./-])((?:[A-Za-z_][\w-]*/)+)(?![\w.-])")
# a dotted name, not inside a longer one, a path or a quoted string ("sensor.noise.bearing" is a setting)
DOTTED = re.compile(r"(?<![\w./\"'])([A-Za-z_]\w*(?:\.[A-Za-z_]\w*)+)(?!\w)")
# a bare name in backticks: checked where it is a module name of the layouts before (`cli_rollouts`)
BARE = re.compile(r"`([A-Za-z_]\w*)`")
# file names (`docs/images.md`, `images.md §6`), not modules and attributes
SUFFIXES = {"md", "py", "csv", "json", "toml", "nc", "png", "pdf", "txt", "yaml", "yml", "npz", "svg", "html", "cff"}
# where a path is looked up besides the naming file's own folder and the folders above it
BASES = ("", "delvjax", "delvjax/core", "studies", "studies/runs", "tests", "benchmarks")
# where a dotted name's first part is looked up when it is not `delvjax` or `studies`: any module or
# package of the tree named so (`maps` is core/maps.py, `_common` any of the three); a first part that
# names no module (`np`, `db`, `self`) is not a module name and is not checked
MODULES = [p.parent if p.name == "__init__.py" else p for p in FILES]
TOP_FOLDERS = {p.parent.name for p in FILES if p.name == "__init__.py"} | {p.name for p in ROOT.iterdir() if p.is_dir()}
# module names of the layouts before today's (`git log --diff-filter=DR -- delvjax studies`): a dotted name
# starting with one (`registry.program`, `api.vector_map`, `presets.random_env`) names nothing any more
FORMER = frozenset(
    """_fit_causes _fit_cells _fit_design _fit_model _fit_tables _gap_causes _quality _tables api api_image_eval
    api_images api_rollouts api_soft cache catchment_tables cell_store claims_ch4 claims_ch4_more claims_ch5
    claims_ch5_occlusion claims_common cli_args cli_gradients cli_images cli_rollouts cli_sweep common compass
    config fit fit_causes fit_cells fit_model gap_matching homing image_db image_worlds images_common io layout
    limits navipy_frames occlusion_layouts plots_images plots_rollouts plots_sweep presets quality registry report
    sensitivities study sweep_examples sweep_kinds sweep_results sweep_spec thesis_claims_ch4 thesis_claims_ch5
    thesis_notes thesis_numbers vector_maps""".split()
)
# (file, name) -> why it is left: names that look like modules but are not
ALLOWED = {
    ("studies/runs/_common.py", "config.trials"): "a study's RunConfig (`ctx.config`), not a module",
    ("benchmarks/ab_vector_map.py", "delvjax.config.Config"): "the API of old revisions this A/B script also runs",
    ("tests/examples/test_examples.py", "examples/NAME.py"): "a placeholder",
    ("tests/test_api_reference.py", "delvjax.NAME"): "a placeholder",
    ("tests/test_architecture.py", "_name.py"): "a placeholder",
    ("tests/images/test_navipy.py", "navipy/sensors/renderer.py"): "a file of the navipy repository",
}


def texts(path: Path):
    """(line, text) of every docstring and comment of a file."""
    source = path.read_text()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc is not None:
                yield node.body[0].lineno, doc
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type == tokenize.COMMENT:
            yield token.start[0], token.string


@functools.cache
def bindings(path: Path) -> frozenset[str]:
    """The names a module binds at its top level (under `if`/`try` too): functions, classes, assigned
    names, imports, and the names listed in `__all__` or in delvjax/__init__.py's lazy tables."""
    names: set[str] = set()

    def visit(body):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names.add(node.name)
            elif isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                names.update(e.id for t in targets for e in ast.walk(t) if isinstance(e, ast.Name))
                if {"__all__", "_LAZY", "_RENAMED", "_PACKAGES"} & {getattr(t, "id", "") for t in targets}:
                    strings = [e for e in ast.walk(node.value) if isinstance(e, ast.Constant)]
                    names.update(e.value for e in strings if isinstance(e.value, str))
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names.update((a.asname or a.name).split(".")[0] for a in node.names)
            elif isinstance(node, (ast.If, ast.Try, ast.With)):
                visit(node.body)
                visit(getattr(node, "orelse", []))
                visit(getattr(node, "finalbody", []))
                for handler in getattr(node, "handlers", []):
                    visit(handler.body)

    visit(ast.parse(path.read_text()).body)
    return frozenset(names)


def found(node: Path, rest: list[str]) -> bool:
    """Whether `rest` (dotted parts) names something from `node`, a package folder or a module file:
    a submodule, or a name the module binds (only the first attribute is checked: `Class.method` is
    not followed)."""
    if not rest:
        return True
    if node.is_dir():
        child = [c for c in (node / f"{rest[0]}.py", node / rest[0]) if c.is_file() or (c / "__init__.py").exists()]
        if child:
            return found(child[0], rest[1:])
        node = node / "__init__.py"
    return rest[0] in bindings(node)


def dotted_exists(name: str, text: str) -> bool | None:
    """Whether a dotted name exists; None where it is no module name: a file name, `np.asarray`, a name of
    the standard library (`io.StringIO`), or an object an example in `text` assigns (`report = ...`)."""
    parts = name.split(".")
    if parts[-1] in SUFFIXES or re.search(rf"(?<![\w.]){parts[0]} = ", text):
        return None
    if parts[0] in sys.stdlib_module_names and hasattr(importlib.import_module(parts[0]), parts[1]):
        return None
    if parts[0] in FORMER:
        return False
    if parts[:2] == ["delvjax", "studies"]:
        starts, rest = [ROOT / "studies"], parts[2:]
    elif parts[0] in ("delvjax", "studies"):
        starts, rest = [ROOT / parts[0]], parts[1:]
    else:
        starts, rest = [m for m in MODULES if m.stem == parts[0]], parts[1:]
        if not starts:
            return None
    return any(found(start, rest) for start in starts)


def path_exists(name: str, where: Path) -> bool | None:
    """Whether a path names a file (a folder, where it ends in `/`) from the naming file's folder, a folder
    above it, or one of BASES; None for a folder that starts with no package or folder of the repository."""
    if name.endswith("/") and name.split("/")[0] not in TOP_FOLDERS:
        return None
    folders = [*where.parents[: len(where.relative_to(ROOT).parts)], *(ROOT / b for b in BASES)]
    return any((folder / name).is_dir() if name.endswith("/") else (folder / name).is_file() for folder in folders)


def stale_names() -> list[tuple[str, int, str]]:
    """(file, line, name) of every module path or dotted module name that names nothing."""
    stale = []
    for path in FILES:
        for line, text in texts(path):
            names = [(m, path_exists(m, path)) for m in PATH.findall(text) + FOLDER.findall(text)]
            names += [(m, dotted_exists(m, text)) for m in DOTTED.findall(text)]
            names += [(m, False) for m in BARE.findall(text) if m in FORMER]
            stale += [(str(path.relative_to(ROOT)), line, m) for m, ok in names if ok is False]
    return stale


def test_the_patterns_find_module_names_and_pass_over_the_rest():
    # would catch: a pattern that misses a form the issue names, or flags a file name, URL or object
    here = ROOT / "delvjax" / "images" / "_load.py"
    text = '`core/maps.py`, `_disk.py`, see https://x.org/a/b.py, `sweeps/_kinds.py` and "sensor.noise.bearing"'
    assert PATH.findall(text) == ["core/maps.py", "_disk.py", "sweeps/_kinds.py"]
    assert DOTTED.findall('`core.maps`, docs/images.md, "noise.bearing", `np.asarray`') == ["core.maps", "np.asarray"]
    assert FOLDER.findall("`core/images/`, out/, `core/maps.py`, https://x.org/a/") == ["core/images/", "out/"]
    paths = ("core/maps.py", "_disk.py", "core/images/", "core/mapz.py", "images.py", "delvjax/methods/", "out/")
    assert [path_exists(p, here) for p in paths] == [True, True, True, False, False, False, None]
    exists = {
        "delvjax.core.maps.vector_map": True,
        "core.maps": True,
        "maps.vector_map": True,
        "options._registry.method_set": True,
        "delvjax.studies.runs._common.vector_map": True,
        "delvjax.vector_map": True,  # delvjax/__init__.py's lazy table
        "delvjax.core.maps.nothing_here": False,
        "core.mapz": False,
        "registry.program": False,  # a module of the layout before
        "images.md": None,
        "np.asarray": None,
        "io.StringIO": None,
    }
    assert {name: dotted_exists(name, "") for name in exists} == exists
    assert dotted_exists("report.points", "report = delvjax.find_traps()") is None  # an example's object
    assert [m for m in BARE.findall("`cli_rollouts`, `registry.program`, `levels`") if m in FORMER] == ["cli_rollouts"]


def test_docstrings_and_comments_name_modules_that_exist():
    # would catch: the 24 stale names in delvjax/ this test came with (`registry.program`, `io.atomic_path`,
    # `api.vector_map`, `presets.random_env`, `reproduce.py`, ...), and any module renamed without its mentions
    found_now = stale_names()
    stale = [s for s in found_now if (s[0], s[2]) not in ALLOWED]
    left = {(f, name) for f, _, name in found_now}
    assert set(ALLOWED) <= left, f"allowed but no longer found (drop them): {set(ALLOWED) - left}"
    assert not stale, "docstrings or comments naming no module (file, line, name):\n" + "\n".join(map(str, stale))


if __name__ == "__main__":
    for s in stale_names():
        print(*s)
