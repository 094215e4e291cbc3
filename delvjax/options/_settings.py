"""The one place where user options (CLI flags, API keywords) become validated modules: a
method (`registry`) with its settings and a `Sensor`.

Every check runs before any array work and raises `InputError` naming the field and value.
A number traced by `jax.jit`, `jax.grad` or `jax.vmap` has no value yet: it is checked inside the
computation instead (`equinox.error_if`, the same message). Public angles are in degrees; the core
sees radians.
"""

from __future__ import annotations

import dataclasses
import inspect
import math

import equinox as eqx
import jax
import jax.numpy as jnp

from ..core.errors import InputError
from ..core.methods import HomingMethod, Program, Warping
from ..core.sensor import BACKGROUNDS, CHANNELS, Noise, Sensor
from ._registry import configure, get_method, owns
from ._registry import program as registry_program

NOISE_FIELDS_DEG = {  # public name -> Noise field (degrees converted to radians)
    "bearing_noise_deg": "bearing",
    "turn_noise_deg": "turn",
    "odometry_turn_noise_deg": "turn_odometry",
    "compass_noise_deg": "compass",
    "motion_heading_noise_deg": "motion_heading",
}
NOISE_FIELDS_FRACTION = {"step_noise": "step", "motion_step_noise": "motion_step"}
NOISE_OPTIONS = (*NOISE_FIELDS_DEG, *NOISE_FIELDS_FRACTION)


def is_traced(value: object) -> bool:
    """A number inside `jax.jit`, `jax.grad` or `jax.vmap`: checked in the computation, not here."""
    return isinstance(value, jax.core.Tracer)


def _traced_check(value: jax.Array, bad: jax.Array, field: str, expected: str) -> jax.Array:
    """`value`, raising at run time with `InputError`'s wording where `bad` holds (equinox.error_if)."""
    return eqx.error_if(value, bad, f"{field}: {expected} (a traced value)")


def finite(value: object, field: str) -> float:
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


def positive(value: object, field: str) -> float:
    v = finite(value, field)
    if is_traced(v):
        return _traced_check(v, v <= 0, field, "must be > 0")
    if v <= 0:
        raise InputError(field, value, "must be > 0")
    return v


def non_negative(value: object, field: str) -> float:
    v = finite(value, field)
    if is_traced(v):
        return _traced_check(v, v < 0, field, "must be >= 0")
    if v < 0:
        raise InputError(field, value, "must be >= 0")
    return v


INT_LIMIT = 2**31 - 1  # JAX computes in int32 (no x64): a larger integer overflows on entering jit


def is_integer(value: object) -> bool:
    """An int, or a float with an integer value (not inf or NaN); not a bool."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    return isinstance(value, int) or value.is_integer()


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
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < SEED_LIMIT:
        raise InputError("seed", value, f"must be an integer in 0..{SEED_LIMIT - 1}")
    return value


def angle_deg(value: object, field: str) -> float:
    """A finite angle in degrees reduced into (-360, 360) in float64 (exact: `math.fmod`), before the
    core's float32 sees it: 1e30 deg is a heading, not a float32 overflow of its sine."""
    return math.fmod(finite(value, field), 360.0)


def make_noise(**kwargs: float) -> Noise:
    """`Noise` from public keywords (`bearing_noise_deg`, `step_noise`, ...), all >= 0."""
    unknown = set(kwargs) - set(NOISE_OPTIONS)
    if unknown:
        name = sorted(unknown)[0]
        raise InputError(name, kwargs[name], f"unknown noise option (choose from {', '.join(NOISE_OPTIONS)})")
    fields = {}
    for name, value in kwargs.items():
        v = non_negative(value, name)
        if name in NOISE_FIELDS_DEG:
            fields[NOISE_FIELDS_DEG[name]] = v * (math.pi / 180.0) if is_traced(v) else math.radians(v)
        else:
            fields[NOISE_FIELDS_FRACTION[name]] = v
    return Noise(**fields)


def defaults(module_type) -> dict[str, object]:
    """The default of every field of a module class (written once, on the module; the CLI reads them)."""
    return {f.name: f.default for f in dataclasses.fields(module_type) if f.default is not dataclasses.MISSING}


def make_sensor(d: float | None = None, background: str | None = None, channel: str | None = None,
                alpha_r_deg: float | None = None, n_pix: int | None = None, **noise: float) -> Sensor:
    """Validated `Sensor` from public options (None: the module's default); noise keywords as `make_noise`."""
    fields: dict[str, object] = {"noise": make_noise(**noise)}
    if background is not None:
        fields["background"] = BACKGROUNDS.index(choice(background, "background", BACKGROUNDS))
    if channel is not None:
        fields["channel"] = choice(channel, "channel", CHANNELS)
    if alpha_r_deg is not None:
        fields["alpha_r"] = math.radians(angle_deg(alpha_r_deg, "alpha_r_deg"))
    if d is not None:
        fields["d"] = positive(d, "d")
    if n_pix is not None:
        fields["n_pix"] = positive_int(n_pix, "n_pix")
        if fields["n_pix"] > SHAPE_LIMITS["n_pix"]:
            raise InputError("n_pix", n_pix, f"must be <= {SHAPE_LIMITS['n_pix']} (it sets an array size)")
    return Sensor(**fields)


