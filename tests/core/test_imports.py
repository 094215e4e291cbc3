"""Nothing heavy is imported before it is used (issue 54): the modules a map, a catchment or a success
rate needs load without scipy.stats (0.5-1 s), which none of them needs (t quantiles and Wilson intervals come
from scipy.special);
a vector map from the command line loads neither optimistix nor matplotlib, xarray or pandas."""

from __future__ import annotations

import subprocess
import sys

CODE = """
import sys
import delvjax
from delvjax.core import metrics
from delvjax.core.rollouts import success
delvjax.vector_map, delvjax.catchment, delvjax.success_rate
print("before", "scipy.stats" in sys.modules)
metrics.t_quantile(5), success.wilson_pct(3, 10)
print("after", "scipy.stats" in sys.modules)
"""


def test_scipy_stats_is_not_loaded_even_when_an_interval_is_computed():
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, check=True).stdout
    assert "before False" in out and "after False" in out, out


HEAVY = ("optimistix", "lineax", "matplotlib", "scipy", "xarray", "pandas", "PIL")

CLI_MAP = """
import sys
import delvjax
print("import", sorted(m for m in HEAVY if m in sys.modules))
from delvjax.cli._entry import main
assert main(["vector-map", "env1", "--method", "alv", "--spacing", "200", "--out", sys.argv[1]]) == 0
print("vector-map", sorted(m for m in HEAVY if m in sys.modules))
"""


def test_a_vector_map_from_the_command_line_loads_no_solver_figure_or_table_library(tmp_path):
    """optimistix (0.1-0.3 s with lineax) loads with a solver (DELVRefined, traps, layouts, equilibria),
    matplotlib with a figure (--plot), xarray and pandas with a labelled table: not for a map's CSV."""
    code = f"HEAVY = {HEAVY!r}\n" + CLI_MAP
    env = {**__import__("os").environ, "DELVJAX_CACHE_DIR": ""}
    run = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path / "vm.csv")], capture_output=True, text=True, env=env, timeout=300
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert "import []" in run.stdout and "vector-map []" in run.stdout, run.stdout
