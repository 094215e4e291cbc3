"""Run configuration as objects (docs/model.md §5; docs/architecture.md "How a setting travels"):
`Rules` (how a rollout runs), beside `Grid` (core/grid.py: where a vector map or catchment is evaluated). Each field
is checked when the object is built (`InputError` naming the field and the value), so an object
that exists is valid; the API passes it unchanged to the core (`catchment_area`, `run_trials`, ...),
as diffrax passes its `SaveAt`. `legacy_config` keeps the flat keywords of earlier releases working
for one release, with a `DeprecationWarning`.

    delvjax.catchment("env1", DELV(heading=Compass()), sensor=Sensor(d=30), noise=Noise(bearing=0.02),
                      grid=Grid(spacing=50), rules=Rules(first_move="homing"), seed=0)
"""

from __future__ import annotations

import dataclasses
from typing import TypeVar

import equinox as eqx

from ..checks import choice, positive, positive_int
from ..deprecation import deprecated
from ..errors import InputError
from ..grid import Grid as Grid
from .rules import COLLISIONS, DEFAULT_FIRST_MOVE, DEFAULT_LANES, FIRST_MOVES, HOME_RADIUS, MAX_STEPS, rules_record


class Rules(eqx.Module):
    """The rollout rules of docs/model.md §5 (core/rollouts/rules.py): moves before a timeout
    (`max_steps`), the success radius (`home_radius`, cm), the first move ("release": thesis
    Algorithm 2, | "homing"), `collisions` ("ignore" | "fail"), and the trials advanced side by
    side (`lanes`: memory and speed, never the numbers)."""

    max_steps: int = eqx.field(default=MAX_STEPS, converter=lambda v: positive_int(v, "max_steps"))
    home_radius: float = eqx.field(default=HOME_RADIUS, converter=lambda v: positive(v, "home_radius"))
    first_move: str = eqx.field(
        default=DEFAULT_FIRST_MOVE, static=True, converter=lambda v: choice(v, "first_move", FIRST_MOVES)
    )
    collisions: str = eqx.field(default="ignore", static=True, converter=lambda v: choice(v, "collisions", COLLISIONS))
    lanes: int = eqx.field(default=DEFAULT_LANES, converter=lambda v: positive_int(v, "lanes"))

    @property
    def recorded(self) -> dict[str, str]:
        """The two rules every summary and table records (`rules.rules_record`)."""
        return rules_record(self.first_move, self.collisions)


GRID_FIELDS = tuple(f.name for f in dataclasses.fields(Grid))
RULES_FIELDS = tuple(f.name for f in dataclasses.fields(Rules))
C = TypeVar("C", Grid, Rules)


def legacy_config(kind: type[C], config: C | None, given: dict) -> C:
    """The object given (or `kind()`), or one built from the old flat keywords in `given` (those named like
    `kind`'s fields; popped from `given`) with a `DeprecationWarning` naming them: they work for one
    release. A keyword given beside the object that holds it is an `InputError` naming it."""
    name = kind.__name__.lower()
    fields = GRID_FIELDS if kind is Grid else RULES_FIELDS
    old = {k: given.pop(k) for k in fields if k in given}
    if config is not None and not isinstance(config, kind):
        raise InputError(name, config, f"must be a delvjax.{kind.__name__}")
    if not old:
        return kind() if config is None else config
    if config is not None:
        field = next(iter(old))
        raise InputError(field, old[field], f"cannot be combined with {name}= (set it on the {kind.__name__})")
    shown = ", ".join(f"{k}={v!r}" for k, v in old.items())
    deprecated(
        f"delvjax: the keyword{'s' if len(old) > 1 else ''} {', '.join(old)} {'are' if len(old) > 1 else 'is'} "
        f"deprecated and will be removed in the next release: pass {name}={kind.__name__}({shown})"
    )
    return kind(**old)