FIELD_OF_OPTION = {"mfdid_blur_deg": "blur_deg"}  # public option -> method field, where they differ
PUBLIC_NAME = {field: option for option, field in FIELD_OF_OPTION.items()}


SHAPE_LIMITS = {"n_heading": 36_000, "n_alpha": 3_600, "n_rho": 1_000, "n_pix": 36_000}  # 0.01 deg at most


def method_settings(levels: int | None = None, n_heading: int | None = None, scale: float | None = None,
                    r_max: float | None = None, n_alpha: int | None = None, n_psi: int | None = None,
                    n_rho: int | None = None, rho_min: float | None = None, rho_max: float | None = None,
                    mfdid_blur_deg: float | None = None, n_pix: int | None = None) -> dict[str, object]:
    """Validated method settings from public options (None: each module's default), as module
    field names (`registry.configure`). levels, n_heading, scale, r_max: DELV's; n_alpha, n_psi,
    n_rho, rho_min, rho_max: the warping hypotheses (docs/model.md §4.3; n_psi must divide n_pix
    and 0 < rho_min <= rho_max < 1); mfdid_blur_deg: MFDID's `blur_deg`."""
    out: dict[str, object] = {}
    for name, value in (("levels", levels), ("n_heading", n_heading), ("n_alpha", n_alpha), ("n_psi", n_psi),
                        ("n_rho", n_rho)):
        if value is not None:
            out[name] = positive_int(value, name)
            if out[name] > SHAPE_LIMITS.get(name, out[name]):
                raise InputError(name, value, f"must be <= {SHAPE_LIMITS[name]} (it sets an array size)")
    for name, value in (("scale", scale), ("r_max", r_max)):
        if value is not None:
            out[name] = positive(value, name)
    if mfdid_blur_deg is not None:
        out[FIELD_OF_OPTION["mfdid_blur_deg"]] = non_negative(mfdid_blur_deg, "mfdid_blur_deg")
    warping = defaults(Warping)
    n_psi = out.get("n_psi", warping["n_psi"])
    n_pix = positive_int(n_pix, "n_pix") if n_pix is not None else defaults(Sensor)["n_pix"]
    if n_pix % n_psi:
        raise InputError("n_psi", n_psi, f"must divide n_pix = {n_pix} (psi hypotheses are whole-pixel rotations)")
    lo = finite(rho_min, "rho_min") if rho_min is not None else warping["rho_min"]
    hi = finite(rho_max, "rho_max") if rho_max is not None else warping["rho_max"]
    if not 0.0 < lo < 1.0:
        raise InputError("rho_min", lo, "must be in (0, 1)")
    if not lo <= hi < 1.0:
        raise InputError("rho_max", hi, f"must be in [rho_min = {lo}, 1)")
    if rho_min is not None:
        out["rho_min"] = lo
    if rho_max is not None:
        out["rho_max"] = hi
    return out


METHOD_OPTIONS = tuple(inspect.signature(method_settings).parameters)
SENSOR_OPTIONS = ("d", "background", "channel", "alpha_r_deg", "n_pix", *NOISE_OPTIONS)


def reads_channel(method: HomingMethod) -> bool:
    """Whether the sensor's image channel changes what `method` reads (an image method)."""
    if isinstance(method, Program):
        return any(reads_channel(m) for m in method.methods)
    return bool(method.reads_gray("gray")) != bool(method.reads_gray("mask"))


def make_setup(method: str | HomingMethod, program=None, sensor: Sensor | None = None,
               **options) -> tuple[HomingMethod, Sensor]:
    """(method module, sensor), validated before any work. `method`: a registry name or a method
    module (`DELV(levels=3, heading=Compass())`); `program`: registry names compiled into one
    program with `method` (`registry.program`); `sensor`: a `Sensor` instead of sensor options.
    A method setting that the method does not have is an error naming it."""
    unknown = sorted(set(options) - set(METHOD_OPTIONS) - set(SENSOR_OPTIONS))
    if unknown:
        raise InputError(unknown[0], options[unknown[0]], "unknown option")
    sensor_options = {k: v for k, v in options.items() if k in SENSOR_OPTIONS and v is not None}
    if sensor is None:
        sensor = make_sensor(**sensor_options)
    elif not isinstance(sensor, Sensor):
        raise InputError("sensor", sensor, "must be a delvjax.Sensor")
    elif sensor_options:
        name = sorted(sensor_options)[0]
        raise InputError(name, sensor_options[name], "cannot be combined with sensor= (set it on the Sensor)")
    settings = method_settings(**{k: v for k, v in options.items() if k in METHOD_OPTIONS})
    if isinstance(method, HomingMethod):
        if program is not None:
            raise InputError("program", program, "needs a registry name as the method")
        module = method
    else:
        module = get_method(method) if program is None else registry_program(method, program)[0]
    if "channel" in sensor_options and not reads_channel(module):
        label = method if isinstance(method, str) else type(method).__name__
        raise InputError("channel", sensor_options["channel"], f"is read only by image methods (warping, mfdid), "
                                                                f"not by {label}")
    for field, value in settings.items():
        if not owns(module, field):
            label = method if isinstance(method, str) else type(method).__name__
            raise InputError(PUBLIC_NAME.get(field, field), value, f"is not a setting of the method {label}")
    return configure(module, **settings), sensor
