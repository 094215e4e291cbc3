"""The one error type for bad user input (files, flags, API arguments)."""

from __future__ import annotations


class InputError(ValueError):
    """Bad input, reported as one line that names the field and the value."""

    def __init__(self, field: str, value: object, expected: str):
        self.field, self.value, self.expected = field, value, expected
        super().__init__(f"{field}: {expected}, got {value!r}")
