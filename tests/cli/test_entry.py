"""`delvjax --help` answers without loading JAX (it starts in well under a second), with the same
text as the full parser's; `import delvjax` loads nothing heavy until a name is used."""

from __future__ import annotations

import subprocess
import sys

import pytest

from delvjax.cli._entry import main as entry
from delvjax.cli._main import build_parser


def test_help_loads_neither_jax_nor_a_command():
    code = (
        "import sys; from delvjax.cli import main; main(['--help']); "
        "print(sorted(m for m in ('jax', 'equinox', 'matplotlib', 'xarray', 'PIL', 'delvjax.cli._main') "
        "if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip().splitlines()[-1] == "[]", out
    assert "optimise-layout" in out


def test_the_quick_help_is_the_full_parsers(capsys):
    assert entry(["--help"]) == 0
    quick = capsys.readouterr().out
    assert quick == build_parser().format_help()


def test_every_other_call_reaches_the_commands(capsys):
    assert entry(["envs"]) == 0
    assert "env1" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        entry(["vector-map", "--help"])
    assert "--levels" in capsys.readouterr().out


def test_names_load_on_first_use():
    code = (
        "import sys, delvjax; before = 'jax' in sys.modules; delvjax.DELV(); "
        "print(before, 'jax' in sys.modules, delvjax.core.maps.SPACING)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "True", "25.0"]


def test_version_prints_the_installed_version_without_loading_jax():
    import subprocess
    import sys
    from importlib.metadata import version

    code = "import sys; from delvjax.cli import main; main(['--version']); print('jax' in sys.modules)"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.stdout.splitlines() == [f"delvjax {version('delvjax')}", "False"]
