"""Command line: argument parsing and validation; calls the API. Exit 2 on bad input, no output file then."""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable

import numpy as np

from ..core import maps
from ..core.errors import InputError
from ..core.metrics import summarize_map
from ..core.tables import vector_map_columns
from ..envs._presets import PRESET_DESCRIPTIONS, PRESETS
from ..evaluate import _vector_map as api
from ..options._registry import DESCRIPTIONS
from ..options._schema import all_options
from ..outputs._cache import enable_compilation_cache
from ..outputs._programs import stored_program
from ..outputs._temporary import Terminated, terminate_as_interrupt
from ..reproduce import _run as reproduce
from ..reproduce._study import figure_formats
from ._args import (
    ProgressBar,
    add_output_args,
    add_scene_args,
    check_outputs,
    compiling,
    progress,
    scene_kwargs,
    warn,
    write_outputs,
)
from ._familiarity import FAMILIARITY_COMMANDS
from ._gradients import GRADIENT_COMMANDS
from ._help import COMMAND_HELP, DESCRIPTION, version
from ._images import IMAGE_COMMANDS, add_image_args, cmd_vector_map_images, refuse_image_options
from ._rollouts import ROLLOUT_COMMANDS
from ._sweep import add_plot_sweep, add_sweep

# --- commands ---------------------------------------------------------------------------

# A vector map's chunk program, kept on disk between `delvjax` processes (`outputs._programs`): a warm run
# neither traces nor lowers it. Not for a call of `main` from Python, whose process keeps its programs itself.
KEPT_MAP = stored_program(maps.CHUNK_PROGRAM, lambda leaves: maps.VectorMap(*leaves))


def cmd_envs(args: argparse.Namespace) -> int:
    for name in PRESETS:
        env = api.load_env(name)
        print(f"{name:7s} {env.n_landmarks} landmarks  {PRESET_DESCRIPTIONS[name]}")
    print("\nmethods:")
    for name, text in DESCRIPTIONS.items():
        print(f"  {name:{max(map(len, DESCRIPTIONS))}s} {text}")
    return 0


def add_vector_map(sub) -> None:
    p = sub.add_parser("vector-map", help=COMMAND_HELP["vector-map"])
    add_scene_args(p, images=True)
    add_output_args(p, "vector-map figure")
    p.add_argument("--classes", action="store_true", help="mark error classes < 45 / 45-90 / > 90 deg (Fig 4.3)")
    add_image_args(p)
    p.set_defaults(func=cmd_vector_map)


def cmd_vector_map(args: argparse.Namespace) -> int:
    if args.classes and args.plot is None:
        raise InputError("--classes", True, "marks the figure: give --plot as well")
    if args.images is not None:
        return cmd_vector_map_images(args)
    refuse_image_options(args)
    check_outputs(args)
    kw = scene_kwargs(args)
    env = api.load_env(args.env)
    t0 = time.perf_counter()
    announce = lambda n: f"vector map of {args.method} on {env.name} ({kw['grid'].describe()}, {n} cells) ..."  # noqa: E731
    with ProgressBar("pt", maps.DEFAULT_BATCH, announce, compiling(1, 1)) as bar:
        # a bar only when the grid runs in several chunks; the API counts the grid and calls bar.start
        vm = api.vector_map(env, **kw, progress=bar, chunk_program=getattr(args, "map_program", None))
    vm.error_deg.block_until_ready()
    summary = {
        "env": env.name,
        "method": args.method,
        **summarize_map(vm.error_deg, vm.valid, vm.included),
        "seconds": time.perf_counter() - t0,
    }
    progress(
        f"done in {summary['seconds']:.2f} s: {summary['points']} points, {summary['invalid']} invalid, "
        f"mean error {summary['mean_error_deg']:.2f} deg, >45: {summary['gt45_pct']:.2f} %, "
        f">90: {summary['gt90_pct']:.2f} %"
    )
    if not bool(np.any(np.asarray(vm.valid) & np.asarray(vm.included))):
        warn("every grid point is invalid: the method finds no homing direction anywhere (too few visible landmarks?)")
    title = f"{args.method} on {env.name}: mean error {summary['mean_error_deg']:.1f}°"

    def figure():
        from ..plots._maps import vector_map_figure  # matplotlib: loaded only when a figure is drawn

        return vector_map_figure(env, vm, title=title, classes=args.classes)  # the map carries its spacing

    write_outputs(args, vector_map_columns(vm), summary, figure)
    return 0


def add_reproduce(sub) -> None:
    p = sub.add_parser(
        "reproduce",
        help=COMMAND_HELP["reproduce"],
        description="Run the thesis's studies (skipping those whose code and settings are unchanged) "
        "and write figures, CSV/JSON, report.md and report.html into --out.",
    )
    p.add_argument(
        "--quick",
        action="store_true",
        help="a preview of the thesis's simulation studies on a coarse 10 x 10 grid (spacing 100 cm); the "
        "studies beyond the thesis and on rendered images run in a full run or when --only names them",
    )
    p.add_argument("--out", default="results", help="output folder (default results/)")
    p.add_argument("--only", default=None, metavar="STUDY[,STUDY]", help="run only these studies")
    p.add_argument("--list", action="store_true", help="list the studies and exit")
    p.add_argument("--force", action="store_true", help="recompute even studies that are up to date")
    p.add_argument("--seed", type=int, default=0, help="seed of every random heading, release point and noise")
    p.add_argument(
        "--format",
        default="png",
        metavar="png[,pdf,svg]",
        help="figure files to write (default png; the PNG is always written, the report shows it): "
        "e.g. png,pdf,svg for vector figures beside it",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="studies run side by side (default: one per CPU core, at most 4; 1: one at a time); "
        "the numbers do not depend on it",
    )
    p.set_defaults(func=cmd_reproduce)


