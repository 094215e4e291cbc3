"""The API reference (docs/api.md, rendered by mkdocstrings from the docstrings): every public name of
`delvjax` has an entry, every entry names a real object, and the site builds with every warning an
error (`mkdocs build --strict`, as CI and the README run it)."""

from __future__ import annotations

import importlib
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

import delvjax
from delvjax.options._docs import generated_page

ROOT = Path(__file__).resolve().parents[1]
# the page as the site builds it: the registered methods' entries are made then (docs/_ext/generated.py)
TARGETS = re.findall(r"^::: (\S+)$", generated_page("api.md", (ROOT / "docs" / "api.md").read_text()), flags=re.M)


def test_every_public_name_has_an_entry():
    documented = {t.rsplit(".", 1)[1] for t in TARGETS}
    assert sorted(set(delvjax.__all__) - documented) == []


@pytest.mark.parametrize("target", TARGETS)
def test_every_entry_is_the_public_object(target):
    module, name = target.rsplit(".", 1)
    obj = getattr(importlib.import_module(module), name)
    if name in delvjax.__all__:
        assert getattr(delvjax, name) is obj, target  # the page documents what `delvjax.NAME` is


def test_the_site_builds_with_warnings_as_errors(tmp_path):
    pytest.importorskip("mkdocstrings")
    run = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    page = (tmp_path / "site" / "api" / "index.html").read_text()
    assert "Mean of 1 - cos(angular error)" in page  # the docstrings are in it
    assert "CartwrightCollett" in page and "MinWarping" in page  # the registered methods, made by the hook
    options = (tmp_path / "site" / "options" / "index.html").read_text()
    assert "--radial-weight" in options and "<!-- the table of options" not in options  # the table, made
    # defaults written as constants show their values (docs/_ext/evaluated_defaults.py; issue 53 point 8)
    text = re.sub(r"<[^>]+>", "", page)
    assert "spacing: float = 25.0" in text and "trials: int = 100" in text, "a default shows its value"
    assert not re.findall(r"= (SPACING|MAX_STEPS|HOME_RADIUS|DEFAULT_DISTANCES|TRIALS_PER_DISTANCE)\b", text)


def test_every_extra_the_docs_name_exists():
    """`pip install -e '.[docs]'` in mkdocs.yml named an extra that did not exist (issue 53 point 8)."""
    extras = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"])
    texts = [ROOT / "README.md", ROOT / "mkdocs.yml", ROOT / ".ci" / "run", *sorted((ROOT / "docs").glob("*.md"))]
    named = {e for p in texts for group in re.findall(r"\.\[([a-z,\s-]+)\]", p.read_text()) for e in group.split(",")}
    assert named and sorted(e.strip() for e in named if e.strip() not in extras) == []
