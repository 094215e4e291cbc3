"""CLI for image databases (docs/images.md): `images render-db`, `images import`, and the `--images`
mode of `vector-map` and `catchment`. Every option is checked before any work; bad input (a
missing or unreadable image, a position outside the arena: the message names the file) -> exit 2,
no output file."""

from __future__ import annotations

import argparse
import time

import numpy as np

from ..core.checks import non_negative, positive_int
from ..core.errors import InputError
from ..core.images.rollouts import OUTCOMES
from ..core.metrics import summarize_map
from ..core.rollouts import check_rules
from ..core.tables import vector_map_columns
from ..evaluate._vector_map import refuse_rollout_only
from ..images._conventions import CHOICES
from ..images._evaluate import catchment_numbers, database_catchment, database_vector_map
from ..images._import import import_database
from ..images._load import load_database
from ..options._schema import extractor_options, method_options, sensor_options
from ..options._setup import make_setup
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_out_dir
from ._args import ProgressBar, check_outputs, progress, warn, write_outputs, wrote
from ._help import COMMAND_HELP
from ._render_db import add_render_db

# scene options that mean nothing for a database (its images fix the scene, the poses and the unit move)
# the scene's options that a database replaces: the sensor's settings but the channel (the motion noise of a
# rollout aside), and the grid and occlusion options
UNUSED_WITH_IMAGES = (
    *(n for n in sensor_options() if n != "channel" and not n.startswith("motion_")),
    "clearance",
    "heading_deg",
    "hide",
    "occlude",
)


def add_image_args(p: argparse.ArgumentParser) -> None:
    """--images and the options that read a database (docs/images.md §4-5)."""
    g = p.add_argument_group("image database (docs/images.md): evaluate on images instead of an environment")
    g.add_argument(
        "--images",
        default=None,
        metavar="DIR",
        help="a BoB database or a folder of panoramas with positions.csv; replaces the environment, "
        "--spacing then sets the unit move (default: the database's spacing)",
    )
    g.add_argument(
        "--home",
        type=float,
        nargs=2,
        default=None,
        metavar=("X", "Y"),
        help="home in cm (default: the metadata's, else a route's last image or the image nearest the arena centre)",
    )
    g.add_argument(
        "--arena",
        type=float,
        nargs=4,
        default=None,
        metavar=("XMIN", "YMIN", "XMAX", "YMAX"),
        help="arena in cm (default: the metadata, else the extent of the positions)",
    )
    add_extractor_args(g)
    add_reading_args(g)
    g.add_argument("--chunk", type=int, default=256, help="images read and reduced at a time (memory bound)")
    only = {a.dest: a.option_strings[0] for a in g._group_actions if a.dest != "images"}
    p.set_defaults(parser_defaults={a.dest: a.default for a in p._actions}, image_only=only)


def refuse_image_options(args: argparse.Namespace) -> None:
    """`InputError` naming the first option of the --images group given without --images: it would be
    ignored, while a summary recorded it (a --home that moved nothing)."""
    for dest, flag in getattr(args, "image_only", {}).items():
        if getattr(args, dest) != args.parser_defaults.get(dest):
            raise InputError(
                flag, getattr(args, dest), "is used only with --images (it sets how an image database is read)"
            )


def add_extractor_args(g) -> None:
    """The extractor's settings, from their declaration on `Extractor` (docs/images.md §5; the default
    is the metadata's, else the declared one)."""
    for opt in extractor_options().values():
        g.add_argument(
            opt.flag,
            type=opt.type,
            default=None,
            metavar="N" if opt.type is int else "X",
            help=opt.help.replace("(default", "(default: the metadata's, else"),
        )


def add_reading_args(g) -> None:
    """How a database's headings, columns and camera are read where its metadata does not say (§4.1-4.2)."""
    for name, (key, allowed, flag) in CHOICES.items():
        g.add_argument(
            flag,
            dest=name if name != "columns" else "column_order",
            choices=allowed,
            default=None,
            help=f"where the metadata does not declare {key}: {' or '.join(allowed)} (docs/images.md §4.1)",
        )
    g.add_argument(
        "--elevation",
        type=float,
        nargs=2,
        default=None,
        metavar=("TOP", "BOTTOM"),
        help="elevation of the top and bottom image edges, deg (default: the metadata's; BoB's opengl: 60 -15)",
    )
    g.add_argument("--camera-height", type=float, default=None, help="camera height, cm (default: metadata, else Z)")


