"""Argument groups shared by the CLI commands (`_main.py`, `_rollouts.py`, `_sweep.py`, ...). The method
and sensor flags, their help and defaults are made from the settings declared on the modules
(`options._schema`), so they are written once."""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Callable
from pathlib import Path

from ..core.errors import InputError, warn  # noqa: F401 - warn: the commands import it from here
from ..core.maps import CLEARANCE, SPACING
from ..core.rollouts import DEFAULT_FIRST_MOVE, DEFAULT_LANES, HOME_RADIUS, MAX_STEPS, Grid, Rules
from ..core.sensor import Noise, Sensor
from ..evaluate._progress import Progress
from ..options._limits import MAX_POINTS
from ..options._registry import METHODS, declaring, owns, reads_compass
from ..options._schema import method_options, renamed, sensor_options
from ..outputs._clashes import check_no_clash
from ..outputs._files import check_distinct, check_output_path, output_set

CSV = (".csv",)
FIGURE = (".png", ".pdf", ".svg")
JSON = (".json",)


def wrote(*paths) -> str:
    """The closing line of a command: the files it wrote."""
    return "wrote " + ", ".join(str(p) for p in paths if p)


def progress(msg: str) -> None:
    print(f"[delvjax] {msg}", file=sys.stderr, flush=True)


def compiling(k: int, m: int) -> str:
    """The phase of a run whose next call compiles program k of m (or loads it from the cache)."""
    return f"compiling program {k} of {m} (cached for later runs)"


class ProgressBar(Progress):
    """The command line's `Progress` (evaluate/_progress.py): a bar on stderr with rate and ETA once the
    work runs in more than one chunk (`total` > `single`); nothing for a run of one chunk. `start(total,
    phase)` (the API calls it once every option is valid) prints `announce(total)` when given (the
    command's line: "vector map of ... (1600 cells) ...") and shows the bar at once (the whole run,
    compilation included) with what is happening now (`phase`, else `first_phase`: "compiling program 1
    of 2"); `phase(text)` changes it; a run of one chunk prints the phases as lines."""

    def __init__(
        self,
        unit: str,
        single: int,
        announce: Callable[[int | None], str] | None = None,
        first_phase: str | None = None,
    ):
        self.unit, self.single, self.bar = unit, single, None
        self.announce, self.first_phase = announce, first_phase
        self._phase: str | None = None

    def _open(self, total: int) -> None:
        from tqdm.auto import tqdm  # tqdm: loaded only when a progress bar is shown

        self.bar = tqdm(  # integer counts ("3/18 cell", "65536/250000 pt"), never "0.00/250k"
            total=total, unit=self.unit, file=sys.stderr, disable=total <= self.single
        )
        if self._phase:
            self.phase(self._phase)

    def start(self, total: int | None, phase: str | None = None) -> None:
        """Print the announcement and show the bar now, before the first chunk (whose call compiles the
        program); with `total` None the bar opens at the first chunk's report."""
        if self.announce is not None:
            progress(self.announce(total))
        self._phase = phase if phase is not None else self.first_phase
        if self.bar is None and total is not None:
            self._open(total)

    def phase(self, text: str) -> None:
        """What the run does now: the bar's description, or a line when the run has no bar; nothing
        before `start` (input checks print nothing: bad input is one line)."""
        self._phase = text
        if self.bar is None:
            return
        if not self.bar.disable:
            self.bar.set_description_str(text, refresh=True)
        elif text:
            progress(f"{text} ...")

    def __call__(self, done: int, total: int) -> None:
        if self.bar is None:
            self._open(total)
        if self._phase and self._phase.startswith("compiling") and not self.bar.disable:
            self.phase("running")  # the first chunk is back: its program is compiled
        self.bar.update(done)

    def __enter__(self) -> "ProgressBar":
        return self

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.close()


