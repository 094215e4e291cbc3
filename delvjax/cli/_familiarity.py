"""`delvjax familiarity`: a familiarity model trained on a route through a colour or mesh world (docs/mesh.md §6),
then its heading field, route-following trials and catchment areas (docs/familiarity.md §3). Every option is
checked before any work; exit 2 on bad input, nothing written."""

from __future__ import annotations

import argparse
import time

from ..core.errors import InputError, warn
from ..familiarity._models import MODELS, SETTINGS, model_settings
from ..familiarity._run import database_experiments, route_experiments
from ..images._load import load_database
from ..images._worlds import BUILT_IN
from ..mesh._site import given_files
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_distinct, check_output_path, output_set
from ._args import CSV, FIGURE, JSON, wrote
from ._help import COMMAND_HELP

OUTPUTS = (("out", "--out", CSV), ("trials_out", "--trials-out", CSV), ("catchments_out", "--catchments-out", CSV),
           ("ridf_out", "--ridf-out", CSV), ("summary", "--summary", JSON), ("plot", "--plot", FIGURE))  # fmt: skip
MODEL_FLAGS = {k: v for s in SETTINGS.values() for k, v in s.items()}  # every model setting, as a flag


def waypoints(text: str) -> list[float]:
    """'x,y x,y ...' -> [x, y, x, y, ...] (checked later, naming --route)."""
    try:
        return [float(v) for pair in text.split() for v in pair.split(",")]
    except ValueError:
        raise InputError("--route", text, "must be waypoints 'x,y x,y ...' in cm") from None


def add_familiarity(sub) -> None:
    p = sub.add_parser("familiarity", help=COMMAND_HELP["familiarity"])
    p.add_argument(
        "world",
        nargs="?",
        default=None,
        help=f"a colour world ({', '.join(BUILT_IN)}), an environment, or a generated mesh habitat (habitat, "
        "habitat<seed>; docs/mesh.md) (default robot)",
    )
    p.add_argument(
        "--mesh", default=None, help="a mesh world file (.mat, .bin, .obj: the Seville world) instead of a world"
    )
    p.add_argument("--ant-route", default=None, help="with --mesh: the recorded route (AntRoutes.mat or a route .bin)")
    p.add_argument(
        "--route-name", default="Ant1_Route1", help="with an AntRoutes.mat: which route (default Ant1_Route1)"
    )
    p.add_argument(
        "--images", default=None, help="a route image database (BoB's layout) to train on, instead of a world"
    )
    p.add_argument(
        "--test-images",
        default=None,
        help="with --images: a database whose images are tested (default: the route's odd images)",
    )
    p.add_argument("--model", default="perfect-memory", help=f"one of {', '.join(MODELS)} (default perfect-memory)")
    p.add_argument(
        "--route",
        default=None,
        help="waypoints 'x,y x,y ...' cm (default: a bent route from the arena's corner to home)",
    )
    p.add_argument("--route-spacing", type=float, default=4.0, help="cm between route images (default 4)")
    p.add_argument("--view-rows", type=int, default=None, help="rows of a view (default 10; 19 in a mesh world)")
    p.add_argument("--view-cols", type=int, default=90, help="columns of a view, dividing 360 (default 90)")
    p.add_argument("--grid-spacing", type=float, default=None, help="heading-field grid, cm (default: the world's)")
    p.add_argument("--trials", type=int, default=20, help="route-following trials (default 20)")
    p.add_argument(
        "--heading-noise-deg", type=float, default=10.0, help="N(0, sigma) added to every turn, deg (default 10)"
    )
    p.add_argument("--step", type=float, default=None, help="cm a move (default: the route spacing)")
    p.add_argument("--max-steps", type=int, default=None, help="moves allowed (default: 2.1 route lengths)")
    p.add_argument("--seed", type=int, default=0, help="trial noise, InfoMax weights, mushroom-body wiring (default 0)")
    g = p.add_argument_group("model settings (docs/familiarity.md §2; each applies to its model only)")
    for k, v in MODEL_FLAGS.items():
        kind = type(v) if v is not None else int
        g.add_argument("--" + k.replace("_", "-"), type=kind, default=None, help=f"default {v}")
    p.add_argument("--out", default=None, help="heading field CSV, one row per grid point")
    p.add_argument("--trials-out", default=None, help="route-following trials CSV")
    p.add_argument("--catchments-out", default=None, help="catchment areas along the route CSV")
    p.add_argument(
        "--ridf-out", default=None, help="RIDF CSV: the unfamiliarity of every heading at every field point (long form)"
    )
    p.add_argument("--summary", default=None, help="JSON file with the headline numbers and every setting")
    p.add_argument("--plot", default=None, help="figure (.png, .pdf or .svg)")
    p.set_defaults(func=cmd_familiarity)


