"""The `delvjax` command's entry point: `delvjax --help` answers from the one-line help of each
command (`_help.py`), without loading JAX or a command (under 1 s); any other call loads the command
line (`cli/_main.py`)."""

from __future__ import annotations

import argparse
import atexit
import os
import sys
import threading

from ._help import COMMAND_HELP, DESCRIPTION, version


def main(argv: list[str] | None = None) -> int:
    """The `delvjax` command (`argv` None: it owns the process) or a call with `argv` from Python."""
    whole_process = argv is None
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

    code = run(argv, own_process=True, keep_programs=whole_process)
    if whole_process:
        leave(code)
    return code


def leave(code: int) -> None:
    """End the `delvjax` process with `code` once its work is done and written: atexit's functions run and
    the streams are flushed, but the interpreter's teardown is skipped (0.2-0.3 s after a vector map: JAX's
    client and compiled programs freed one by one, for nothing). Not while another thread that Python
    would wait for runs: the process then ends as usual."""
    if any(not t.daemon for t in threading.enumerate() if t is not threading.main_thread()):
        return
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: nothing more can be said
            pass
    os._exit(code)
