"""The `delvjax` command's entry point: `delvjax --help` answers from the one-line help of each
command (`_help.py`), without loading JAX or a command (under 1 s); any other call loads the command
line (`cli/_main.py`)."""

from __future__ import annotations

import argparse
import sys

from ._help import COMMAND_HELP, DESCRIPTION, version


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv in (["-V"], ["--version"]):
        print(f"delvjax {version()}")
        return 0
    if argv in (["-h"], ["--help"]):
        parser = argparse.ArgumentParser(prog="delvjax", description=DESCRIPTION)
        parser.add_argument("-V", "--version", action="store_true", help="print the version and exit")
        sub = parser.add_subparsers(dest="command", required=True)
        for name, text in COMMAND_HELP.items():
            sub.add_parser(name, help=text)
        parser.print_help()
        return 0
    from ._main import main as run  # JAX and every command: loaded for a command, not for --help

    return run(argv, own_process=True)
