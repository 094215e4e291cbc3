"""How big a run may be: the number of grid points or trials is known before any work, so a run
too large for the machine is refused with an estimate instead of exhausting memory (docs/reproduce.md
"Large grids"). The limit is the user's to raise (`--max-points`, `max_points=`)."""

from __future__ import annotations

import math

import numpy as np

from ..core.errors import InputError
from ._checks import positive_int

MAX_POINTS = 1_000_000  # grid points (times masks) or trials in one run, by default
# host memory per item of the results and their CSV rows, bytes; slowest method per item on 2 CPU cores, s
BYTES = {"grid point": 120, "trial": 160, "path point": 40}
SECONDS = {"grid point": 50e-6, "trial": 1.5e-3, "path point": 1e-4, "move": 1.5e-5}
MOVES_PER_POINT = 100  # trials x (max_steps + 1) moves of a rollout run: at most this times max_points


def duration(seconds: float) -> str:
    """A time for a person: "40 s", "12 min", "2.5 h", "3.1 days" (never "0.0556 h")."""
    if seconds < 90:
        return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"
    if seconds < 90 * 60:
        return f"{seconds / 60:.0f} min"
    if seconds < 48 * 3600:
        return f"{seconds / 3600:.2g} h"
    return f"{seconds / 86400:.2g} days"


def check_moves(trials: int, max_steps: int, max_points) -> None:
    """`InputError` naming max_steps when `trials` rollouts of up to `max_steps` moves could run longer
    than MOVES_PER_POINT x max_points moves (the default: 1e8, about 25 minutes on 2 CPU cores)."""
    limit = MOVES_PER_POINT * positive_int(max_points, "max_points")
    moves = trials * (max_steps + 1)
    if moves > limit:
        raise InputError(
            "max_steps",
            max_steps,
            f"allows {moves:.3g} moves ({trials} trials x {max_steps + 1}), more than {MOVES_PER_POINT} x "
            f"max_points = {limit:.3g} (up to {duration(moves * SECONDS['move'])} on 2 CPU cores); lower --max-steps or raise --max-points",
        )


def grid_count(arena, spacing: float) -> int:
    """Number of cells of the docs/model.md §5 grid (at most one more per axis than `maps.grid_points`
    keeps), computed without building it."""
    xmin, ymin, xmax, ymax = (float(v) for v in np.asarray(arena))  # host numbers, also while jax traces
    nx = max(0, math.ceil((xmax - xmin - spacing / 2) / spacing))
    ny = max(0, math.ceil((ymax - ymin - spacing / 2) / spacing))
    return nx * ny


def check_size(count: int, max_points, field: str, value, what: str = "grid point") -> int:
    """`InputError` naming `field` when `count` items exceed `max_points`; the message estimates the
    memory and time such a run would need. Returns the validated limit."""
    limit = positive_int(max_points, "max_points")
    if count > limit:
        gb = count * BYTES[what] / 1e9
        raise InputError(
            field,
            value,
            f"gives {count:.3g} {what}s, more than max_points {limit} (about {gb:.3g} GB "
            f"of results and up to {duration(count * SECONDS[what])} on 2 CPU cores); use fewer or raise "
            f"--max-points",
        )
    return limit
