"""Every option a user sets, generated from the settings declared on the modules
(`core/settings.py`; docs/architecture.md "Settings"): the method settings of every registered
method (and of a method module passed in), the `Sensor`'s and the `Noise`'s. The CLI flags and
their help, the validation and its messages, the sweep axes and docs/options.md are all made
from these `Option`s, so a setting is written once, on its field.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ..core import checks
from ..core.deprecation import deprecated
from ..core.errors import InputError
from ..core.images.pipeline import Extractor
from ..core.methods import HomingMethod, MethodSet
from ..core.sensor import Noise, Sensor
from ..core.settings import Setting, declared
from ._registry import METHODS

ROLLOUT_ONLY = ("motion_",)  # settings that act only in rollouts (the motion noise): a vector map refuses them

SENSOR_TYPES = (Sensor, Noise)


@dataclass(frozen=True)
class Declaration:
    """One module class's declaration of an option: the class, its field, its `Setting`, the default."""

    owner: type
    field: str
    setting: Setting
    default: Any


@dataclass(frozen=True)
class Option:
    """A public option: its name (API keyword and sweep axis; the flag is `--name-with-dashes`) and
    the declarations of the module classes that have it. A name means one thing: several methods may
    declare it (`n_alpha`: Warping, MinWarping, Warping2D), each with its own check and default, and
    a value is checked by the declaration of each method it sets (`validate(value, owner)`)."""

    name: str
    declarations: tuple[Declaration, ...]

    @property
    def owners(self) -> tuple[type, ...]:
        return tuple(d.owner for d in self.declarations)

    def declaration(self, owner: type | None = None) -> Declaration:
        """`owner`'s declaration (None: the first; a subclass: its base's)."""
        for d in self.declarations:
            if owner is None or issubclass(owner, d.owner):
                return d
        raise KeyError(f"{owner.__name__} has no option {self.name!r}")

    @property
    def field(self) -> str:
        return self.declarations[0].field

    @property
    def setting(self) -> Setting:
        return self.declarations[0].setting

    @property
    def default(self) -> Any:
        return self.declarations[0].default

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")

    @property
    def type(self) -> type:
        """What argparse and a sweep file's values are: int, float or str (the same for every owner)."""
        return _value_type(self.setting)

    def variants(self) -> list[tuple[tuple[type, ...], Declaration]]:
        """The distinct declarations (check, help, unit, default) and the classes that share each."""
        out: dict[tuple, list] = {}
        for d in self.declarations:
            key = (dataclasses.replace(d.setting, formerly=None), repr(d.default))  # the old names differ
            out.setdefault(key, [(), d])[0] += (d.owner,)
        return [(owners, d) for owners, d in out.values()]

    @property
    def shown_default(self) -> str:
        return _shown_default(self.declarations[0])

    @property
    def help(self) -> str:
        """One line: the owners (for a method setting), what it is, its unit, its choices and default;
        each owner's where their declarations differ."""
        if self.owners[0] in SENSOR_TYPES:
            return _help(self.declarations[0])
        return "; ".join(f"{'/'.join(t.__name__ for t in owners)}: {_help(d)}" for owners, d in self.variants())

    def validate(self, value: Any, owner: type | None = None) -> Any:
        """The field's value for a public `value` under `owner`'s declaration (None: every owner's,
        the strictest), or `InputError` naming the option."""
        chosen = self.declarations if owner is None else (self.declaration(owner),)
        return [_validate(self.name, d.setting, value) for d in chosen][0]


def _value_type(s: Setting) -> type:
    return {"positive_int": int, "choice": str}.get(s.check, float)


def _shown_default(d: Declaration) -> str:
    s = d.setting
    if s.shown_default is not None:
        return s.shown_default
    return f"{d.default:g}" if isinstance(d.default, float) else str(d.default)


def _help(d: Declaration) -> str:
    s = d.setting
    unit = f", {s.unit}" if s.unit else ""
    choices = f": {', '.join(s.choices)}" if s.choices else ""
    return f"{s.help}{unit}{choices} (default {_shown_default(d)})"


def _validate(name: str, s: Setting, value: Any) -> Any:
    v = checks.CHECKS[s.check](value, name) if s.check != "choice" else checks.choice(value, name, s.choices)
    if s.limit is not None and v > s.limit:
        raise InputError(name, value, f"must be <= {s.limit} (it sets an array size)")
    return s.to_field(v) if s.to_field is not None else v


@functools.lru_cache(maxsize=64)
def _options(types: tuple[type, ...]) -> dict[str, Option]:
    """The options of these module classes (cached per set of classes: callers must not change it). A
    name several classes declare is one option if its values are of one type and convert alike (a
    developer's error otherwise: `TypeError`)."""
    found: dict[str, list[Declaration]] = {}
    for t in types:
        for name, (field, setting, default) in declared(t).items():
            found.setdefault(name, []).append(Declaration(t, field, setting, default))
    out = {}
    for name, decls in found.items():
        # a subclass inherits its base's settings: name the base only (DELV, not DELVGap and DELVRefined)
        kept = tuple(
            d for d in decls if not any(d.owner is not b.owner and issubclass(d.owner, b.owner) for b in decls)
        )
        if len({(_value_type(d.setting), d.setting.to_field, d.setting.unit) for d in kept}) > 1:
            raise TypeError(f"option {name!r} is declared with different types, units or conversions by {kept}")
        out[name] = Option(name, kept)
    return out


def renamed() -> dict[str, str]:
    """Former option name -> today's (`Setting.formerly`: `mw_n_alpha` -> `n_alpha`), of every
    registered method."""
    return {
        d.setting.formerly: name
        for name, opt in method_options().items()
        for d in opt.declarations
        if d.setting.formerly
    }


def method_types(extra: Iterable[HomingMethod] = ()) -> tuple[type, ...]:
    """The classes of the registered methods and of `extra` modules (a `MethodSet`'s members), once each."""
    out: dict[type, None] = {}
    for m in (*METHODS.values(), *extra):
        for member in m.methods if isinstance(m, MethodSet) else (m,):
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


def upgraded(options: dict, where: str = "option") -> dict:
    """`options` with every former name (`mw_n_alpha`) read as today's (`n_alpha`), with one
    `DeprecationWarning` saying what to write; `InputError` where both are given (or two former names of
    one option). `where`: what the names are, for the messages ("option", "sweep axis")."""
    old = renamed()
    found = [k for k in options if k in old]
    if not found:
        return options
    out = {k: v for k, v in options.items() if k not in found}
    for k in found:
        new = old[k]
        if new in out:
            raise InputError(k, options[k], f"is the former name of the {where} {new!r}, given too: give {new!r} alone")
        out[new] = options[k]
    changes = ", ".join(f"{k!r} is now {old[k]!r}" for k in found)
    deprecated(f"delvjax: the former {where} names go next release: {changes} (one name for every method that has it)")
    return out
