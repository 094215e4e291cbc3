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


LEAVE = """
import atexit, sys, threading
atexit.register(lambda: print("atexit ran", flush=True))
go = threading.Event()
if sys.argv[1] == "thread":  # a thread Python waits for: the process ends as usual, after it
    threading.Thread(target=lambda: (go.wait(), print("thread done", flush=True))).start()
sys.argv = ["delvjax", "vector-map", "no-such-env", "--out", "x.csv"]
from delvjax.cli import main
code = main()
print("returned", code, flush=True)
go.set()
sys.exit(code)
"""


@pytest.mark.parametrize("case", ["plain", "thread"])
def test_the_delvjax_process_ends_with_its_code_after_atexit_and_waits_for_threads(case, tmp_path):
    """`delvjax` skips the interpreter's teardown (`_entry.leave`, issue 54): exit code, atexit's functions
    and flushed output as before; with a thread still running it returns and Python waits for the thread."""
    run = subprocess.run([sys.executable, "-c", LEAVE, case], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 2 and "atexit ran" in run.stdout and "no-such-env" in run.stderr, run
    if case == "plain":
        assert "returned" not in run.stdout  # ended in main, after its output
    else:
        assert run.stdout.split() == ["returned", "2", "thread", "done", "atexit", "ran"], run.stdout
