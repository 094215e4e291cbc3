"""The command line, `delvjax` (README): argument parsing and validation; calls the Python API."""

from ._entry import main as main
