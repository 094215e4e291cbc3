"""`delvjax sweep`: a sweep file -> labelled results in a folder (docs/sweeps.md)."""

from __future__ import annotations

import argparse
import time

from .cli_args import ProgressBar, progress
from .core.errors import InputError
from .limits import MAX_POINTS


def add_sweep(sub) -> None:
    p = sub.add_parser("sweep", help="every combination of the axes of a sweep file (TOML), one program per shape",
                       description="Evaluate every cell of a sweep file and write sweep.nc (xarray/netCDF), "
                                   "sweep.csv (one row per cell) and sweep.toml into --out. "
                                   "`delvjax sweep --example` prints a documented example file.")
    p.add_argument("file", nargs="?", help="the sweep file (TOML)")
    p.add_argument("--out", default=None, help="output folder")
    p.add_argument("--example", action="store_true", help="print a documented example sweep file and exit")
    p.add_argument("--max-points", type=int, default=MAX_POINTS,
                   help=f"refuse a cell of more grid points than this (default {MAX_POINTS})")
    p.set_defaults(func=cmd_sweep)


def cmd_sweep(args: argparse.Namespace) -> int:
    from .sweep_spec import EXAMPLE, read_sweep
    from .io import check_out_dir
    from .sweeps import run_sweep, save_sweep

    if args.example:
        print(EXAMPLE, end="")
        return 0
    if args.file is None:
        raise InputError("file", None, "give a sweep file (or --example)")
    if args.out is None:
        raise InputError("--out", None, "give an output folder")
    spec = read_sweep(args.file)
    out = check_out_dir(args.out)
    t0 = time.perf_counter()
    n = len(spec.cells())
    with ProgressBar("cell", 0) as bar:
        ds = run_sweep(spec, max_points=args.max_points, progress=bar, out=out,
                       announce=lambda: progress(f"sweep of {n} cells ({' x '.join(map(str, spec.shape))}: "
                                                 f"{', '.join(spec.axes)}) ..."))
    progress(f"done in {time.perf_counter() - t0:.1f} s: {n} cells ({ds.attrs['cells_reused']} finished before), "
             f"{ds.attrs['programs_compiled']} program(s) compiled")
    paths = save_sweep(ds, out)
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0