def add_scene_args(p: argparse.ArgumentParser, methods=None, grid: bool = True, images: bool = False) -> None:
    """The scene, method and noise options; `grid`: the command evaluates a grid (--spacing); `images`:
    it can run on an image database instead (`_images.add_image_args`; the environment is optional).
    The method and sensor flags are made from the settings declared on the modules (`add_setting_args`)."""
    p.add_argument(
        "env",
        nargs="?" if images else None,
        default=None,
        help="preset name (see `delvjax envs`) or a docs/model.md §7 JSON file"
        + (" (or --images DIR)" if images else ""),
    )
    p.add_argument("--method", default="delv", help=f"homing method: {', '.join(methods or METHODS)} (default delv)")
    if grid:
        p.add_argument(
            "--spacing", type=float, default=SPACING, help=f"grid spacing in cm (default {SPACING:g}: 40x40)"
        )
    else:  # not offered; recognized only to refuse it in one line naming it (`scene_kwargs`)
        p.add_argument("--spacing", type=float, default=None, dest="unused_spacing", help=argparse.SUPPRESS)
    p.add_argument(
        "--clearance",
        type=float,
        default=CLEARANCE,
        help=f"grid points closer than r + clearance to a landmark are dropped (default {CLEARANCE:g})",
    )
    p.add_argument(
        "--heading-deg",
        type=float,
        default=None,
        help="fixed heading at every point (default: random per point from --seed)",
    )
    p.add_argument("--seed", type=int, default=0, help="seed of random headings and all noise (default 0)")
    p.add_argument(
        "--max-points",
        type=int,
        default=MAX_POINTS,
        help=f"refuse a run of more grid points (x occlusion masks) or trials than this, with an estimate "
        f"of its memory and time (default {MAX_POINTS})",
    )
    p.add_argument(
        "--hide",
        type=int,
        nargs="+",
        default=None,
        metavar="I",
        help="landmark indices invisible during homing (occlusion; the home record sees all)",
    )
    add_setting_args(p)


def add_setting_args(p: argparse.ArgumentParser, only: tuple[str, ...] | None = None) -> None:
    """A flag per declared setting (`options._schema`): the sensor's, the methods' (grouped by the
    module classes that have them) and the noise sigmas; `only`: just these option names."""
    groups: dict[str, argparse._ArgumentGroup] = {}
    noise = "noise: standard deviations, all default 0, all drawn from --seed (docs/model.md §2.5)"
    for opt in {**sensor_options(), **method_options()}.values():
        if only is not None and opt.name not in only:
            continue
        title = noise if opt.owners[0] is Noise else None if opt.owners[0] is Sensor else _group_title(opt.owners)
        target = p if title is None else groups.setdefault(title, p.add_argument_group(title))
        target.add_argument(opt.flag, type=opt.type, default=None, dest=opt.name, help=opt.help)
    added = {**sensor_options(), **method_options()} if only is None else {n: None for n in only}
    for former, name in renamed().items():  # the flags of earlier releases (--n-alpha), hidden
        if name in added:
            opt = method_options()[name]
            p.add_argument(
                "--" + former.replace("_", "-"), type=opt.type, dest=name, action=FormerFlag, help=argparse.SUPPRESS
            )


class FormerFlag(argparse.Action):
    """A flag renamed in this release (`--n-alpha` -> `--n-alpha`): still read, with a line on stderr."""

    def __call__(self, parser, namespace, values, option_string=None):
        new = "--" + self.dest.replace("_", "-")
        warn(f"{option_string} is now {new}; {option_string} goes next release")
        setattr(namespace, self.dest, values)


def _group_title(owners: tuple[type, ...]) -> str:
    """ "MFDID (docs/model.md §4.5)": the module classes and the docs section their docstring names."""
    ref = re.search(r"docs/[\w.]+ §[\d.]+", owners[0].__doc__ or "")
    return "/".join(t.__name__ for t in owners) + (f" ({ref.group(0)})" if ref else " settings")


def setting_values(args: argparse.Namespace) -> dict:
    """The settings given on the command line (flags of `add_setting_args`), by option name."""
    names = (*sensor_options(), *method_options())
    return {name: getattr(args, name) for name in names if getattr(args, name, None) is not None}


