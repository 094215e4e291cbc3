"""CLI subcommands for homing rollouts (docs/model.md §5): `catchment`, `success-rate`, `trajectories`.

Each validates its outputs and options before any work; bad input -> exit 2, no output file.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from ..core.checks import occlusion_count
from ..core.errors import InputError
from ..core.rollouts import (
    DEFAULT_DISTANCES,
    N_STARTS,
    TRIAL_BLOCK,
    TRIALS_PER_DISTANCE,
    catchment_summary,
)
from ..core.tables import (
    catchment_columns,
    concat_columns,
    outcome_names,
    success_rows,
    success_trial_columns,
    trajectory_columns,
)
from ..evaluate import _rollouts as api_rollouts
from ..evaluate import _vector_map as api
from ..options._registry import get_method
from ..options._setup import make_setup, option_names
from ._args import (
    ProgressBar,
    add_output_args,
    add_rollout_args,
    add_scene_args,
    check_outputs,
    compiling,
    progress,
    rollout_kwargs,
    warn,
    write_outputs,
)
from ._help import COMMAND_HELP
from ._images import add_image_args, cmd_catchment_images, refuse_image_options


def _check_methods(methods: list[str], kw: dict) -> None:
    """Every method of a comma-separated list with the options, validated before the first one runs."""
    names = set().union(*option_names())
    options = {k: v for k, v in kw.items() if k in names}
    for m in methods:
        make_setup(m, **options)


def _methods(text: str) -> list[str]:
    parts = [m.strip() for m in text.split(",")]
    names = [m for m in parts if m]
    if not names or len(names) < len(parts):
        raise InputError("method", text, "must be method names separated by commas, none empty")
    if len(set(names)) < len(names):  # its rows would appear twice in the CSV and once in the JSON
        raise InputError("method", text, f"names {next(m for m in names if names.count(m) > 1)} twice")
    for m in names:
        get_method(m)
    return names


# --- catchment -------------------------------------------------------------------------------


def _rollout_parser(sub, name: str, plot_help: str, epilog: str | None = None, grid: bool = False):
    """A subcommand with the scene, output and rollout options every rollout command takes (--spacing
    only where a grid is evaluated: an option a command does not use is not offered)."""
    p = sub.add_parser(name, help=COMMAND_HELP[name], epilog=epilog)
    add_scene_args(p, grid=grid, images=grid)
    add_output_args(p, plot_help)
    add_rollout_args(p)
    return p


def add_catchment(sub) -> None:
    p = _rollout_parser(sub, "catchment", "catchment map: squares on catchment points over the vector map", grid=True)
    p.add_argument(
        "--occlude",
        type=int,
        default=None,
        metavar="K",
        help="evaluate every choice of K landmarks hidden during homing (Tables 5.3/5.4)",
    )
    add_image_args(p)
    p.set_defaults(func=cmd_catchment)


def cmd_catchment(args: argparse.Namespace) -> int:
    if args.images is not None:
        return cmd_catchment_images(args)
    refuse_image_options(args)
    check_outputs(args)
    kw = rollout_kwargs(args, drop=())
    if args.occlude is not None:
        if args.hide:
            raise InputError("--occlude", args.occlude, "cannot be combined with --hide")
        kw["occlude"] = args.occlude
    env = api.load_env(args.env)
    if args.occlude is not None:
        occlusion_count(args.occlude, env.n_landmarks)
    t0 = time.perf_counter()
    line = (  # printed when the API starts the bar: every option is valid
        f"catchment of {args.method} on {env.name} ({kw['grid'].describe()}"
        + (f", {args.occlude} of {env.n_landmarks} landmarks hidden" if args.occlude else "")
        + f") ...\n[delvjax] {compiling(1, 1)} ..."
    )
    with ProgressBar("trial", TRIAL_BLOCK, lambda total: line) as bar:  # a bar once the trials run in several blocks
        res = api_rollouts.catchment(env, **kw, progress=bar)
    res.outcome.block_until_ready()
    seconds = time.perf_counter() - t0
    summary = {
        "env": env.name,
        "method": args.method,
        "occlude": args.occlude if args.occlude is not None else len(args.hide or ()),  # --hide 3: one hidden
        "seconds": seconds,
        **catchment_summary(res),
    }
    c = summary["catchment_pct"]
    progress(
        f"done in {seconds:.2f} s: {summary['points']} points x {summary['masks']} mask(s); catchment "
        + (
            f"{c['mean']:.2f} %"
            if summary["masks"] == 1
            else f"mean {c['mean']:.2f} %, min {c['min']:.2f} %, max {c['max']:.2f} %"
        )
        + f"; >45: {summary['gt45_pct']['mean']:.2f} %, >90: {summary['gt90_pct']['mean']:.2f} %"
    )
    if not bool(np.any(np.asarray(res.valid)[:, np.asarray(res.included)])):
        warn(
            "every grid point is invalid under every mask: the method finds no homing direction anywhere "
            "(too few visible landmarks?)"
        )
    from ..plots._rollouts import catchment_figure  # matplotlib: loaded only when a figure is drawn

    write_outputs(
        args,
        catchment_columns(res, with_hidden=args.occlude is not None or bool(args.hide)),
        summary,
        lambda: catchment_figure(env, res, title=f"{args.method} on {env.name}"),  # on the result's own grid
    )
    return 0


# --- success rate ----------------------------------------------------------------------------


def add_success_rate(sub) -> None:
    p = _rollout_parser(
        sub, "success-rate", "success-rate curve", "--method takes a comma-separated list (one curve each)."
    )
    p.add_argument(
        "--trials",
        type=int,
        default=TRIALS_PER_DISTANCE,
        help=f"trials per distance bin (default {TRIALS_PER_DISTANCE})",
    )
    p.add_argument(
        "--distances",
        type=float,
        nargs="+",
        default=list(DEFAULT_DISTANCES),
        metavar="CM",
        help="release distances from home (default 50 100 ... 450)",
    )
    p.add_argument("--trials-out", default=None, help="per-trial CSV (release point, heading, outcome, steps)")
    p.set_defaults(func=cmd_success_rate)


def cmd_success_rate(args: argparse.Namespace) -> int:
    check_outputs(args)
    methods = _methods(args.method)
    env = api.load_env(args.env)
    kw = rollout_kwargs(args, drop=("method",))
    kw.update(trials=args.trials, distances=args.distances)
    _check_methods(methods, kw)
    tables, rows, trial_cols, timing = {}, [], [], {}
    for m in methods:  # one program per method (different methods are different programs)
        t0 = time.perf_counter()
        line = (
            f"success rate of {m} on {env.name}: {args.trials} trials x {len(args.distances)} distances ...\n"
            f"[delvjax] {compiling(methods.index(m) + 1, len(methods))} ..."
        )
        res = api_rollouts.success_rate(env, method=m, **kw, progress=ProgressBar("trial", 0, lambda total: line))
        res.outcome.block_until_ready()
        timing[m] = time.perf_counter() - t0
        tables[m] = res.table()
        total = sum(r["successes"] for r in tables[m]), sum(r["placed"] for r in tables[m])
        progress(f"done in {timing[m]:.2f} s: {total[0]}/{total[1]} trials reach home")
        asked = args.trials * len(args.distances)
        if total[1] < asked:  # release points outside the arena or in a landmark: no trial, success_pct NaN if none
            warn(
                f"{asked - total[1]} of {asked} release points of {m} could not be placed (outside the arena or in a "
                "landmark): their trials are outcome not_placed, and a distance with none placed has success_pct NaN"
            )
        rows += success_rows(res, m)
        trial_cols.append(success_trial_columns(res, m))
    rules = kw["rules"].recorded
    from ..plots._rollouts import success_rate_figure  # matplotlib: loaded only when a figure is drawn

    summary = {
        "env": env.name,
        "trials_per_bin": args.trials,
        "seed": args.seed,
        "rules": rules,
        "max_steps": args.max_steps,
        "home_radius": args.home_radius,
        "seconds": timing,
        "bins": tables,
    }
    write_outputs(
        args,
        rows,
        summary,
        lambda: success_rate_figure(tables, title=f"success rate on {env.name} ({args.trials} trials per distance)"),
        concat_columns(trial_cols),
    )
    return 0


# --- trajectories ----------------------------------------------------------------------------


def add_trajectories(sub) -> None:
    p = _rollout_parser(
        sub,
        "trajectories",
        "trajectory figure (one panel per method)",
        "--method takes a comma-separated list (one panel each, same release points).",
    )
    p.add_argument(
        "--start",
        type=float,
        nargs=2,
        action="append",
        default=None,
        metavar=("X", "Y"),
        help="a release point in cm (repeatable; default: --n-starts random points from --seed)",
    )
    p.add_argument(
        "--n-starts", type=int, default=None, help=f"random release points, instead of --start (default {N_STARTS})"
    )
    p.set_defaults(func=cmd_trajectories)


def cmd_trajectories(args: argparse.Namespace) -> int:
    check_outputs(args)
    if args.start and args.n_starts is not None:
        raise InputError("--n-starts", args.n_starts, "cannot be combined with --start")
    methods = _methods(args.method)
    env = api.load_env(args.env)
    kw = rollout_kwargs(args, drop=("method",))
    kw.update(starts=args.start, n_starts=N_STARTS if args.n_starts is None else args.n_starts)
    results, cols = {}, []
    summary = {"env": env.name, "rules": kw["rules"].recorded, "trials": {}}
    _check_methods(methods, kw)
    for m in methods:  # one program per method
        line = f"trajectories of {m} on {env.name} ...\n[delvjax] {compiling(methods.index(m) + 1, len(methods))} ..."
        tr = api_rollouts.trajectories(env, method=m, **kw, progress=ProgressBar("trial", 0, lambda total: line))
        results[m] = tr
        path, steps = np.asarray(tr.path), np.asarray(tr.steps)
        cols.append(trajectory_columns(tr, m))
        outcome = outcome_names(tr.outcome)
        summary["trials"][m] = [
            {
                "start": np.asarray(tr.start[t]).tolist(),
                "release_heading_deg": float(np.degrees(tr.heading[t])),
                "outcome": outcome[t],
                "steps": int(steps[t]),
            }
            for t in range(path.shape[0])
        ]
        progress(f"{int(np.asarray(tr.success).sum())}/{path.shape[0]} reach home")
    from ..plots._rollouts import trajectories_figure  # matplotlib: loaded only when a figure is drawn

    write_outputs(
        args,
        concat_columns(cols),
        summary,
        lambda: trajectories_figure(env, results, args.home_radius, title=f"homing trajectories on {env.name}"),
    )
    return 0


ROLLOUT_COMMANDS = [add_catchment, add_success_rate, add_trajectories]
