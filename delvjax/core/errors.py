"""The one error type for bad user input (files, flags, API arguments), and the one-line warning."""

from __future__ import annotations

import math
import sys


class InputError(ValueError):
    """Bad input, reported as one line that names the field and the value."""

    def __init__(self, field: str, value: object, expected: str):
        self.field, self.value, self.expected = field, value, expected
        super().__init__(f"{field}: {expected}, got {value!r}")


def warn(msg: str) -> None:
    """One line on stderr for a result that is valid but probably not what was meant, or for work redone."""
    print(f"delvjax: warning: {msg}", file=sys.stderr, flush=True)


def is_finite_number(value: object) -> bool:
    """An int or float (not a bool) that is finite as a float: an int beyond float range (JSON, YAML and TOML
    allow any number of digits) is not, and is refused instead of raising OverflowError."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False
