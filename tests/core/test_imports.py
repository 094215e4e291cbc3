"""Nothing heavy is imported before it is used (issue 54): the modules a map, a catchment or a success
rate needs load without scipy.stats (0.6 CPU-s), which comes in with the first t quantile or Wilson interval."""

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


def test_scipy_stats_loads_only_when_an_interval_is_computed():
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, check=True).stdout
    assert "before False" in out and "after True" in out, out
