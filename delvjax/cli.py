"""Command line: argument parsing and validation; calls the API. Exit 2 on bad input, no output file then."""

from __future__ import annotations

import argparse
import sys
import time
from typing import Callable


from . import api, maps
from .cache import enable_compilation_cache
from .config import BACKGROUNDS, CHANNELS
from .errors import InputError
from .io import check_output_path, save_figure, write_csv, write_json
from .methods import DESCRIPTIONS, METHODS
from .options import NOISE_FIELDS_DEG, NOISE_OPTIONS
from .scene import PRESET_DESCRIPTIONS, PRESETS

CSV = (".csv",)
FIGURE = (".png", ".pdf", ".svg")
JSON = (".json",)


def progress(msg: str) -> None:
    print(f"[delvjax] {msg}", file=sys.stderr, flush=True)


# --- shared argument groups ------------------------------------------------------------

def add_scene_args(p: argparse.ArgumentParser, methods=None) -> None:
    p.add_argument("env", help="preset name (see `delvjax envs`) or a docs/model.md §7 JSON file")
    p.add_argument("--method", default="delv", help=f"homing method: {', '.join(methods or METHODS)} (default delv)")
    p.add_argument("--levels", type=int, default=None, help="DELV distance quantization levels Q >= 1 (default: continuous)")
    p.add_argument("--d", type=float, default=50.0, help="unit-movement step d in cm (default 50)")
    p.add_argument("--spacing", type=float, default=25.0, help="grid spacing in cm (default 25: 40x40)")
    p.add_argument("--clearance", type=float, default=10.0, help="grid points closer than r + clearance to a landmark are dropped (default 10)")
    p.add_argument("--heading-deg", type=float, default=None, help="fixed heading at every point (default: random per point from --seed)")
    p.add_argument("--seed", type=int, default=0, help="seed of random headings and all noise (default 0)")
    p.add_argument("--background", default="distant", help=f"{', '.join(BACKGROUNDS)} (default distant)")
    p.add_argument("--channel", default="mask", help=f"image channel of holistic methods: {', '.join(CHANNELS)} (default mask)")
    p.add_argument("--n-heading", type=int, default=360, help="DELV heading hypotheses (default 360)")
    p.add_argument("--hide", type=int, nargs="+", default=None, metavar="I",
                   help="landmark indices invisible during homing (occlusion; the home record sees all)")
    w = p.add_argument_group("warping hypotheses (docs/model.md §4.3)")
    w.add_argument("--n-alpha", type=int, default=72, help="movement directions alpha (default 72: 5 deg steps)")
    w.add_argument("--n-psi", type=int, default=72, help="rotations psi, must divide 360 (default 72: 5 deg steps)")
    w.add_argument("--n-rho", type=int, default=15, help="values of rho = d/r (default 15)")
    w.add_argument("--rho-min", type=float, default=0.10, help="smallest rho (default 0.10)")
    w.add_argument("--rho-max", type=float, default=0.80, help="largest rho, < 1 (default 0.80)")
    w.add_argument("--mfdid-blur-deg", type=float, default=0.0, help="MFDID: Gaussian low-pass of both images, deg (default 0)")
    g = p.add_argument_group("noise (all default 0; angles in degrees)")
    for name in NOISE_OPTIONS:
        unit = "deg" if name in NOISE_FIELDS_DEG else "fraction of d"
        g.add_argument("--" + name.replace("_", "-"), type=float, default=0.0, dest=name, help=f"sigma ({unit})")


def scene_kwargs(args: argparse.Namespace) -> dict:
    kw = dict(method=args.method, levels=args.levels, d=args.d, spacing=args.spacing, clearance=args.clearance,
              heading_deg=args.heading_deg, seed=args.seed, background=args.background, channel=args.channel,
              n_heading=args.n_heading, hidden=args.hide, n_alpha=args.n_alpha, n_psi=args.n_psi, n_rho=args.n_rho,
              mfdid_blur_deg=args.mfdid_blur_deg,
              rho_min=args.rho_min, rho_max=args.rho_max)
    kw.update({name: getattr(args, name) for name in NOISE_OPTIONS if getattr(args, name) != 0.0})
    return kw


def add_output_args(p: argparse.ArgumentParser, plot_help: str) -> None:
    p.add_argument("--out", required=True, help="per-point CSV file")
    p.add_argument("--plot", default=None, help=plot_help + " (.png, .pdf or .svg)")
    p.add_argument("--summary", default=None, help="JSON file with the headline numbers")


def check_outputs(args: argparse.Namespace) -> None:
    check_output_path(args.out, "--out", CSV)
    if args.plot is not None:
        check_output_path(args.plot, "--plot", FIGURE)
    if args.summary is not None:
        check_output_path(args.summary, "--summary", JSON)