def cmd_reproduce(args: argparse.Namespace) -> int:
    if args.list:
        for name, module in reproduce.registry().items():
            print(f"{name:16s} {module.TITLE}")
        return 0
    reproduce.select(args.only)  # validate before any work
    figure_formats(args.format)
    if args.workers is not None and args.workers < 1:
        raise InputError("--workers", args.workers, "must be at least 1")
    reproduce.check_out_dir(args.out)
    t0 = time.perf_counter()
    try:
        result = reproduce.reproduce(
            args.out,
            quick=args.quick,
            only=args.only,
            force=args.force,
            seed=args.seed,
            workers=args.workers,
            formats=args.format,
        )
    except OSError as exc:  # e.g. a full disk: every file is whole or absent, finished studies are kept
        why = exc.strerror or str(exc)
        raise InputError("--out", args.out, f"could not be written ({why}): finished studies are kept") from None
    skipped = [n for n in result["records"] if n not in result["ran"]]
    print(
        f"ran {len(result['ran'])} studies"
        + (f", {len(skipped)} unchanged (skipped)" if skipped else "")
        + f" in {time.perf_counter() - t0:.1f} s; report: {result['report']}"
    )
    return 0


# Each entry adds one subcommand; a new command is one function here or in its own module.
COMMANDS: list[Callable] = [
    add_vector_map,
    add_reproduce,
    *ROLLOUT_COMMANDS,
    add_sweep,
    add_plot_sweep,
    *GRADIENT_COMMANDS,
    *IMAGE_COMMANDS,
    *FAMILIARITY_COMMANDS,
]


class Parser(argparse.ArgumentParser):
    """argparse, but a bad flag is one line naming it (and where to read more), not the usage first."""

    def error(self, message: str):
        print(f"{self.prog}: error: {message} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="delvjax", description=DESCRIPTION)
    parser.add_argument(
        "-V", "--version", action="version", version=f"delvjax {version()}", help="print the version and exit"
    )
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("envs", help=COMMAND_HELP["envs"]).set_defaults(func=cmd_envs)
    for add in COMMANDS:
        add(sub)
    return parser


def command_defaults(parser: argparse.ArgumentParser, args: argparse.Namespace) -> dict:
    """The default of every option of the command `args` ran (of its subcommand, for `images ...`)."""
    return {a.dest: a.default for a in command_parser(parser, args)._actions if a.dest != "help"}


FILE_KEYED = ("sweep", "plot-sweep")  # commands whose settings are a file's keys (n_psi), not flags


def command_parser(parser: argparse.ArgumentParser, args: argparse.Namespace) -> argparse.ArgumentParser:
    """The parser of the (sub)command `args` ran (of `images ...`'s subcommand)."""
    for name in ("command", "images_command"):
        chosen = getattr(args, name, None)
        subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        if chosen is None or not subs or chosen not in subs[0].choices:
            break
        parser = subs[0].choices[chosen]
    return parser


def as_typed(exc: InputError, parser: argparse.ArgumentParser, args: argparse.Namespace) -> InputError:
    """The error as the user typed it: a field that is one of the command's options (`n_psi`, the API
    keyword a check raises with; `Option.flag` of the options registry, or the parser's own flags) named
    by its flag (`--n-psi`); a sweep's keys and an environment file's (`file_key`) stay as the file writes them."""
    if getattr(args, "command", None) in FILE_KEYED or exc.file_key:
        return exc
    actions = command_parser(parser, args)._actions
    flags = {a.dest: a.option_strings[-1] for a in actions if a.option_strings and a.help != argparse.SUPPRESS}

    def typed(field: str) -> str:
        option = all_options().get(field)
        flag = flags.get(field) or (option.flag if option is not None and option.flag in flags.values() else None)
        return field if flag is None else flag

    field = " and ".join(typed(f) for f in exc.field.split(" and "))  # "n_alpha and n_psi": each by its flag
    return exc if field == exc.field else InputError(field, exc.value, exc.expected)


def main(argv: list[str] | None = None, own_process: bool = False, keep_programs: bool = False) -> int:
    """Run one command: exit 0, 2 on bad input (one line), 130 on Ctrl-C and 143 on SIGTERM (every
    temporary removed, finished work kept: docs/reliability.md). `own_process`: the `delvjax` command
    owns the process, and SIGTERM unwinds like Ctrl-C (not so for a call from Python). `keep_programs`:
    a vector map's compiled program is kept on disk for the next process (`KEPT_MAP`)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    args.defaults = command_defaults(parser, args)
    if keep_programs:
        args.map_program = KEPT_MAP  # a callable: no setting of the run (`command_settings`)
    enable_compilation_cache()
    if own_process:
        terminate_as_interrupt()
    try:
        return args.func(args)
    except InputError as exc:
        print(f"delvjax: error: {as_typed(exc, parser, args)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        term = isinstance(exc, Terminated)
        print(f"delvjax: {'terminated' if term else 'interrupted'}: finished work is kept", file=sys.stderr)
        return 143 if term else 130


if __name__ == "__main__":
    sys.exit(main())
