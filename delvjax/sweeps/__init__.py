"""Sweeps (docs/sweeps.md): a file of axes -> every cell evaluated, one compiled program per
shape -> labelled results (xarray)."""

from ._file import read_sweep as read_sweep
from ._points import point_errors as point_errors
from ._points import point_outcomes as point_outcomes
from ._run import load_sweep as load_sweep
from ._run import run_sweep as run_sweep
from ._run import save_sweep as save_sweep
from ._spec import SweepSpec as SweepSpec
from ._spec import parse_sweep as parse_sweep
