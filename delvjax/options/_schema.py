"""Every option a user sets, generated from the settings declared on the modules
(`core/settings.py`; docs/architecture.md "Settings"): the method settings of every registered
method (and of a method module passed in), the `Sensor`'s and the `Noise`'s. The CLI flags and
their help, the validation and its messages, the sweep axes and docs/options.md are all made
from these `Option`s, so a setting is written once, on its field.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ..core import checks
from ..core.errors import InputError
from ..core.images.pipeline import Extractor
from ..core.methods import HomingMethod, Program
from ..core.sensor import Noise, Sensor
from ..core.settings import Setting, declared
from ._registry import METHODS

ROLLOUT_ONLY = ("motion_",)  # settings that act only in rollouts (the motion noise): a vector map refuses them

SENSOR_TYPES = (Sensor, Noise)


@dataclass(frozen=True)
class Option:
    """A public option: its name (API keyword and sweep axis; the flag is `--name-with-dashes`),
    the field it sets, its declaration, the field's default and the module classes that have it."""

    name: str
    field: str
    setting: Setting
    default: Any
    owners: tuple[type, ...]

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")

    @property
    def type(self) -> type:
        """What argparse and a sweep file's values are: int, float or str."""
        return {"positive_int": int, "choice": str}.get(self.setting.check, float)

    @property
    def shown_default(self) -> str:
        s = self.setting
        return (
            s.shown_default
            if s.shown_default is not None
            else f"{self.default:g}"
            if isinstance(self.default, float)
            else str(self.default)
        )

    @property
    def help(self) -> str:
        """One line: the owners (for a method setting), what it is, its unit, its choices and default."""
        s = self.setting
        owners = "" if self.owners[0] in SENSOR_TYPES else "/".join(t.__name__ for t in self.owners) + ": "
        unit = f", {s.unit}" if s.unit else ""
        choices = f": {', '.join(s.choices)}" if s.choices else ""
        return f"{owners}{s.help}{unit}{choices} (default {self.shown_default})"

    def validate(self, value: Any) -> Any:
        """The field's value for a public `value`, or `InputError` naming the option."""
        s = self.setting
        v = (
            checks.CHECKS[s.check](value, self.name)
            if s.check != "choice"
            else checks.choice(value, self.name, s.choices)
        )
        if s.limit is not None and v > s.limit:
            raise InputError(self.name, value, f"must be <= {s.limit} (it sets an array size)")
        return s.to_field(v) if s.to_field is not None else v


@functools.lru_cache(maxsize=64)
def _options(types: tuple[type, ...]) -> dict[str, Option]:
    """The options of these module classes (cached per set of classes: callers must not change it)."""
    found: dict[str, list] = {}
    for t in types:
        for name, (field, setting, default) in declared(t).items():
            found.setdefault(name, [field, setting, default, []])[3].append(t)
    # a subclass inherits its base's settings: name the base only (DELV, not DELVGap and DELVRefined)
    return {
        name: Option(
            name, f, s, d, tuple(t for t in owners if not any(t is not b and issubclass(t, b) for b in owners))
        )
        for name, (f, s, d, owners) in found.items()
    }


def method_types(extra: Iterable[HomingMethod] = ()) -> tuple[type, ...]:
    """The classes of the registered methods and of `extra` modules (a `Program`'s members), once each."""
    out: dict[type, None] = {}
    for m in (*METHODS.values(), *extra):
        for member in m.methods if isinstance(m, Program) else (m,):
            out.setdefault(type(member), None)
    return tuple(out)


def method_options(extra: Iterable[HomingMethod] = ()) -> dict[str, Option]:
    """The method settings of every registered method (read now: a method registered later counts)."""
    return _options(method_types(extra))


def sensor_options() -> dict[str, Option]:
    """The settings of the `Sensor` and its `Noise`."""
    return _options(SENSOR_TYPES)


def extractor_options() -> dict[str, Option]:
    """The settings of the image pipeline's `Extractor` (docs/images.md §5): options of `--images` only."""
    return _options((Extractor,))


def all_options(extra: Iterable[HomingMethod] = ()) -> dict[str, Option]:
    return {**method_options(extra), **sensor_options()}
