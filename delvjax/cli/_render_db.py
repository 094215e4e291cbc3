"""`delvjax images render-db`: a grid database of a colour world's panoramas (docs/images.md §4), or a grid or
route database of a mesh world (a generated habitat, or the user's world file and ant route: docs/mesh.md §7),
in BoB's layout. Every option is checked before any work; nothing is left at --out if it fails."""

from __future__ import annotations

import argparse
import time

from ..core.errors import InputError
from ..core.images import Catadioptric
from ..images._render import ImageSettings, camera, check_render, render_database
from ..mesh._database import KINDS, render_mesh_database
from ..mesh._site import given_files, is_mesh_name, mesh_site
from ..options._limits import MAX_POINTS
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_out_dir
from ._args import ProgressBar, progress, wrote

COLOUR_ONLY = {"donut": False, "pixel_noise": None, "gain_noise": None, "light_deg": None, "seed": None}


def add_render_db(isub) -> None:
    r = isub.add_parser("render-db", help="render a database of colour panoramas in the BoB layout")
    r.add_argument(
        "env",
        nargs="?",
        default=None,
        help="image world (robot, natural), preset, environment JSON file, or a generated mesh habitat (habitat<seed>)",
    )
    r.add_argument("--out", required=True, help="database folder (must not exist or be empty)")
    r.add_argument("--mesh", default=None, help="a mesh world file (.mat, .bin, .obj) instead of env (docs/mesh.md)")
    r.add_argument("--ant-route", default=None, help="with --mesh: the recorded route (AntRoutes.mat or a route .bin)")
    r.add_argument(
        "--route-name", default="Ant1_Route1", help="with an AntRoutes.mat: which route (default Ant1_Route1)"
    )
    r.add_argument(
        "--kind", default="grid", choices=KINDS, help="a mesh world: grid (about its route) or route (default grid)"
    )
    r.add_argument(
        "--spacing", type=float, default=None, help="grid spacing = unit move, cm (default: the world's; a route: 4)"
    )
    r.add_argument(
        "--colour", action="store_true", help="a mesh world: store the colours (default: the green channel, as gray)"
    )
    r.add_argument("--band", type=float, default=None, help="a mesh grid: cm about the route it covers (default 100)")
    r.add_argument("--cols", type=int, default=360, help="panorama width in pixels (default 360)")
    r.add_argument(
        "--rows", type=int, default=None, help="panorama height (default 60: 30 to -30 deg; a mesh world 76: 60 to -15)"
    )
    r.add_argument("--donut", action="store_true", help="store catadioptric (donut) images instead of panoramas")
    r.add_argument(
        "--pixel-noise", type=float, default=None, help="camera noise per pixel, of full scale (default 0.02)"
    )
    r.add_argument("--gain-noise", type=float, default=None, help="per-image brightness gain noise (default 0)")
    r.add_argument("--light-deg", type=float, default=None, help="light azimuth, deg (default: the world's, 45)")
    r.add_argument("--seed", type=int, default=None, help="seed of the camera noise (default 0)")
    r.add_argument("--max-points", type=int, default=MAX_POINTS, help="refuse more images than this")
    r.add_argument("--chunk", type=int, default=256, help="images rendered at a time (memory bound)")
    r.set_defaults(func=cmd_render_db)


def cmd_render_db(args: argparse.Namespace) -> int:
    check_out_dir(args.out)
    if args.mesh is not None or args.ant_route is not None or (args.env is not None and is_mesh_name(args.env)):
        return mesh_db(args)
    if args.env is None:
        raise InputError("env", None, "give a world (or --mesh and --ant-route)")
    if args.kind != "grid" or args.band is not None or args.colour:
        flag, value = next((f, v) for f, v, unset in (("--kind", args.kind, "grid"), ("--band", args.band, None),
                                                      ("--colour", args.colour, False)) if v != unset)  # fmt: skip
        raise InputError(flag, value, "applies to a mesh world (a colour world's database is a grid of its arena)")
    settings = ImageSettings(
        camera=camera(60 if args.rows is None else args.rows, args.cols),
        mirror=Catadioptric() if args.donut else None,
        pixel_noise=0.02 if args.pixel_noise is None else args.pixel_noise,
        gain_noise=0.0 if args.gain_noise is None else args.gain_noise,
        light_azimuth_deg=args.light_deg,
    )
    seed = 0 if args.seed is None else args.seed
    iw, spacing = check_render(args.env, args.spacing, settings, seed, args.max_points, args.chunk)
    t0 = time.perf_counter()
    progress(f"rendering {iw.name} every {spacing:g} cm into {args.out} ...")
    with ProgressBar("img", args.chunk) as bar:
        summary = render_database(args.env, args.out, spacing=spacing, settings=settings, seed=seed, chunk=args.chunk,
                                  max_points=args.max_points, progress=bar)  # fmt: skip
    progress(f"{summary['images']} images in {time.perf_counter() - t0:.2f} s")
    print(wrote(args.out))
    return 0


def mesh_db(args: argparse.Namespace) -> int:
    """A mesh world's database: options that only a colour world has are refused, then the world is read."""
    for name, unset in COLOUR_ONLY.items():
        if getattr(args, name) != unset:
            raise InputError(
                "--" + name.replace("_", "-"), getattr(args, name), "applies to a colour world, not a mesh"
            )
    check_no_clash(
        {"--out": args.out}, {f: v for f, v in (("--mesh", args.mesh), ("--ant-route", args.ant_route)) if v}
    )
    site = given_files(args.env, args.mesh, args.ant_route, args.route_name, "env") or mesh_site(args.env)
    t0 = time.perf_counter()
    progress(f"rendering a {args.kind} database of {site.name} into {args.out} ...")
    with ProgressBar("img", args.chunk) as bar:
        summary = render_mesh_database(site, args.out, kind=args.kind, spacing=args.spacing, band=args.band,
                                       colour=args.colour, rows=76 if args.rows is None else args.rows, cols=args.cols,
                                       chunk=args.chunk, max_points=args.max_points, progress=bar)  # fmt: skip
    progress(f"{summary['images']} images every {summary['spacing_cm']:g} cm in {time.perf_counter() - t0:.2f} s")
    print(wrote(args.out))
    return 0
