"""The `delvjax` command's entry point: `delvjax --help` answers from the one-line help of each
command (`_help.py`), without loading JAX or a command (under 1 s); any other call loads the command
line (`cli/_main.py`), after asking XLA for one CPU device per core where the command gains by it
(`host_devices`)."""

from __future__ import annotations

import argparse
import atexit
import os
import sys
import threading
from collections.abc import Mapping

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
    if whole_process:
        try:
            use_host_devices(host_devices(split_command(argv), os.environ))
        except ValueError as exc:
            print(f"delvjax: error: {exc}", file=sys.stderr)
            return 2
    from ._main import main as run  # JAX and every command: loaded for a command, not for --help

    code = run(argv, own_process=True, keep_programs=whole_process)
    if whole_process:
        leave(code)
    return code


DEVICES_ENV = "DELVJAX_DEVICES"  # CPU devices a `delvjax` process splits its work over (1: one device)
DEVICE_FLAG = "--xla_force_host_platform_device_count"
# Commands whose work `batching.over_devices` splits over a `local_mesh`, and that gain by it on a CPU host
# (benchmarks/bench_cores.py, 2 loaded cores: catchment 1.00x cold / 1.39x warm, sweep 1.08x / 1.14x). Not
# `success-rate` or `trajectories` (a few hundred rollouts: 0.92x cold, the partitioned program compiles longer),
# `vector-map` (0.92x cold, and a warm map runs the program kept on disk for one device, `outputs/_programs.py`)
# nor `reproduce` (its studies already run side by side in threads: --quick 148 CPU-s on 2 devices, 120 on one).
EVERY_CORE = frozenset({"catchment", "sweep"})


def split_command(argv: list[str]) -> str | None:
    """The command of `argv` whose work may take every core; None for a process of a `--num-processes`
    run (its processes share the cores already)."""
    return None if not argv or any(a.startswith("--num-processes") for a in argv) else argv[0]


def host_devices(command: str | None, environ: Mapping[str, str]) -> int:
    """How many CPU devices the `delvjax` process running `command` asks XLA for: `DELVJAX_DEVICES` where
    set, else one per core this process may run on for a command of `EVERY_CORE`; 0 (XLA's default, one)
    for another command or where `XLA_FLAGS` sets the count itself. Every device gets whole fixed-width
    groups of items, so the numbers are those of one device (docs/reproduce.md "Chunking"). The flag
    makes host (CPU) devices only: on a GPU or TPU the work is split over that platform's devices."""
    if DEVICE_FLAG in environ.get("XLA_FLAGS", ""):
        return 0
    asked = environ.get(DEVICES_ENV, "").strip()
    if asked:
        if not asked.isdigit() or int(asked) < 1:
            raise ValueError(f"{DEVICES_ENV}={asked!r}: must be a whole number of devices, at least 1")
        return int(asked)
    if command not in EVERY_CORE:
        return 0
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def use_host_devices(count: int) -> None:
    """Ask XLA for `count` CPU devices (before JAX loads; 0 or 1: as it is)."""
    if count > 1:
        os.environ["XLA_FLAGS"] = f"{os.environ.get('XLA_FLAGS', '')} {DEVICE_FLAG}={count}".strip()


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
