"""What every homing method is (docs/model.md §3-4): an equinox module called on two unit moves.

    method(home: UnitMove, view: UnitMove) -> (angle, valid)

`home` is what was recorded at home (a unit move from home along alpha_r), `view` the unit
move that ended at the current point; `angle` is the homing direction in the agent's frame at
the end of that move (rad), `valid` False where it is undefined (then `angle` is NaN). A
method owns its settings: continuous ones are traced leaves (a sweep or a gradient reaches
them with `eqx.tree_at`), shapes and choices are static fields. Maps, rollouts and
sensitivity take the method as a pytree argument; nothing under jit looks a method up by name.
"""

from __future__ import annotations

import abc
from typing import Protocol, runtime_checkable

import equinox as eqx
from jax import Array

from ..sensing import UnitMove
from ..types import Direction


@runtime_checkable
class Method(Protocol):
    """The one signature of a homing method."""

    def __call__(self, home: UnitMove, view: UnitMove) -> Direction: ...


class HomingMethod(eqx.Module):
    """Base class of the methods: the protocol plus what the method reads, so that rendering it
    does not need is skipped (`sensing.computed_if`)."""

    @abc.abstractmethod
    def __call__(self, home: UnitMove, view: UnitMove) -> Direction:
        """Homing direction in the agent frame at the end of `view` (rad) and its validity."""

    def reads_start_view(self) -> bool | Array:
        """Whether the method reads the snapshot at the start of the current unit move
        (DELV's motion parallax, docs/model.md §3.1); most read only the current view."""
        return False

    def reads_image(self) -> bool | Array:
        """Whether the method reads the ring image of a view (`Snapshot.image`, either channel); the
        blob-reading methods do not, so their rollouts skip rendering it (`sensing.snapshot`)."""
        return False

    def reads_panorama(self) -> bool:
        """Whether the method reads the whole gray panorama of a view (`Snapshot.panorama`: MinWarping,
        2D-Warping, or a method whose heading source is MinWarping's compass); such a method runs on
        image databases and rendered worlds only."""
        return bool(getattr(getattr(self, "heading", None), "reads_panorama", False))

    def parts(self) -> dict[str, "HomingMethod"]:
        """The methods this one is made of, by field name (the hybrid's two); their settings are set
        through it (`options._registry.configure`)."""
        return {}

    def check_input(self, n_pix: int) -> None:
        """Raise `InputError` where the settings cannot serve views of `n_pix` columns (the edge calls
        it before any work): by default, those of its heading source."""
        heading = getattr(self, "heading", None)
        if heading is not None and hasattr(heading, "check_input"):
            heading.check_input(n_pix)

    def reads_gray(self, channel: str) -> bool | Array:
        """Whether the method reads the gray channel of the current view (docs/model.md §2.2)
        when the sensor's image channel is `channel`."""
        return False