def scene_kwargs(args: argparse.Namespace) -> dict:
    if getattr(args, "unused_spacing", None) is not None:
        raise InputError("--spacing", args.unused_spacing, f"is not used by {args.command} (it evaluates no grid)")
    spacing = {"spacing": args.spacing} if hasattr(args, "spacing") else {}
    kw = dict(
        method=args.method,
        grid=Grid(**spacing, clearance=args.clearance, heading_deg=args.heading_deg),
        seed=args.seed,
        hidden=args.hide,
        max_points=args.max_points,
    )
    kw.update(setting_values(args))
    check_compass_read(args.method, kw.get("compass_noise_deg"))
    return kw


def check_compass_read(method: str, compass_noise_deg: float | None) -> None:
    """`InputError` for --compass-noise-deg given to methods none of which reads a compass (it would change
    nothing while a summary recorded it); `method`: a name or comma-separated names."""
    modules = [METHODS.get(name.strip()) for name in str(method).split(",") if name.strip()]
    if compass_noise_deg is None or not modules or None in modules or any(reads_compass(m) for m in modules):
        return  # an unknown name is refused where the method is made
    readers = ", ".join(name for name, m in METHODS.items() if reads_compass(m))
    raise InputError(
        "--compass-noise-deg", compass_noise_deg, f"is read only by methods with a compass ({readers}), not by {method}"
    )


def add_output_args(p: argparse.ArgumentParser, plot_help: str) -> None:
    p.add_argument("--out", default=None, help="per-point CSV file (at least one of --out, --plot, --summary)")
    p.add_argument("--plot", default=None, help=plot_help + " (.png, .pdf or .svg)")
    p.add_argument("--summary", default=None, help="JSON file with the headline numbers")


OUTPUTS = (
    ("out", "--out", CSV),
    ("trials_out", "--trials-out", CSV),
    ("plot", "--plot", FIGURE),
    ("summary", "--summary", JSON),
)  # attribute, option, suffixes of every output option


def check_outputs(args: argparse.Namespace) -> None:
    """Validate every output path before any work (`outputs._files.check_output_path`; no two the same file, none
    the environment file); at least one output must be asked for; an environment (or --images)."""
    if args.env is None and getattr(args, "images", None) is None:
        raise InputError("env", None, "give an environment (preset name or JSON file) or --images DIR")
    named = {flag: getattr(args, name) for name, flag, _ in OUTPUTS if getattr(args, name, None) is not None}
    if not any(named.values()):
        raise InputError("--out", None, "no output asked for (give --out, --plot or --summary)")
    for name, flag, suffixes in OUTPUTS:
        if flag in named:
            check_output_path(named[flag], flag, suffixes)
    check_distinct(named)
    check_no_clash(named, {"env": args.env if args.env and Path(args.env).is_file() else None, **image_input(args)})


def image_input(args: argparse.Namespace) -> dict:
    """The image database a command reads ({"--images": folder}), if any: an input no output may touch."""
    return {"--images": args.images} if getattr(args, "images", None) else {}


NOT_SETTINGS = {"out", "trials_out", "summary", "plot", "func", "command", "images_command", "defaults", "not_applied"}


def command_settings(args: argparse.Namespace) -> dict:
    """Every option the command ran with (the ones given and the defaults), outputs left out: recorded in the
    summary JSON and, where not the default, under the figure (issue 53 point 3)."""
    plain = (str, int, float, bool, type(None))
    sensor, methods = sensor_options(), method_options()
    chosen = METHODS.get(getattr(args, "method", None)) if isinstance(getattr(args, "method", None), str) else None
    settings = {}
    unused = set(getattr(args, "not_applied", ()))  # options the input replaces (an image database's d, n_pix)
    for k, v in sorted(vars(args).items()):
        if k in NOT_SETTINGS or k in unused or callable(v):
            continue
        if v is None:  # not given: the sensor's default, or the method's where the method has the setting
            if k in sensor:  # a choice stored as its index (background 0) is recorded by its name ("distant")
                choices, v = sensor[k].setting.choices, sensor[k].default
                v = choices[v] if choices and isinstance(v, int) and not isinstance(v, bool) else v
            elif k in methods and chosen is not None and owns(chosen, k):  # the chosen method's default, as its
                d = methods[k].declaration(declaring(chosen, k)[0])  # help shows it (levels: "continuous", not 0)
                v = d.default if d.setting.shown_default is None else d.setting.shown_default
            else:
                continue  # an option of another method or of image input: does not apply
        if isinstance(v, (list, tuple)) and all(isinstance(x, plain) for x in v):
            settings[k] = list(v)
        elif isinstance(v, plain):
            settings[k] = v
    return settings