def reading_options(args: argparse.Namespace) -> dict:
    """load_database's conventions, elevation and camera_height from the flags of `add_reading_args`."""
    conv = {"heading": args.heading, "heading_column": args.heading_column, "columns": args.column_order}
    return {"conventions": conv, "elevation": args.elevation, "camera_height": args.camera_height}


def _refuse_unused(args: argparse.Namespace, extra=()) -> None:
    defaults = args.parser_defaults
    for dest in (*UNUSED_WITH_IMAGES, *extra):
        if hasattr(args, dest) and getattr(args, dest) != defaults.get(dest):
            raise InputError("--" + dest.replace("_", "-"), getattr(args, dest), "is not used with --images")
    args.not_applied = (*UNUSED_WITH_IMAGES, *extra)  # left out of the settings a summary records (d, n_pix, ...)
    if args.env is not None:
        raise InputError("env", args.env, "cannot be combined with --images (the database is the scene)")


def _method_options(args: argparse.Namespace) -> dict:
    names = (*method_options(), "channel")
    return {k: getattr(args, k) for k in names if getattr(args, k, None) is not None}


def load(args: argparse.Namespace):
    """The database of --images with the reading options, after every option is checked."""
    opts = _method_options(args)
    module, _ = make_setup(args.method, panorama_cols=0, **opts)  # checked before any image is read
    positive_int(args.chunk, "--chunk")
    if args.max_blobs is not None:
        positive_int(args.max_blobs, "--max-blobs")
    progress(f"reading {args.images} ...")
    spacing = None if args.spacing == args.parser_defaults.get("spacing") else args.spacing
    ex = {k: getattr(args, k) for k in extractor_options() if k != "max_blobs" and getattr(args, k) is not None}

    def check(n_images: int, n_pix: int) -> None:  # from the index and the first image, before the others
        if n_images > args.max_points:
            raise InputError(
                "--images", args.images, f"has {n_images} images, more than --max-points {args.max_points}"
            )
        make_setup(args.method, n_pix=n_pix, panorama_cols=n_pix, **opts)  # e.g. n_psi must divide the width

    with ProgressBar("img", args.chunk) as bar:
        db = load_database(
            args.images,
            home=args.home,
            arena=args.arena,
            spacing=spacing,
            channel=args.channel,
            extractor=ex,
            max_blobs=args.max_blobs,
            chunk=args.chunk,
            progress=bar,
            check=check,
            warn=warn,
            panoramas=module.reads_panorama(),
            **reading_options(args),
        )
    args.spacing = db.spacing  # what ran, as the summary's command_settings records it: the database's unit move
    return db, opts


def warn_empty(vm) -> None:
    """A warning for a map with nothing to evaluate, or no valid direction anywhere."""
    included = np.asarray(vm.included)
    if not included.any():
        warn("the database has no point besides home: nothing to evaluate")
    elif not bool(np.any(np.asarray(vm.valid) & included)):
        warn(
            "every database point is invalid: the method finds no homing direction anywhere (no landmark "
            "found by the threshold, or no neighbour one spacing away?)"
        )


def cmd_vector_map_images(args: argparse.Namespace) -> int:
    from ..plots._images import database_map_figure  # matplotlib: loaded only when a figure is drawn

    _refuse_unused(args)
    refuse_rollout_only({n: getattr(args, n, None) for n in ("motion_heading_noise_deg", "motion_step_noise")})
    check_outputs(args)
    t0 = time.perf_counter()
    db, opts = load(args)
    progress(
        f"vector map of {args.method} on {len(db.files)} images ({db.camera.cols} x {db.camera.rows}, "
        f"unit move {db.spacing:g} cm) ..."
    )
    vm = database_vector_map(db, args.method, warn=warn, **opts)
    summary = {
        "images": args.images,
        "method": args.method,
        "home": db.absolute(db.home).tolist(),
        "spacing_cm": db.spacing,
        **summarize_map(vm.error_deg, vm.valid, vm.included),
        "seconds": time.perf_counter() - t0,
    }
    progress(
        f"done in {summary['seconds']:.2f} s: mean error {summary['mean_error_deg']:.2f} deg, "
        f"{summary['invalid']} invalid"
    )
    warn_empty(vm)
    columns = vector_map_columns(vm)
    if db.origin.any():  # the database's own coordinates (docs/images.md §4)
        columns["x"], columns["y"] = (np.asarray(columns[k], np.float64) + db.origin[i] for i, k in enumerate("xy"))
    write_outputs(
        args,
        columns,
        summary,
        lambda: database_map_figure(
            db, vm, f"{args.method} on {db.name}: mean error {summary['mean_error_deg']:.1f}°", classes=args.classes
        ),
    )
    return 0


