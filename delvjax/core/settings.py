"""What a user may set on a module, declared once on the field it configures (docs/architecture.md
"Settings"): the public option name, its check, unit, help and, for a public unit that differs
from the field's, the conversion. The edge generates the CLI flags, their help and validation,
the sweep axes and the docs' option table from these declarations; the core only reads the
fields.

    class MyMethod(HomingMethod):
        gain: float = setting(1.0, help="how strongly it turns", check="positive")
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import equinox as eqx

CHECKS = ("finite", "positive", "non_negative", "positive_int", "unit_interval", "angle_deg", "choice")


@dataclass(frozen=True)
class Setting:
    """help: one line for `--help` and the docs; check: one of CHECKS (`unit_interval`: 0 < x < 1;
    `angle_deg`: any finite angle, reduced into (-360, 360)); unit: the public unit ("cm", "deg");
    option: the public name where it is not the field's; limit: the largest value of a setting that
    sizes an array; choices: the allowed names (`choice`); to_field: public value -> field value
    (degrees -> radians); shown_default: the default as the help prints it, where the field's is
    not what a user types; formerly: the option's name before it lost its method prefix (`mw_n_alpha`
    for MinWarping's `n_alpha`), still read for one release with a DeprecationWarning (docs/options.md
    "Renamed options")."""

    help: str
    check: str = "finite"
    unit: str = ""
    option: str | None = None
    limit: int | None = None
    choices: tuple[str, ...] = ()
    to_field: Callable[[Any], Any] | None = None
    shown_default: str | None = None
    formerly: str | None = None

    def __post_init__(self):
        if self.check not in CHECKS:
            raise ValueError(f"Setting.check must be one of {CHECKS}, got {self.check!r}")


def setting(default: Any, *, static: bool = False, converter: Callable | None = None, **meta: Any) -> Any:
    """An `eqx.field` with its `Setting` in the field's metadata (the one declaration of an option)."""
    kwargs: dict[str, Any] = {"default": default, "static": static, "metadata": {"setting": Setting(**meta)}}
    if converter is not None:
        kwargs["converter"] = converter
    return eqx.field(**kwargs)


def declared(module_type: type) -> dict[str, tuple[str, Setting, Any]]:
    """option name -> (field name, Setting, field default) of every declared setting of a module class."""
    out = {}
    for f in dataclasses.fields(module_type):
        s = f.metadata.get("setting")
        if s is not None:
            out[s.option or f.name] = (f.name, s, f.default)
    return out


def radians(value: Any) -> Any:
    """Degrees -> radians: `math.radians` for a number (exact as before), a product for a traced one."""
    return math.radians(value) if isinstance(value, (int, float)) else value * (math.pi / 180.0)