# --- commands ---------------------------------------------------------------------------

def cmd_envs(args: argparse.Namespace) -> int:
    for name in PRESETS:
        env = api.load_env(name)
        print(f"{name:7s} {env.n_landmarks} landmarks  {PRESET_DESCRIPTIONS[name]}")
    print("\nmethods:")
    for name, text in DESCRIPTIONS.items():
        print(f"  {name:13s} {text}")
    return 0


def add_vector_map(sub) -> None:
    p = sub.add_parser("vector-map", help="homing direction at every grid point (docs/model.md §5; Figs 4.2/4.3)")
    add_scene_args(p)
    add_output_args(p, "vector-map figure")
    p.add_argument("--classes", action="store_true", help="mark error classes < 45 / 45-90 / > 90 deg (Fig 4.3)")
    p.set_defaults(func=cmd_vector_map)


def cmd_vector_map(args: argparse.Namespace) -> int:
    from .metrics import summarize_map
    from .plots import vector_map_figure

    check_outputs(args)
    request = api.map_request(args.env, **scene_kwargs(args))
    env = request["env"]
    t0 = time.perf_counter()
    progress(f"vector map of {args.method} on {env.name} (spacing {args.spacing:g} cm) ...")
    vm = maps.vector_map(**request)
    vm.error_deg.block_until_ready()
    summary = {"env": env.name, "method": args.method, **summarize_map(vm.error_deg, vm.valid, vm.included),
               "seconds": time.perf_counter() - t0}
    progress(f"done in {summary['seconds']:.2f} s: {summary['points']} points, {summary['invalid']} invalid, "
             f"mean error {summary['mean_error_deg']:.2f} deg, >45: {summary['gt45_pct']:.2f} %, "
             f">90: {summary['gt90_pct']:.2f} %")
    write_csv(args.out, maps.vector_map_columns(vm))
    if args.summary:
        write_json(args.summary, summary)
    if args.plot:
        title = f"{args.method} on {env.name}: mean error {summary['mean_error_deg']:.1f}°"
        save_figure(vector_map_figure(env, vm, args.spacing, title=title, classes=args.classes), args.plot)
    print(f"wrote {args.out}" + (f", {args.plot}" if args.plot else "") + (f", {args.summary}" if args.summary else ""))
    return 0


def add_reproduce(sub) -> None:
    p = sub.add_parser("reproduce", help="every simulation study of the thesis, a report beside the thesis's numbers",
                       description="Run the thesis's studies (skipping those whose code and settings are unchanged) "
                                   "and write figures, CSV/JSON, report.md and report.html into --out.")
    p.add_argument("--quick", action="store_true", help="coarse 10 x 10 grid (spacing 100 cm): a preview in about a minute")
    p.add_argument("--out", default="results", help="output folder (default results/)")
    p.add_argument("--only", default=None, metavar="STUDY[,STUDY]", help="run only these studies")
    p.add_argument("--list", action="store_true", help="list the studies and exit")
    p.add_argument("--force", action="store_true", help="recompute even studies that are up to date")
    p.add_argument("--seed", type=int, default=0, help="seed of every random heading, release point and noise")
    p.set_defaults(func=cmd_reproduce)


def cmd_reproduce(args: argparse.Namespace) -> int:
    from . import reproduce

    if args.list:
        for name, module in reproduce.registry().items():
            print(f"{name:16s} {module.TITLE}")
        return 0
    reproduce.select(args.only)  # validate before any work
    reproduce.check_out_dir(args.out)
    t0 = time.perf_counter()
    result = reproduce.reproduce(args.out, quick=args.quick, only=args.only, force=args.force, seed=args.seed)
    skipped = [n for n in result["records"] if n not in result["ran"]]
    print(f"ran {len(result['ran'])} studies" + (f", {len(skipped)} unchanged (skipped)" if skipped else "")
          + f" in {time.perf_counter() - t0:.1f} s; report: {result['report']}")
    return 0


# Each entry adds one subcommand; a new command is one function here or in its own module.
COMMANDS: list[Callable] = [add_vector_map, add_reproduce]
from .cli_rollouts import ROLLOUT_COMMANDS  # noqa: E402  (catchment, success-rate, trajectories)

COMMANDS += ROLLOUT_COMMANDS


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="delvjax", description="Visual homing methods (DELV, ALV, ACV, ...) as JAX batch evaluators.")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("envs", help="list the built-in environments and methods").set_defaults(func=cmd_envs)
    for add in COMMANDS:
        add(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    enable_compilation_cache()
    try:
        return args.func(args)
    except InputError as exc:
        print(f"delvjax: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
