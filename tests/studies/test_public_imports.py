"""The studies use delvjax as a user would: they import an edge package's names from the package
(`delvjax.plots`, `delvjax.envs`, ...), not from its private modules (`delvjax.plots._maps`; issue 55
point 5: 92 such import lines before, 25 after), except the names in ALLOWED, each with the reason it
stays private."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EDGE = sorted(p.parent.name for p in (ROOT / "delvjax").glob("*/__init__.py") if p.parent.name != "core")

SETTINGS = "run settings become objects (issue 55 point 1); their public home comes with them"
KINDS = "a sweep's cells set up and run by hand (the settings study): the sweep kinds' internals, not a user's call"
IMAGES = "a renderer or database detail, not a user's call; images' surface is its own part of issue 55"
ALLOWED = {
    ("delvjax.cli._main", "main"): "the in-process command line; delvjax.cli.main sets up devices for a process",
    ("delvjax.envs._ensembles", "angular_gaps_deg"): "takes the array module `xp`: a twin's helper, not an API",
    ("delvjax.envs._presets", "preset_dict"): "the raw dict of a preset (no docstring); env_to_dict is public",
    ("delvjax.evaluate._vector_map", "map_request"): SETTINGS,
    ("delvjax.evaluate._vector_map", "resolve_headings"): SETTINGS,
    ("delvjax.images._disk", "file_columns"): IMAGES,
    ("delvjax.images._evaluate", "catchment_numbers"): IMAGES,
    ("delvjax.images._evaluate", "perceived"): IMAGES,
    ("delvjax.images._load", "with_channel"): IMAGES,
    ("delvjax.images._render", "camera"): IMAGES,
    ("delvjax.images._render", "render_rings"): IMAGES,
    ("delvjax.images._worlds", "ImageWorld"): IMAGES,
    ("delvjax.images._worlds", "robot_arena"): IMAGES,
    ("delvjax.sweeps._kinds", "cell_setup"): KINDS,
    ("delvjax.sweeps._kinds", "evaluate"): KINDS,
    ("delvjax.sweeps._kinds", "catchment_metrics"): KINDS,
}


def private_imports() -> dict[tuple[str, str], list[str]]:
    """(private module, name) -> the study files importing it (any depth of the file, `import x.y` too)."""
    found: dict[tuple[str, str], list[str]] = {}
    for path in sorted((ROOT / "studies").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and not node.level and node.module:
                pairs = [(node.module, a.name) for a in node.names]
            elif isinstance(node, ast.Import):
                pairs = [(a.name, "") for a in node.names]
            else:
                continue
            for module, name in pairs:
                parts = module.split(".")
                if parts[0] == "delvjax" and len(parts) > 2 and parts[1] in EDGE and parts[2].startswith("_"):
                    found.setdefault((module, name), []).append(str(path.relative_to(ROOT)))
    return found


def test_the_edge_packages_are_found():
    assert {"plots", "envs", "sweeps", "options", "images"} <= set(EDGE) and "core" not in EDGE


def test_studies_import_edge_packages_only_through_their_surface():
    found = private_imports()
    assert found, "the scan finds the allowed private imports (or ALLOWED is stale)"
    bad = {f"{m}.{n}": files for (m, n), files in found.items() if (m, n) not in ALLOWED}
    assert not bad, f"import these from the package (add a re-export if the name is public-worthy): {bad}"


def test_every_allowed_private_import_is_still_used_and_still_private():
    found = private_imports()
    stale = sorted(f"{m}.{n}" for m, n in ALLOWED if (m, n) not in found)
    assert not stale, f"no study imports these any more: drop them from ALLOWED: {stale}"
    public = sorted(  # a name the package re-exports is imported from the package
        f"{m}.{n}"
        for m, n in ALLOWED
        if getattr(importlib.import_module(m.rsplit(".", 1)[0]), n, None) is getattr(importlib.import_module(m), n)
    )
    assert not public, public
