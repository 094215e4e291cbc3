"""The command line, `delvjax` (README): argument parsing and validation; calls the Python API."""

from ._main import main as main
