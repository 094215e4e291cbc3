"""Calls compiled once per shape. A core function called eagerly compiles each primitive as its own
program (about 150 for one DELV match), and the suite is compile-bound: tests that call the core
outside a delvjax program go through `call` or `compiled`, which trace the whole call into one."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import equinox as eqx

F = TypeVar("F", bound=Callable)


@eqx.filter_jit
def call(f: Callable, *args, **kwargs):
    """`f(*args, **kwargs)` as one compiled program: arrays (in `f` too, e.g. a method module) are traced,
    everything else is static."""
    return f(*args, **kwargs)


def compiled(f: F) -> F:
    """`f`, compiled once per shape of its arguments (`equinox.filter_jit`)."""
    return eqx.filter_jit(f)
