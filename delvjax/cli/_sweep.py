"""`delvjax sweep`: a sweep file -> labelled results in a folder (docs/sweeps.md)."""

from __future__ import annotations

import argparse
import os
import sys
import threading
import time
from pathlib import Path

import jax

from ..core.checks import positive
from ..core.errors import InputError
from ..options._limits import MAX_POINTS, duration
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_out_dir, check_output_path, output_set
from ..sweeps._examples import EXAMPLES
from ..sweeps._file import read_sweep
from ..sweeps._results import dim_name
from ..sweeps._run import load_sweep, run_sweep, save_sweep, sweep_inputs
from ._args import FIGURE, ProgressBar, progress
from ._help import COMMAND_HELP

CONNECT_TIMEOUT = 300.0  # s: jax.distributed's own default


def add_sweep(sub) -> None:
    p = sub.add_parser(
        "sweep",
        help=COMMAND_HELP["sweep"],
        description="Evaluate every cell of a sweep file (a vector map, a catchment or a success-rate table "
        "per cell) and write sweep.nc (xarray/netCDF), "
        "sweep.csv (one row per cell) and sweep.toml into --out. "
        "`delvjax sweep --example` prints a documented example file.",
    )
    p.add_argument("file", nargs="?", help="the sweep file (TOML)")
    p.add_argument("--out", default=None, help="output folder")
    p.add_argument(
        "--example",
        nargs="?",
        const="vector-map",
        default=None,
        choices=tuple(EXAMPLES),
        help="print a documented example sweep file of that kind (default vector-map) and exit",
    )
    p.add_argument(
        "--max-points",
        type=int,
        default=MAX_POINTS,
        help=f"refuse a cell of more grid points than this (default {MAX_POINTS})",
    )
    g = p.add_argument_group("several processes or machines (jax.distributed; docs/sweeps.md)")
    g.add_argument("--coordinator", default=None, metavar="HOST:PORT", help="address of process 0")
    g.add_argument("--num-processes", type=int, default=None, help="number of processes")
    g.add_argument("--process-id", type=int, default=None, help="this process, 0 .. num-processes - 1")
    g.add_argument(
        "--connect-timeout",
        type=float,
        default=CONNECT_TIMEOUT,
        metavar="S",
        help=f"seconds to wait for every process to join, then fail with one line (default {CONNECT_TIMEOUT:g})",
    )
    g.add_argument(
        "--distributed",
        action="store_true",
        help="let jax.distributed.initialize() read the cluster (SLURM, Open MPI) from the environment",
    )
    p.set_defaults(func=cmd_sweep)


def start_processes(args: argparse.Namespace) -> None:
    """Join the other processes (`jax.distributed.initialize`) before any JAX work, if asked to."""
    given = [args.coordinator, args.num_processes, args.process_id]
    if not args.distributed and all(v is None for v in given):
        return
    if not args.distributed:
        if any(v is None for v in given):
            raise InputError("--coordinator", args.coordinator, "needs --num-processes and --process-id too")
        host, _, port = args.coordinator.rpartition(":")
        if not host or not port.isdigit():
            raise InputError("--coordinator", args.coordinator, "must be HOST:PORT")
        if args.num_processes < 1:
            raise InputError("--num-processes", args.num_processes, "must be >= 1")
        if not 0 <= args.process_id < args.num_processes:
            raise InputError("--process-id", args.process_id, f"must be in 0..{args.num_processes - 1}")

    timeout = positive(args.connect_timeout, "--connect-timeout")
    jax.config.update("jax_cpu_collectives_implementation", "gloo")  # CPU processes exchange results
    kw = (
        {}
        if args.distributed
        else dict(coordinator_address=args.coordinator, num_processes=args.num_processes, process_id=args.process_id)
    )
    joined = threading.Event()

    def watchdog() -> None:  # JAX aborts (SIGABRT) when its own timeout passes: say why first, exit 2
        if not joined.wait(timeout):
            where = args.coordinator or "the coordinator jax.distributed found in the environment"
            print(
                f"delvjax: error: --coordinator: not every process joined {where} within {timeout:g} s "
                "(--connect-timeout): is every process started, with the same --coordinator and --num-processes?",
                file=sys.stderr,
                flush=True,
            )
            os._exit(2)

    threading.Thread(target=watchdog, daemon=True).start()
    jax.distributed.initialize(**kw, initialization_timeout=int(timeout) + 60)
    joined.set()


