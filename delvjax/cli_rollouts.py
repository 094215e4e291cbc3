"""CLI subcommands for homing rollouts (docs/model.md §5): `catchment`, `success-rate`, `trajectories`.

Each validates its outputs and options before any work; bad input -> exit 2, no output file.
`cli` is imported inside the functions so that this module can be imported from cli.py.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from . import rollouts
from .errors import InputError


def _add_rollout_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("rollouts (docs/model.md §5)")
    g.add_argument("--max-steps", type=int, default=50, help="moves allowed to reach home (default 50)")
    g.add_argument("--home-radius", type=float, default=50.0, help="success within this distance of home, cm (default 50)")
    g.add_argument("--lanes", type=int, default=rollouts.DEFAULT_LANES,
                   help=f"trials advanced side by side (memory bound; default {rollouts.DEFAULT_LANES})")
    g.add_argument("--first-move", default="homing", metavar="RULE",
                   help="homing (default): the first move follows the homing direction computed at the release "
                        "point, as in the vector map; release: it follows the release heading")
    g.add_argument("--collisions", default="ignore", metavar="RULE",
                   help="ignore (default): landmarks are no obstacles; fail: a move ending inside a landmark fails")


def _kwargs(args: argparse.Namespace, drop=("spacing",)) -> dict:
    from .cli import scene_kwargs

    kw = scene_kwargs(args)
    for name in drop:
        kw.pop(name, None)
    rollouts.check_rules(args.first_move, args.collisions)  # before any work or progress line
    kw.update(max_steps=args.max_steps, home_radius=args.home_radius, first_move=args.first_move,
              collisions=args.collisions)
    return kw


def _methods(text: str) -> list[str]:
    from .methods import get_method

    names = [m.strip() for m in text.split(",") if m.strip()]
    if not names:
        raise InputError("method", text, "must name at least one method")
    for m in names:
        get_method(m)
    return names


def _rule_columns(rules: dict[str, str], n: int) -> dict[str, list[str]]:
    """The rollout rules as constant CSV columns (so every CSV names the rules it was made under)."""
    return {name: [value] * n for name, value in rules.items()}


def _outcome_names(codes) -> list[str]:
    return [rollouts.OUTCOMES[c] if c >= 0 else "not_placed" for c in np.asarray(codes).tolist()]


# --- catchment -------------------------------------------------------------------------------

def _rollout_parser(sub, name: str, help_text: str, plot_help: str, epilog: str | None = None):
    """A subcommand with the scene, output and rollout options every rollout command takes."""
    from .cli import add_output_args, add_scene_args

    p = sub.add_parser(name, help=help_text, epilog=epilog)
    add_scene_args(p)
    add_output_args(p, plot_help)
    _add_rollout_args(p)
    return p


def add_catchment(sub) -> None:
    p = _rollout_parser(sub, "catchment", "catchment area: a rollout from every grid point (docs/model.md §5; Figs 4.5, 5.5)",
                        "catchment map: squares on catchment points over the vector map")
    p.add_argument("--occlude", type=int, default=None, metavar="K",
                   help="evaluate every choice of K landmarks hidden during homing (Tables 5.3/5.4)")
    p.set_defaults(func=cmd_catchment)


def cmd_catchment(args: argparse.Namespace) -> int:
    from . import api
    from .cli import check_outputs, progress
    from .io import save_figure, write_csv, write_json
    from .options import occlusion_count

    check_outputs(args)
    kw = _kwargs(args, drop=())
    kw["lanes"] = args.lanes
    if args.occlude is not None:
        if args.hide:
            raise InputError("--occlude", args.occlude, "cannot be combined with --hide")
        kw["occlude"] = args.occlude
    env = api.load_env(args.env)
    if args.occlude is not None:
        occlusion_count(args.occlude, env.n_landmarks)
    t0 = time.perf_counter()
    progress(f"catchment of {args.method} on {env.name} (spacing {args.spacing:g} cm"
             + (f", {args.occlude} of {env.n_landmarks} landmarks hidden" if args.occlude else "") + ") ...")
    res = rollouts.catchment(env, **kw)
    res.outcome.block_until_ready()
    seconds = time.perf_counter() - t0
    summary = {"env": env.name, "method": args.method, "occlude": args.occlude or 0, "seconds": seconds,
               **rollouts.catchment_summary(res)}
    c = summary["catchment_pct"]
    progress(f"done in {seconds:.2f} s: {summary['points']} points x {summary['masks']} mask(s); catchment "
             + (f"{c['mean']:.2f} %" if summary["masks"] == 1 else
                f"mean {c['mean']:.2f} %, min {c['min']:.2f} %, max {c['max']:.2f} %")
             + f"; >45: {summary['gt45_pct']['mean']:.2f} %, >90: {summary['gt90_pct']['mean']:.2f} %")
    inc = np.asarray(res.included)
    n_masks = summary["masks"]
    pts = np.tile(np.asarray(res.points)[inc], (n_masks, 1))
    per = lambda a: np.asarray(a)[:, inc].reshape(-1)  # noqa: E731
    columns = {
        "x": pts[:, 0], "y": pts[:, 1],
        "heading_deg": np.tile(np.degrees(np.asarray(res.heading)[inc]), n_masks),
        "success": per(res.success), "steps": per(res.steps), "outcome": _outcome_names(per(res.outcome)),
        "end_x": per(np.asarray(res.end)[..., 0]), "end_y": per(np.asarray(res.end)[..., 1]),
        "invalid_steps": per(res.invalid_steps),
        "direction_deg": np.degrees(per(res.direction)), "error_deg": per(res.error_deg), "valid": per(res.valid),
        **_rule_columns(res.rules, pts.shape[0]),
    }
    if args.occlude is not None or args.hide:
        columns["hidden"] = [" ".join(map(str, h)) for h in res.hidden for _ in range(int(inc.sum()))]
    write_csv(args.out, columns)
    if args.summary:
        write_json(args.summary, summary)
    if args.plot:
        from .plots_rollouts import catchment_figure

        save_figure(catchment_figure(env, res, args.spacing, title=f"{args.method} on {env.name}"), args.plot)
    print(f"wrote {args.out}" + (f", {args.plot}" if args.plot else "") + (f", {args.summary}" if args.summary else ""))
    return 0


# --- success rate ----------------------------------------------------------------------------

def add_success_rate(sub) -> None:
    p = _rollout_parser(sub, "success-rate", "success rate vs release distance (docs/model.md §5; Figs 4.10b, 5.7b)",
                        "success-rate curve", "--method takes a comma-separated list (one curve each); --spacing is not used.")
    p.add_argument("--trials", type=int, default=100, help="trials per distance bin (default 100)")
    p.add_argument("--distances", type=float, nargs="+", default=list(rollouts.DEFAULT_DISTANCES), metavar="CM",
                   help="release distances from home (default 50 100 ... 450)")
    p.add_argument("--trials-out", default=None, help="per-trial CSV (release point, heading, outcome, steps)")
    p.set_defaults(func=cmd_success_rate)


def cmd_success_rate(args: argparse.Namespace) -> int:
    from . import api
    from .cli import CSV, check_outputs, progress
    from .io import check_output_path, save_figure, write_csv, write_json, write_rows_csv

    check_outputs(args)
    if args.trials_out is not None:
        check_output_path(args.trials_out, "--trials-out", CSV)
    methods = _methods(args.method)
    env = api.load_env(args.env)
    kw = _kwargs(args, drop=("spacing", "method"))
    kw.update(lanes=args.lanes, trials=args.trials, distances=args.distances)
    tables, trial_cols, timing = {}, [], {}
    for m in methods:  # one program per method (different methods are different programs)
        t0 = time.perf_counter()
        progress(f"success rate of {m} on {env.name}: {args.trials} trials x {len(args.distances)} distances ...")
        res = rollouts.success_rate(env, method=m, **kw)
        res.outcome.block_until_ready()
        timing[m] = time.perf_counter() - t0
        tables[m] = res.table()
        total = sum(r["successes"] for r in tables[m]), sum(r["placed"] for r in tables[m])
        progress(f"done in {timing[m]:.2f} s: {total[0]}/{total[1]} trials reach home")
        placed = np.asarray(res.placed).reshape(-1)
        start = np.asarray(res.start).reshape(-1, 2)
        n_bins, n_tr = res.placed.shape
        trial_cols.append({
            "method": [m] * placed.size,
            "distance_cm": np.repeat(np.asarray(res.distances), n_tr),
            "trial": np.tile(np.arange(n_tr), n_bins),
            "x": start[:, 0], "y": start[:, 1],
            "heading_deg": np.degrees(np.asarray(res.heading).reshape(-1)),
            "placed": placed, "success": np.asarray(res.success).reshape(-1),
            "steps": np.asarray(res.steps).reshape(-1), "outcome": _outcome_names(np.asarray(res.outcome).reshape(-1)),
            **_rule_columns(res.rules, placed.size),
        })
    rules = rollouts.check_rules(args.first_move, args.collisions)
    write_rows_csv(args.out, [{"method": m, **row, **rules} for m, rows in tables.items() for row in rows])
    if args.trials_out:
        write_csv(args.trials_out, {k: np.concatenate([np.asarray(c[k], dtype=object) for c in trial_cols]).tolist()
                                    for k in trial_cols[0]})
    if args.summary:
        write_json(args.summary, {"env": env.name, "trials_per_bin": args.trials, "seed": args.seed,
                                  "rules": rules, "max_steps": args.max_steps, "home_radius": args.home_radius,
                                  "seconds": timing, "bins": tables})
    if args.plot:
        from .plots_rollouts import success_rate_figure

        fig = success_rate_figure(tables, title=f"success rate on {env.name} ({args.trials} trials per distance)")
        save_figure(fig, args.plot)
    print(f"wrote {args.out}" + "".join(f", {p}" for p in (args.trials_out, args.plot, args.summary) if p))
    return 0


# --- trajectories ----------------------------------------------------------------------------

def add_trajectories(sub) -> None:
    p = _rollout_parser(sub, "trajectories", "homing paths from chosen release points (docs/model.md §5; Figs 4.11, 5.8)",
                        "trajectory figure (one panel per method)",
                        "--method takes a comma-separated list (one panel each, same release points); --spacing is not used.")
    p.add_argument("--start", type=float, nargs=2, action="append", default=None, metavar=("X", "Y"),
                   help="a release point in cm (repeatable; default: --n-starts random points from --seed)")
    p.add_argument("--n-starts", type=int, default=6, help="random release points when no --start is given (default 6)")
    p.set_defaults(func=cmd_trajectories)


def cmd_trajectories(args: argparse.Namespace) -> int:
    from . import api
    from .cli import check_outputs, progress
    from .io import save_figure, write_csv, write_json

    check_outputs(args)
    methods = _methods(args.method)
    env = api.load_env(args.env)
    kw = _kwargs(args, drop=("spacing", "method"))
    kw.update(starts=args.start, n_starts=args.n_starts)
    results, cols = {}, []
    summary = {"env": env.name, "rules": rollouts.check_rules(args.first_move, args.collisions), "trials": {}}
    for m in methods:  # one program per method
        progress(f"trajectories of {m} on {env.name} ...")
        tr = rollouts.trajectories(env, method=m, **kw)
        results[m] = tr
        path = np.asarray(tr.path)
        steps = np.asarray(tr.steps)
        outcome = _outcome_names(tr.outcome)
        for t in range(path.shape[0]):  # a handful of paths: output formatting
            n = steps[t] + 1
            cols.append({"method": [m] * n, "trial": [t] * n, "step": list(range(n)),
                         "x": path[t, :n, 0], "y": path[t, :n, 1],
                         "release_heading_deg": [float(np.degrees(tr.heading[t]))] * n,
                         "success": [bool(tr.success[t])] * n, "steps": [int(steps[t])] * n,
                         "outcome": [outcome[t]] * n, **_rule_columns(tr.rules, n)})
        summary["trials"][m] = [{"start": np.asarray(tr.start[t]).tolist(),
                                 "release_heading_deg": float(np.degrees(tr.heading[t])),
                                 "outcome": outcome[t], "steps": int(steps[t])} for t in range(path.shape[0])]
        progress(f"{int(np.asarray(tr.success).sum())}/{path.shape[0]} reach home")
    write_csv(args.out, {k: [v for c in cols for v in np.asarray(c[k]).tolist()] for k in cols[0]})
    if args.summary:
        write_json(args.summary, summary)
    if args.plot:
        from .plots_rollouts import trajectories_figure

        save_figure(trajectories_figure(env, results, args.home_radius, title=f"homing trajectories on {env.name}"),
                    args.plot)
    print(f"wrote {args.out}" + "".join(f", {p}" for p in (args.plot, args.summary) if p))
    return 0


ROLLOUT_COMMANDS = [add_catchment, add_success_rate, add_trajectories]
