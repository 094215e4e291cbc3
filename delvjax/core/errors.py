"""The one error type for bad user input (files, flags, API arguments), and the one-line warning."""

from __future__ import annotations

import difflib
import math
import sys
from collections.abc import Iterable


class InputError(ValueError):
    """Bad input, reported as one line that names the field and the value."""

    def __init__(self, field: str, value: object, expected: str, file_key: bool = False):
        """file_key: `field` is a key of an input file (an environment's arena), not a command-line option."""
        self.field, self.value, self.expected, self.file_key = field, value, expected, file_key
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


def did_you_mean(name: object, choices: Iterable[str]) -> str:
    """' (did you mean 'alv'?)' where one of `choices` is close to `name` (case, '_' for '-', a swapped or
    missing letter: "ALV", "delv_compass", "bearing_nosie_deg"), else ''."""
    if not isinstance(name, str):
        return ""
    choices = list(choices)
    fold = {c.lower().replace("_", "-"): c for c in choices}
    typed = name.strip().lower().replace("_", "-").replace(" ", "-")
    close = difflib.get_close_matches(typed, list(fold), n=1, cutoff=0.75)  # an exact match scores highest
    return f" (did you mean {fold[close[0]]!r}?)" if close else ""
