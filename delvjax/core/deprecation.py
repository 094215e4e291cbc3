"""Deprecations that point at the user's line (CHANGELOG): an old keyword or an argument passed by
position keeps working for one release, with a `DeprecationWarning` that says what to write instead."""

from __future__ import annotations

import functools
import inspect
import sys
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TypeVar

PACKAGE = str(Path(__file__).resolve().parents[1])  # delvjax/
WRAPPERS = ("jaxtyping", "beartype", "typeguard")  # run-time type checks may wrap a call in frames of their own
F = TypeVar("F", bound=Callable)


def deprecated(message: str) -> None:
    """A `DeprecationWarning` at the user's line: the first frame outside delvjax and outside a type
    checker's wrappers (`warnings.warn_explicit`), however deep in delvjax the old form is read."""
    frame = sys._getframe(1)
    while frame.f_back is not None and (
        frame.f_code.co_filename.startswith((PACKAGE, "<@"))  # "<@beartype(...)": a type checker's wrapper
        or frame.f_globals.get("__name__", "").startswith(WRAPPERS)
    ):
        frame = frame.f_back
    warnings.warn_explicit(
        message,
        DeprecationWarning,
        frame.f_code.co_filename,
        frame.f_lineno,
        module=frame.f_globals.get("__name__"),
        registry=frame.f_globals.setdefault("__warningregistry__", {}),
    )


def renamed_keyword(legacy: dict, old: str, new: str, value, why: str = ""):
    """The value of the keyword `new`, or of its former name `old` popped from `legacy` (the caller's
    `**options`) with a `DeprecationWarning`; `TypeError` where both are given."""
    if old not in legacy:
        return value
    former = legacy.pop(old)
    if value is not None:
        raise TypeError(f"{old}= is the former name of {new}=, given too: give {new}= alone")
    deprecated(f"delvjax: {old}= is now {new}={f' ({why})' if why else ''}; {old}= goes next release")
    return former


def refuse_unknown(legacy: dict, call: str) -> None:
    """`TypeError` for the keywords left in `legacy` once the deprecated ones were read from it (`call`: the
    function given them), as Python's own for an unexpected keyword."""
    if legacy:
        raise TypeError(f"{call}() got unexpected keyword arguments {sorted(legacy)}")


BY_NAME = {"Grid": "grid", "Rules": "rules"}  # settings objects, by the keyword that takes them


def keywords_after(n: int, old_order: Sequence[str]) -> Callable[[F], F]:
    """Every argument after the first `n` is keyword-only; one passed by position in the order of
    earlier releases (`old_order`) still works for one release, named in a `DeprecationWarning`."""

    def wrap(fn: F) -> F:
        @functools.wraps(fn)
        def call(*args, **kwargs):
            if len(args) > n:
                extra = args[n:]
                if len(extra) > len(old_order):
                    raise TypeError(f"{fn.__name__}() takes {n + len(old_order)} positional arguments at most")
                params = inspect.signature(fn).parameters
                for value in extra:  # a settings object where an old positional number was: name the keyword
                    keyword = BY_NAME.get(type(value).__name__)
                    if keyword in params:
                        kind = type(value).__name__
                        raise TypeError(f"{fn.__name__}() takes a {kind} by name only: {keyword}={kind}(...)")
                given = dict(zip(old_order, extra))
                for name in given:
                    if name in kwargs:
                        raise TypeError(f"{fn.__name__}() got multiple values for argument {name!r}")
                deprecated(
                    f"delvjax: {fn.__name__}(): passing {', '.join(given)} by position is deprecated and will be "
                    f"an error in the next release: name {'them' if len(given) > 1 else 'it'} "
                    f"({', '.join(f'{k}=...' for k in given)})"
                )
                args, kwargs = args[:n], {**kwargs, **given}
            return fn(*args, **kwargs)

        call.__signature__ = inspect.signature(fn)  # type: ignore[attr-defined]
        return call  # type: ignore[return-value]

    return wrap