def changed_settings(args: argparse.Namespace) -> str:
    """The options given other than their defaults, "bearing_noise_deg = 2.0, d = 20.0" (env and method, in every
    figure's title already, left out)."""
    defaults = getattr(args, "defaults", {})
    given = {k: v for k, v in vars(args).items() if k in defaults and v != defaults[k] and k not in NOT_SETTINGS}
    shown = command_settings(args)
    return ", ".join(f"{k} = {shown[k]}" for k in sorted(given) if k in shown and k not in ("env", "method", "methods"))


def write_outputs(args: argparse.Namespace, columns, summary: dict, figure, trials_columns=None) -> None:
    """Write the outputs asked for as a unit (`outputs._files.output_set`), then the closing line: --out (a dict of
    columns or a list of row dicts), --trials-out, --summary (with every setting the command ran with), --plot
    (`figure()` is built only then, with the settings that are not the defaults under it)."""
    trials_out = getattr(args, "trials_out", None)
    with output_set() as files:  # all or nothing
        if args.out:
            (files.rows_csv if isinstance(columns, list) else files.csv)(args.out, columns, "--out")
        if trials_out:
            files.csv(trials_out, trials_columns, "--trials-out")
        if args.summary:
            files.json(args.summary, {**summary, "command_settings": command_settings(args)}, "--summary")
        if args.plot:
            fig, changed = figure(), changed_settings(args)
            titled = [ax for ax in fig.axes if ax.get_title()]
            if changed and titled:  # under the first panel's title: the settings that are not the defaults
                titled[0].set_title(f"{titled[0].get_title()}\n{changed}", fontsize=8)
            files.figure(fig, args.plot, "--plot")
    print(wrote(args.out, trials_out, args.plot, args.summary))


def add_rollout_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("rollouts (docs/model.md §5)")
    g.add_argument(
        "--max-steps", type=int, default=MAX_STEPS, help=f"moves allowed to reach home (default {MAX_STEPS})"
    )
    g.add_argument(
        "--home-radius",
        type=float,
        default=HOME_RADIUS,
        help=f"success within this distance of home, cm (default {HOME_RADIUS:g})",
    )
    g.add_argument(
        "--lanes",
        type=int,
        default=DEFAULT_LANES,
        help=f"trials advanced side by side (memory bound; default {DEFAULT_LANES})",
    )
    g.add_argument(
        "--first-move",
        default=DEFAULT_FIRST_MOVE,
        metavar="RULE",
        help="release (default, thesis Algorithm 2): a method that needs a unit movement (DELV) first "
        "moves d along the release heading, then matches; the catchment counts grid points at least "
        "d from every wall; homing: every method's first move follows the direction computed at the "
        "release point, as in the vector map",
    )
    g.add_argument(
        "--collisions",
        default="ignore",
        metavar="RULE",
        help="ignore (default): landmarks are no obstacles; fail: a move ending inside a landmark fails",
    )


def rollout_kwargs(args: argparse.Namespace, drop=()) -> dict:
    """`scene_kwargs` plus the rollout `Rules`, validated before any work or progress line."""
    kw = scene_kwargs(args)
    for name in drop:
        kw.pop(name, None)
    kw["rules"] = Rules(
        max_steps=args.max_steps,
        home_radius=args.home_radius,
        first_move=args.first_move,
        collisions=args.collisions,
        lanes=args.lanes,
    )
    return kw
