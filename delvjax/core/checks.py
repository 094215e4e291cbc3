"""The checks of user input: each returns the validated value or raises `InputError` naming the
field and the value (before any array work). A number traced by `jax.jit`, `jax.grad` or
`jax.vmap` has no value yet: it is checked inside the computation instead (`equinox.error_if`,
the same message)."""

from __future__ import annotations

import math
import numbers

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..core.errors import InputError
from ..core.types import Real


def is_traced(value: object) -> bool:
    """A number inside `jax.jit`, `jax.grad` or `jax.vmap`: checked in the computation, not here."""
    return isinstance(value, jax.core.Tracer)


def _traced_check(value: jax.Array, bad: jax.Array, field: str, expected: str) -> jax.Array:
    """`value`, raising at run time with `InputError`'s wording where `bad` holds (equinox.error_if)."""
    return eqx.error_if(value, bad, f"{field}: {expected} (a traced value)")


def finite(value: object, field: str) -> Real:
    """`value` as a finite float, else `InputError` (a traced value: checked at run time)."""
    if is_traced(value):
        return _traced_check(value, ~jnp.isfinite(value), field, "must be finite")
    if isinstance(value, bool):
        raise InputError(field, value, "must be a number")
    try:
        v = float(value)  # type: ignore[arg-type]
    except OverflowError:  # an int beyond float range
        v = math.inf
    except (TypeError, ValueError):
        raise InputError(field, value, "must be a number") from None
    if not math.isfinite(v):
        raise InputError(field, value, "must be finite")
    return v


F32_MAX = 3.4028234663852886e38  # the largest float32: JAX computes in float32 (no x64)


def in_float32(value: object, field: str) -> Real:
    """A finite number that float32 can hold (not an angle: those are reduced first, `angle_deg`)."""
    v = finite(value, field)
    if not is_traced(v) and abs(v) > F32_MAX:
        raise InputError(field, value, f"is beyond float32's range ({F32_MAX:.3g}), the precision of the computation")
    return v


def positive(value: object, field: str) -> Real:
    v = in_float32(value, field)
    if is_traced(v):
        return _traced_check(v, v <= 0, field, "must be > 0")
    if v <= 0:
        raise InputError(field, value, "must be > 0")
    return v


def non_negative(value: object, field: str) -> Real:
    v = in_float32(value, field)
    if is_traced(v):
        return _traced_check(v, v < 0, field, "must be >= 0")
    if v < 0:
        raise InputError(field, value, "must be >= 0")
    return v


INT_LIMIT = 2**31 - 1  # JAX computes in int32 (no x64): a larger integer overflows on entering jit


def is_integer(value: object) -> bool:
    """An integer, Python's or NumPy's, or a float with an integer value (not inf or NaN); not a bool."""
    if isinstance(value, (bool, np.bool_)):
        return False
    return isinstance(value, numbers.Integral) or (isinstance(value, numbers.Real) and float(value).is_integer())


def positive_int(value: object, field: str) -> int:
    if not is_integer(value):
        raise InputError(field, value, "must be an integer")
    if value < 1:
        raise InputError(field, value, "must be >= 1")
    if value > INT_LIMIT:
        raise InputError(field, value, f"must be <= {INT_LIMIT}")
    return int(value)


def occlusion_count(value: object, n_landmarks: int) -> int:
    """Number k of landmarks hidden during homing (docs/model.md §5 occlusion): an integer in 0..N."""
    if not is_integer(value):
        raise InputError("occlude", value, "must be an integer")
    if not 0 <= value <= n_landmarks:
        raise InputError("occlude", value, f"must be in 0..{n_landmarks} (the number of landmarks)")
    return int(value)


def choice(value: object, field: str, options) -> str:
    if value not in options:
        raise InputError(field, value, f"must be one of {', '.join(options)}")
    return value  # type: ignore[return-value]


SEED_LIMIT = 2**32  # PRNGKey keeps 32 bits of a seed (without x64): larger seeds would repeat smaller ones


def seed_value(value: object) -> int:
    """A seed in 0..2**32 - 1 (`InputError` otherwise, also for a seed too large for the key)."""
    integral = isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))
    if not integral or not 0 <= value < SEED_LIMIT:  # type: ignore[operator]
        raise InputError("seed", value, f"must be an integer in 0..{SEED_LIMIT - 1}")
    return int(value)  # type: ignore[arg-type]


def angle_deg(value: object, field: str) -> float:
    """A finite angle in degrees reduced into (-360, 360) in float64 (exact: `math.fmod`), before the
    core's float32 sees it: 1e30 deg is a heading, not a float32 overflow of its sine."""
    return math.fmod(finite(value, field), 360.0)


def unit_interval(value: object, field: str) -> float:
    """A number strictly between 0 and 1."""
    v = finite(value, field)
    if not 0.0 < v < 1.0:
        raise InputError(field, value, "must be in (0, 1)")
    return v


CHECKS = {
    "finite": finite,
    "positive": positive,
    "non_negative": non_negative,
    "positive_int": positive_int,
    "unit_interval": unit_interval,
    "angle_deg": angle_deg,
}  # core/settings.py CHECKS, but "choice"