def cmd_familiarity(args: argparse.Namespace) -> int:
    named = {flag: getattr(args, name) for name, flag, _ in OUTPUTS if getattr(args, name) is not None}
    if not named:
        raise InputError(
            "--out",
            None,
            "no output asked for (give --out, --trials-out, --catchments-out, --ridf-out, --summary or --plot)",
        )
    for name, flag, suffixes in OUTPUTS:
        if flag in named:
            check_output_path(named[flag], flag, suffixes)
    check_distinct(named)
    inputs = {f: getattr(args, k) for k, f in (("images", "--images"), ("test_images", "--test-images"),
                                               ("mesh", "--mesh"), ("ant_route", "--ant-route"))}  # fmt: skip
    check_no_clash(named, {f: v for f, v in inputs.items() if v is not None})
    given = {k: getattr(args, k) for k in MODEL_FLAGS if getattr(args, k) is not None}
    applies = SETTINGS.get(args.model, {})
    for k in given:
        if k not in applies:
            raise InputError("--" + k.replace("_", "-"), given[k], f"is no setting of {args.model}")
    t0 = time.perf_counter()
    result = on_databases(args, given) if args.images is not None else in_world(args, given)
    summary = {**result.summary(), "seconds": round(time.perf_counter() - t0, 2)}
    with output_set() as files:  # all or nothing
        if args.out:
            files.csv(args.out, result.field_columns(), "--out")
        if args.trials_out:
            files.csv(args.trials_out, result.trial_columns(), "--trials-out")
        if args.catchments_out:
            files.csv(args.catchments_out, result.catchment_columns(), "--catchments-out")
        if args.ridf_out:
            files.csv(args.ridf_out, result.ridf_columns(), "--ridf-out")
        if args.summary:
            files.json(args.summary, summary, "--summary")
        if args.plot:
            from ..plots._familiarity import familiarity_figure  # matplotlib: loaded only when a figure is drawn

            files.figure(familiarity_figure(result), args.plot, "--plot")
    print(headline(summary))
    print(wrote(*named.values()))
    return 0


def in_world(args: argparse.Namespace, given: dict):
    """The route experiments in a colour world or a mesh world."""
    if args.test_images is not None:
        raise InputError("--test-images", args.test_images, "applies with --images only")
    model_settings(args.model, **given)  # checked before any file is read
    world = given_files(args.world, args.mesh, args.ant_route, args.route_name) or args.world or "robot"
    return route_experiments(
        world, args.model, route=None if args.route is None else waypoints(args.route),
        route_spacing=args.route_spacing, view_rows=args.view_rows, view_cols=args.view_cols,
        grid_spacing=args.grid_spacing, trials=args.trials, heading_noise_deg=args.heading_noise_deg,
        step=args.step, max_steps=args.max_steps, seed=args.seed, progress=lambda s: print(s, flush=True), **given,
    )  # fmt: skip


def on_databases(args: argparse.Namespace, given: dict):
    """The route experiments on a route database (and a test database)."""
    if args.world is not None or args.mesh is not None:
        raise InputError("world", args.world or args.mesh, "give a world, --mesh or --images, not more than one")
    for flag in ("route", "grid_spacing", "step", "max_steps"):
        if getattr(args, flag) is not None:
            raise InputError("--" + flag.replace("_", "-"), getattr(args, flag), "applies to a world, not to --images")
    model_settings(args.model, **given)  # checked before any image is read
    print(f"reading {args.images} ...", flush=True)
    route_db = load_database(args.images, panoramas=True, warn=warn)
    test_db = None if args.test_images is None else load_database(args.test_images, panoramas=True, warn=warn)
    return database_experiments(
        route_db, args.model, test_db=test_db, view_rows=10 if args.view_rows is None else args.view_rows,
        view_cols=args.view_cols, seed=args.seed,
        trials=args.trials, heading_noise_deg=args.heading_noise_deg,
        progress=lambda s: print(s, flush=True), **given,
    )  # fmt: skip


def headline(s: dict) -> str:
    """The closing summary line."""
    near = s["median_error_deg_near_route"]
    tail = (
        f"heading error near the route {near:.1f} deg (median)" if near is not None else "no test point near the route"
    )
    if s["trials"] == 0:
        return f"{s['world']} {s['model']}: {s['field_points']} test images, {tail}"
    ci = s["success_ci95_pct"]
    return (f"{s['world']} {s['model']}: success {s['success_pct']:.0f} % of {s['trials']} trials "
            f"(95 % CI {ci[0]:.0f}-{ci[1]:.0f}), {s['mean_route_errors']:.2f} returns to the route a trial; {tail}")  # fmt: skip


FAMILIARITY_COMMANDS = [add_familiarity]
