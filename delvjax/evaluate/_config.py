"""Config objects of the Python API (docs/model.md §5), beside the core's modules: `Grid` (where a
vector map or catchment is evaluated) and `Rules` (how a rollout runs). With the method module,
`Sensor` and `Noise` they describe a run as objects:

    delvjax.catchment("env1", DELV(heading=Compass()), sensor=Sensor(d=30), noise=Noise(bearing=0.02),
                      grid=Grid(spacing=50), rules=Rules(first_move="homing"), seed=0)

Each field is the keyword of the same name (`spacing=`, `first_move=`, ...), validated alike; a
keyword given beside the object that holds it is an error naming it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..core.errors import InputError
from ..core.maps import CLEARANCE, SPACING
from ..core.rollouts import DEFAULT_FIRST_MOVE, DEFAULT_LANES, HOME_RADIUS, MAX_STEPS


@dataclass(frozen=True)
class Grid:
    """The docs/model.md §5 grid: cell spacing and clearance from the landmarks (cm); a fixed heading
    at every point (degrees), or None for a random heading per point from the seed."""

    spacing: float = SPACING
    clearance: float = CLEARANCE
    heading_deg: float | None = None


@dataclass(frozen=True)
class Rules:
    """The rollout rules of docs/model.md §5: moves before a timeout, the success radius (cm), the
    first move ("release": thesis Algorithm 2, | "homing"), collisions ("ignore" | "fail"), and the
    trials advanced side by side (memory, not numbers)."""

    max_steps: int = MAX_STEPS
    home_radius: float = HOME_RADIUS
    first_move: str = DEFAULT_FIRST_MOVE
    collisions: str = "ignore"
    lanes: int = DEFAULT_LANES


GRID_DEFAULTS = dataclasses.asdict(Grid())
RULES_DEFAULTS = dataclasses.asdict(Rules())


def unpack(config, kind: type, given: dict, defaults: dict) -> dict:
    """The keywords of `kind`'s fields: from `config` when one is given (a keyword beside it that is not
    at its default is an error naming it), else from `given`."""
    if config is None:
        return given
    name = kind.__name__.lower()
    if not isinstance(config, kind):
        raise InputError(name, config, f"must be a delvjax.{kind.__name__}")
    for field, value in given.items():
        if value != defaults[field]:
            raise InputError(field, value, f"cannot be combined with {name}= (set it on the {kind.__name__})")
    return {field: getattr(config, field) for field in given}  # in the order of `given`