def cmd_sweep(args: argparse.Namespace) -> int:
    if args.example:
        print(EXAMPLES[args.example], end="")
        return 0
    if args.file is None:
        raise InputError("file", None, "give a sweep file (or --example)")
    if args.out is None:
        raise InputError("--out", None, "give an output folder")
    spec = read_sweep(args.file)
    out = check_out_dir(args.out)
    envs = [spec.env_files.get(e, e) for e in spec.axes.get("env", []) if Path(spec.env_files.get(e, e)).is_file()]
    check_no_clash({"--out": [out / "sweep.nc", out / "sweep.csv"]}, {"file": args.file, "axes.env": envs})
    start_processes(args)

    lead = jax.process_index() == 0  # process 0 reports and writes
    t0 = time.perf_counter()
    n = spec.n_cells
    work = f"about {duration(spec.seconds())} of work on 2 CPU cores plus compilation"
    if lead and n >= 10_000:  # checking the cells takes about 1 ms each: a big sweep says what it is first
        progress(f"sweep of {n} cells: {work}; checking every cell first (about {duration(n * 1e-3)}) ...")
    line = (  # printed when every cell is checked: the bar covers the rest of the run
        f"sweep of {n} cells ({' x '.join(map(str, spec.shape))}: {', '.join(spec.axes)}) on "
        f"{jax.process_count()} process(es), {jax.device_count()} device(s): {work} ..."
    )
    with ProgressBar("cell", 0, lambda total: line) as bar:
        ds = run_sweep(spec, max_points=args.max_points, progress=bar if lead else None, out=out)
    if not lead:
        return 0
    progress(
        f"done in {time.perf_counter() - t0:.1f} s: {n} cells ({ds.attrs['cells_reused']} finished before), "
        f"{ds.attrs['programs_compiled']} program(s) compiled"
    )
    paths = save_sweep(ds, out)
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def add_plot_sweep(sub) -> None:
    p = sub.add_parser(
        "plot-sweep",
        help=COMMAND_HELP["plot-sweep"],
        description="Draw a metric of a sweep folder over one axis (--x: lines with 95 % intervals "
        "over the seeds) or two (--x and --y: heat maps, mean over the seeds); one panel "
        "per combination of the remaining axes. Writes the figure and a CSV of the "
        "numbers drawn (same name, .csv).",
    )
    p.add_argument("dir", help="a folder written by `delvjax sweep`")
    p.add_argument("--x", required=True, help="axis along x")
    p.add_argument("--y", default=None, help="axis along y (a heat map)")
    p.add_argument("--metric", default="mean_error_deg", help="metric to draw (default mean_error_deg)")
    p.add_argument("--out", default=None, help="figure file (.png, .pdf or .svg; default DIR/METRIC.png)")
    p.set_defaults(func=cmd_plot_sweep)


def cmd_plot_sweep(args: argparse.Namespace) -> int:
    from ..plots._sweep import check_plot, sweep_figure  # matplotlib: loaded only when a figure is drawn

    ds = load_sweep(args.dir)
    args.x, args.y = dim_name(args.x), None if args.y is None else dim_name(args.y)  # --x method: homing_method
    check_plot(ds, args.x, args.y, args.metric)
    fig_path = check_output_path(args.out or Path(args.dir) / f"{args.metric}.png", "--out", FIGURE)
    csv_path = fig_path.with_suffix(".csv")
    check_no_clash({"--out": [fig_path, csv_path]}, {"dir": sweep_inputs(args.dir)})
    fig, rows = sweep_figure(ds, args.x, args.y, args.metric)
    with output_set() as files:
        files.figure(fig, fig_path, "--out")
        files.rows_csv(csv_path, rows, "--out")
    print(f"wrote {fig_path}, {csv_path}")
    return 0