def cmd_catchment_images(args: argparse.Namespace) -> int:
    from ..plots._images import database_catchment_figure  # matplotlib: loaded only when a figure is drawn

    _refuse_unused(args, extra=("lanes",))
    check_rules(args.first_move, args.collisions)
    positive_int(args.max_steps, "--max-steps")
    motion = {
        n: 0.0 if getattr(args, n) is None else getattr(args, n)  # a setting flag's default is None
        for n in ("motion_heading_noise_deg", "motion_step_noise")
    }
    for name, value in (("home_radius", args.home_radius), *motion.items()):
        non_negative(value, "--" + name.replace("_", "-"))
    if args.first_move != args.parser_defaults.get("first_move", args.first_move):
        raise InputError(
            "--first-move",
            args.first_move,
            "is not used with --images (every move follows the direction at the nearest snapshot)",
        )
    check_outputs(args)
    t0 = time.perf_counter()
    db, opts = load(args)
    radius = None if args.home_radius == args.parser_defaults.get("home_radius") else args.home_radius
    vm = database_vector_map(db, args.method, warn=warn, **opts)
    warn_empty(vm)
    starts, paths = database_catchment(
        db,
        vm,
        home_radius=radius,
        max_steps=args.max_steps,
        **motion,
        seed=args.seed,
        collisions=args.collisions == "fail",
    )

    summary = {
        "images": args.images,
        "method": args.method,
        **catchment_numbers(paths),
        "home_radius_cm": db.spacing if radius is None else radius,
        "step_cm": db.spacing,
        "collisions": args.collisions,
        "seconds": time.perf_counter() - t0,
    }
    progress(
        f"done in {summary['seconds']:.2f} s: catchment {summary['catchment_pct']:.2f} % of "
        f"{summary['releases']} releases"
    )
    code = np.asarray(paths.outcome)
    columns = {
        "x": starts[:, 0] + db.origin[0] if db.origin.any() else starts[:, 0],  # the database's own coordinates
        "y": starts[:, 1] + db.origin[1] if db.origin.any() else starts[:, 1],
        "outcome": [OUTCOMES[c] for c in code],
        "steps": np.asarray(paths.steps),
    }
    write_outputs(
        args,
        columns,
        summary,
        lambda: database_catchment_figure(
            db, vm, starts, paths, f"{args.method} on {db.name}: catchment {summary['catchment_pct']:.1f} %"
        ),
    )
    return 0


# --- images render-db / import ------------------------------------------------------------------


def add_images(sub) -> None:
    p = sub.add_parser("images", help=COMMAND_HELP["images"])
    isub = p.add_subparsers(dest="images_command", required=True)
    add_render_db(isub)
    i = isub.add_parser("import", help="check a database (BoB, or panoramas + positions.csv) and write it as BoB")
    i.add_argument("src", help="database folder")
    i.add_argument("--out", required=True, help="new database folder (must not exist or be empty)")
    i.add_argument("--home", type=float, nargs=2, default=None, metavar=("X", "Y"), help="home, cm")
    i.add_argument(
        "--arena", type=float, nargs=4, default=None, metavar=("XMIN", "YMIN", "XMAX", "YMAX"), help="arena, cm"
    )
    i.add_argument("--spacing", type=float, default=None, help="grid spacing = unit move, cm")
    add_reading_args(i)
    i.set_defaults(func=cmd_import)


def cmd_import(args: argparse.Namespace) -> int:
    check_out_dir(args.out)
    check_no_clash({"--out": args.out}, {"src": args.src})
    t0 = time.perf_counter()
    db = import_database(
        args.src, args.out, home=args.home, arena=args.arena, spacing=args.spacing, warn=warn, **reading_options(args)
    )
    blobs = np.asarray(db.rings.snapshots.valid).sum(-1)
    home = db.absolute(db.home)
    progress(
        f"{len(db.files)} {db.kind} images in {time.perf_counter() - t0:.2f} s; landmark blobs per image: min "
        f"{blobs.min()}, mean {blobs.mean():.2f}, max {blobs.max()}; home ({home[0]:g}, {home[1]:g}), "
        f"spacing {db.spacing:g} cm"
    )
    if (blobs == 0).any():
        empty = [db.files[i].name for i in np.flatnonzero(blobs == 0)]
        warn(
            f"{len(empty)} of {len(blobs)} images show no landmark blob ({', '.join(empty[:3])}"
            f"{', ...' if len(empty) > 3 else ''}): check the hue window (--hue-deg, --hue-width-deg) and the band"
        )
    print(wrote(args.out))
    return 0


IMAGE_COMMANDS = [add_images]
