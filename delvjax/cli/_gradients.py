"""The commands of the differentiable path (docs/differentiable.md): `delvjax sensitivity`."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..core.errors import warn
from ..core.maps import SPACING
from ..envs._presets import env_to_dict
from ..evaluate._progress import OnStart
from ..gradients._layout import SEEDS, STEPS, optimise_layout, start_layout
from ..gradients._loss import TAU
from ..gradients._sensitivity import (
    RESOLVED_SE,
    SETTING_UNITS,
    check_sensitivity,
    sensitivity,
    sensitivity_profiles,
    unresolved_counts,
)
from ..gradients._sensitivity import SENSITIVITY_METHODS as METHODS
from ..gradients._smoothing import SAMPLES, SMOOTHING_CM, SMOOTHING_DEG
from ..gradients._traps import find_traps
from ..options._setup import NOISE_OPTIONS
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_out_dir, output_set
from ._args import ProgressBar, add_setting_args, progress, setting_values
from ._help import COMMAND_HELP


def add_sensitivity(sub) -> None:
    p = sub.add_parser(
        "sensitivity",
        help=COMMAND_HELP["sensitivity"],
        description="Gradients of the soft homing loss (mean 1 - cos angular error over the grid) "
        "smoothed at a stated scale (--smoothing-cm, --smoothing-deg), with respect to every "
        "landmark and to d, bearing, odometry and compass noise, for DELV, ALV and ACV, each "
        "with its standard error; central differences of the ordinary loss for warping. "
        "Writes two figures, two CSVs and sensitivity.json into --out.",
    )
    p.add_argument("env", help="preset name or environment JSON")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--methods", nargs="+", default=list(METHODS), help=f"among {', '.join(METHODS)} (default all)")
    p.add_argument("--spacing", type=float, default=SPACING, help=f"grid spacing, cm (default {SPACING:g})")
    p.add_argument("--seed", type=int, default=0, help="seed of headings and noise draws (default 0)")
    p.add_argument("--tau", type=float, default=TAU, help=f"softmin temperature of the soft methods (default {TAU:g})")
    p.add_argument(
        "--smoothing-cm",
        type=_scale,
        default=SMOOTHING_CM,
        help="scale of the sensitivity for landmark and home positions, radii, d and the quantization scale: "
        f"sigma of the Gaussian smoothing, cm, or 'none' for the gradient at the point (default {SMOOTHING_CM:g})",
    )
    p.add_argument(
        "--smoothing-deg",
        type=float,
        default=SMOOTHING_DEG,
        help=f"scale of the sensitivity for the noise sigmas, degrees (default {SMOOTHING_DEG:g})",
    )
    p.add_argument(
        "--samples",
        type=int,
        default=SAMPLES,
        help=f"draws of the smoothing, an even number (antithetic pairs; default {SAMPLES})",
    )
    p.add_argument(
        "--profile",
        action="store_true",
        help="also draw the loss along landmark 0's x at the point, 1 cm and --smoothing-cm, with the "
        "sensitivity as a tangent, per soft method (profile.png, profile.csv)",
    )
    p.set_defaults(func=cmd_sensitivity)


def _scale(text: str) -> float | None:
    """A smoothing scale on the command line: a number, or 'none'."""
    return None if text.strip().lower() == "none" else float(text)


def cmd_sensitivity(args: argparse.Namespace) -> int:
    from ..plots._gradients import (  # matplotlib: loaded only when a figure is drawn
        landmark_figure,
        parameter_figure,
        profile_figure,
    )

    out = check_out_dir(args.out)
    paths = [
        Path(out) / name
        for name in (
            "sensitivity_landmarks.png",
            "sensitivity_parameters.png",
            "landmarks.csv",
            "parameters.csv",
            "sensitivity.json",
        )
    ]
    if args.profile:
        paths += [Path(out) / "profile.png", Path(out) / "profile.csv"]
    check_no_clash({"--out": paths}, {"env": args.env})
    scale = {"smoothing_cm": args.smoothing_cm, "smoothing_deg": args.smoothing_deg, "samples": args.samples}
    env = check_sensitivity(args.env, args.methods, args.spacing, args.seed, args.tau, **scale)
    result = sensitivity(
        env,
        args.methods,
        spacing=args.spacing,
        seed=args.seed,
        tau=args.tau,
        **scale,
        progress=lambda m: progress(f"sensitivity of {m} on {env.name} ..."),
    )
    unresolved = unresolved_counts(result)
    summary = {
        "env": env.name,
        "spacing": args.spacing,
        "seed": args.seed,
        "tau": args.tau,
        "smoothing": scale,  # the scale every soft method's sensitivity holds at (docs/differentiable.md)
        "setting_units": SETTING_UNITS,  # d_loss_per_setting_unit: per cm of d, per degree of each sigma
        "methods": {
            m: {
                "loss": r["loss"],
                "how": r["how"],
                "d_loss_per_setting_unit": r["per_setting_unit"],
                "standard_error_per_setting_unit": {
                    row["parameter"]: row["standard_error"]
                    for row in result["parameter_rows"]
                    if row["method"] == m and row["standard_error"] != ""
                },
                # derivatives whose sign the draws leave open: |d| <= 2 standard errors (landmarks x, y, r and settings)
                "within_noise": None
                if m not in unresolved
                else {"count": unresolved[m][0], "of": unresolved[m][1], "rule": f"|d| <= {RESOLVED_SE:g} SE"},
            }
            for m, r in result["methods"].items()
        },
    }
    with output_set() as files:
        files.figure(landmark_figure(result), paths[0], "--out")
        files.figure(parameter_figure(result), paths[1], "--out")
        files.rows_csv(paths[2], result["landmark_rows"], "--out")
        files.rows_csv(paths[3], result["parameter_rows"], "--out")
        files.json(paths[4], summary, "--out")
        if args.profile:
            profiles = sensitivity_profiles(
                env, args.methods, spacing=args.spacing, seed=args.seed, tau=args.tau, **scale, progress=progress
            )
            files.figure(profile_figure(profiles), paths[5], "--out")
            files.rows_csv(paths[6], [dict(method=m, **r) for m, rows in profiles.items() for r in rows], "--out")
    for m, (k, n) in unresolved.items():
        if k:
            warn(
                f"{m}: {k} of {n} derivatives are within {RESOLVED_SE:g} standard errors of 0 at this scale "
                f"({args.samples} draws): their sign is not known (resolved_* = 0 in the CSVs); more --samples "
                "or a larger --smoothing-cm narrow them"
            )
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def add_traps(sub) -> None:
    p = sub.add_parser(
        "traps",
        help=COMMAND_HELP["traps"],
        description="Run the catchment, then root-find the zeros of the soft homing field from the end "
        "points of the timed-out rollouts, classify them from the Jacobian, and report how "
        "many failed rollouts end within --near cm of a sink. Writes traps.png, traps.csv "
        "and traps.json into --out.",
    )
    p.add_argument("env", help="preset name or environment JSON")
    p.add_argument("--method", default="delv", help="delv, delv-compass, alv or acv (default delv)")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--spacing", type=float, default=SPACING, help=f"grid spacing, cm (default {SPACING:g})")
    p.add_argument("--seed", type=int, default=0, help="seed of headings and noise (default 0)")
    p.add_argument("--tau", type=float, default=TAU, help=f"softmin temperature (default {TAU:g})")
    p.add_argument(
        "--near",
        type=float,
        default=None,
        help="a failed rollout ending this close to a sink counts as trapped, cm (default d)",
    )
    add_setting_args(p, only=("levels", "d", *NOISE_OPTIONS))
    p.set_defaults(func=cmd_traps)


def cmd_traps(args: argparse.Namespace) -> int:
    from ..plots._gradients import trap_figure  # matplotlib: loaded only when a figure is drawn

    out = check_out_dir(args.out)
    paths = [Path(out) / name for name in ("traps.png", "traps.csv", "traps.json")]
    check_no_clash({"--out": paths}, {"env": args.env})
    options = setting_values(args)
    report = find_traps(
        args.env,
        args.method,
        spacing=args.spacing,
        seed=args.seed,
        tau=args.tau,
        near=args.near,
        progress=OnStart(lambda: progress(f"catchment of {args.method} on {args.env}, then its trap points ...")),
        **options,
    )
    s = report.summary
    progress(
        f"{s['timed_out']} rollouts timed out; {s['sinks']} sink(s) besides home, {s['saddles']} saddle(s), "
        f"{s['discontinuities']} discontinuity point(s); {s['timed_out_within_near_of_a_sink']} timed-out "
        f"rollouts end within {s['near_cm']:g} cm of a sink"
    )
    with output_set() as files:
        files.figure(trap_figure(report, args.spacing), paths[0], "--out")
        files.rows_csv(paths[1], report.points, "--out")
        files.json(paths[2], {**s, "points": report.points}, "--out")
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def add_optimise_layout(sub) -> None:
    p = sub.add_parser(
        "optimise-layout",
        help=COMMAND_HELP["optimise-layout"],
        description="Optimise the landmark positions of ENV (or of --landmarks N seeded random ones) "
        "for a method on the soft loss smoothed at --smoothing-cm, with or without occlusion (the "
        "mean over every choice of --occlude hidden landmarks), then compare start and result by "
        "the hard loss and the ordinary catchment and error rates over --seeds seeds, saying "
        "whether each change is within the seed-to-seed spread. Writes layout.png, comparison.csv, optimised_env.json (an environment "
        "file) and layout.json into --out.",
    )
    p.add_argument("env", nargs="?", default=None, help="preset name or environment JSON (or use --landmarks)")
    p.add_argument("--landmarks", type=int, default=None, help="start from N seeded random landmarks instead")
    p.add_argument("--seed", type=int, default=0, help="seed of the random layout, headings and noise (default 0)")
    p.add_argument("--method", default="delv", help="delv, delv-compass, alv or acv (default delv)")
    p.add_argument("--occlude", type=int, default=0, help="optimise the mean over every choice of k hidden landmarks")
    p.add_argument("--steps", type=int, default=STEPS, help=f"BFGS steps at most (default {STEPS})")
    p.add_argument("--spacing", type=float, default=SPACING, help=f"grid of the comparison, cm (default {SPACING:g})")
    p.add_argument("--tau", type=float, default=TAU, help=f"softmin temperature (default {TAU:g})")
    p.add_argument(
        "--smoothing-cm",
        type=_scale,
        default=SMOOTHING_CM,
        help=f"optimise the soft loss smoothed at this scale, cm, or 'none' (default {SMOOTHING_CM:g})",
    )
    p.add_argument("--samples", type=int, default=SAMPLES, help=f"draws of the smoothing (default {SAMPLES})")
    p.add_argument(
        "--seeds",
        type=int,
        default=SEEDS,
        help=f"evaluation seeds of the hard comparison, from --seed on (default {SEEDS})",
    )
    p.add_argument("--out", required=True, help="output folder")
    p.set_defaults(func=cmd_optimise_layout)


def cmd_optimise_layout(args: argparse.Namespace) -> int:
    from ..plots._gradients import layout_figure  # matplotlib: loaded only when a figure is drawn

    out = check_out_dir(args.out)
    paths = [Path(out) / name for name in ("layout.png", "comparison.csv", "optimised_env.json", "layout.json")]
    check_no_clash({"--out": paths}, {"env": args.env})
    env = start_layout(args.env, args.landmarks, args.seed)
    line = f"optimising the {env.n_landmarks} landmarks of {env.name} for {args.method} ..."
    with ProgressBar("step", 0, lambda steps: line) as bar:
        result = optimise_layout(
            env,
            args.method,
            occlude=args.occlude,
            spacing=args.spacing,
            seed=args.seed,
            tau=args.tau,
            steps=args.steps,
            smoothing_cm=args.smoothing_cm,
            samples=args.samples,
            seeds=args.seeds,
            progress=bar,
        )
    start, end = result.rows
    progress(
        f"catchment {start['catchment_pct']:.1f} % -> {end['catchment_pct']:.1f} %, e>45° {start['gt45_pct']:.1f} % "
        f"-> {end['gt45_pct']:.1f} %, hard loss {start['hard_loss']:.4f} -> {end['hard_loss']:.4f} "
        f"(means over {args.seeds} seeds; {len(result.objective) - 1} steps, {result.seconds:.1f} s)"
    )
    for name, v in result.verdict.items():
        progress(f"  {name}: change {v['change']:+.4g} (SE {v['se']:.2g}): {v['reading']}")
    with output_set() as files:
        files.figure(layout_figure(result, args.spacing), paths[0], "--out")
        files.rows_csv(paths[1], result.rows, "--out")
        files.json(paths[2], env_to_dict(result.optimised), "--out")
        files.json(
            paths[3],
            {
                "method": args.method,
                "occlude": result.occlude,
                "seconds": result.seconds,
                "objective": result.objective,
                "smoothing_cm": args.smoothing_cm,
                "samples": args.samples,
                "rows": result.rows,
                "per_seed": result.per_seed,
                "verdict": result.verdict,
                "start_env": env_to_dict(result.start),
                "optimised_env": env_to_dict(result.optimised),
            },
            "--out",
        )
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


GRADIENT_COMMANDS = [add_sensitivity, add_traps, add_optimise_layout]
