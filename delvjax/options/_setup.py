"""The one place where user options (CLI flags, API keywords) become a validated setup (`make_setup`): a
method (`_registry.py`) with its settings and a `Sensor`. Which options exist, their checks and units
are declared once on the module fields (`core/settings.py`) and read here through
`options._schema`.

Every check runs before any array work and raises `InputError` naming the field and value.
A number traced by `jax.jit`, `jax.grad` or `jax.vmap` has no value yet: it is checked inside the
computation instead (`equinox.error_if`, the same message). Public angles are in degrees; the core
sees radians.
"""

from __future__ import annotations

import dataclasses
import math

from ..core.checks import is_traced
from ..core.deprecation import renamed_keyword
from ..core.errors import InputError
from ..core.images.scene_panorama import scene_panorama
from ..core.methods import HomingMethod, MethodSet
from ..core.sensor import Noise, Sensor
from ..core.settings import declared
from ..core.types import Real
from ..envs._presets import RESOLUTION_CM
from ._limits import check_tables
from ._registry import configure, declaring, get_method, owns
from ._registry import method_set as registry_method_set
from ._schema import method_options, sensor_options, upgraded

METHOD_SET_WHY = "the methods compiled as one MethodSet; a program is what XLA compiles"
_NOISE = declared(Noise)  # public name -> (field, Setting, default)
NOISE_FIELDS_DEG = {o: f for o, (f, s, _) in _NOISE.items() if s.unit == "deg"}  # degrees -> radians
NOISE_FIELDS_FRACTION = {o: f for o, (f, s, _) in _NOISE.items() if s.unit != "deg"}
NOISE_OPTIONS = tuple(_NOISE)


def make_noise(**kwargs: Real) -> Noise:
    """`Noise` from public keywords (`bearing_noise_deg`, `step_noise`, ...), all >= 0."""
    options = sensor_options()
    unknown = set(kwargs) - set(NOISE_OPTIONS)
    if unknown:
        name = sorted(unknown)[0]
        raise InputError(name, kwargs[name], f"unknown noise option (choose from {', '.join(NOISE_OPTIONS)})")
    return Noise(**{options[name].field: options[name].validate(value) for name, value in kwargs.items()})


def make_sensor(**options) -> Sensor:
    """Validated `Sensor` from public options (d, background, channel, alpha_r_deg, n_pix and the noise
    keywords of `make_noise`; None: the module's default)."""
    known = sensor_options()
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise InputError(unknown[0], options[unknown[0]], "unknown sensor option")
    given = {k: v for k, v in options.items() if v is not None}
    noise = make_noise(**{k: v for k, v in given.items() if k in NOISE_OPTIONS})
    fields = {known[k].field: known[k].validate(v) for k, v in given.items() if k not in NOISE_OPTIONS}
    return Sensor(noise=noise, **fields)


def check_quantum(levels, scale, named_scale: bool) -> None:
    """`InputError` naming the scale (or the levels, when the scale is the default) when DELV's quantization
    step a/Q (Eq 3.17) is below float32's resolution of distances (`RESOLUTION_CM`): a scale of 1e-40 cm made
    every distance 0 and every point invalid, with a hint about landmarks. A traced value is not checked."""
    if is_traced(levels) or is_traced(scale) or not levels or scale / levels >= RESOLUTION_CM:
        return
    fix = (
        f"scale >= levels x {RESOLUTION_CM} cm = {levels * RESOLUTION_CM:.3g} cm"
        if named_scale
        else f"levels <= scale / {RESOLUTION_CM} cm = {math.floor(scale / RESOLUTION_CM)}"
    )
    raise InputError(
        "scale" if named_scale else "levels",
        scale if named_scale else levels,
        f"gives a quantization step scale/levels = {scale / levels:.3g} cm, below float32's {RESOLUTION_CM} cm "
        f"resolution of distances: use {fix}",
    )


def method_settings(options: dict, extra=(), method: HomingMethod | None = None) -> dict[str, object]:
    """Validated method settings by public name (their field values; `options._schema`). The relations
    between settings are declared on the method and checked by `make_setup` through its `check_input`
    (n_psi divides n_pix: `core.methods.warping.check_hypotheses`); the quantization step of DELV's
    levels and scale (`check_quantum`) is checked here, where the float32 resolution is known."""
    known = method_options(extra)
    out = {}
    for name, value in options.items():  # checked by the declaration of each method it sets
        if value is not None:
            owners = declaring(method, name) if method is not None else ()
            out[name] = [known[name].validate(value, t) for t in owners or (None,)][0]
    if {"levels", "scale"} & set(out) and "scale" in known and (method is None or owns(method, "scale")):
        check_quantum(out.get("levels", 0), out.get("scale", known["scale"].default), "scale" in out)
    return out


def option_names(extra=()) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(method settings, sensor options): every public option name, read from the declarations now."""
    return tuple(method_options(extra)), tuple(sensor_options())


def reads_channel(method: HomingMethod) -> bool:
    """Whether the sensor's image channel changes what `method` reads (an image method)."""
    if isinstance(method, MethodSet):
        return any(reads_channel(m) for m in method.methods)
    return bool(method.reads_gray("gray")) != bool(method.reads_gray("mask"))


def make_setup(
    method: str | HomingMethod,
    method_set=None,
    sensor: Sensor | None = None,
    noise: Noise | None = None,
    panorama_cols: int | None = None,
    own_only: bool = False,
    **options,
) -> tuple[HomingMethod, Sensor]:
    """(method module, sensor), validated before any work. `method`: a registry name or a method
    module (`DELV(levels=3, heading=Compass())`); `method_set`: registry names compiled into one
    program with `method` (`_registry.method_set`); `sensor`: a `Sensor` instead of sensor options;
    `noise`: a `Noise` instead of the noise options; `panorama_cols`: the width of the panoramas of an
    image database (0: a database not read yet; None: a scene of rings, whose sensor then renders the
    panoramas of its cylinders for a method that reads them, `core.images.scene_panorama`).
    A method setting that the method does not have is an error naming it; with a `method_set`, one that no
    method of the set has, or with `own_only` (a sweep's set, which must not change what a cell may set) one
    that `method` itself does not have."""
    options = upgraded(options)  # a former name (mw_n_alpha) read as today's, with a DeprecationWarning
    method_set = renamed_keyword(options, "program", "method_set", method_set, METHOD_SET_WHY)
    extra = (method,) if isinstance(method, HomingMethod) else ()
    method_names, sensor_names = option_names(extra)
    unknown = sorted(set(options) - set(method_names) - set(sensor_names))
    if unknown:
        raise InputError(unknown[0], options[unknown[0]], "unknown option")
    given_sensor = {k: v for k, v in options.items() if k in sensor_names and v is not None}
    if sensor is None:
        sensor = make_sensor(**given_sensor)
    elif not isinstance(sensor, Sensor):
        raise InputError("sensor", sensor, "must be a delvjax.Sensor")
    elif given_sensor:
        name = sorted(given_sensor)[0]
        raise InputError(name, given_sensor[name], "cannot be combined with sensor= (set it on the Sensor)")
    if noise is not None:  # a Noise module in place of the noise options
        if not isinstance(noise, Noise):
            raise InputError("noise", noise, "must be a delvjax.Noise")
        given_noise = sorted(k for k in given_sensor if k in NOISE_OPTIONS)
        if given_noise:
            raise InputError(
                given_noise[0], given_sensor[given_noise[0]], "cannot be combined with noise= (set it on the Noise)"
            )
        sensor = dataclasses.replace(sensor, noise=noise)
    if isinstance(method, HomingMethod):
        if method_set is not None:
            raise InputError("method_set", method_set, "needs a registry name as the method")
        module = method
    else:
        module = get_method(method) if method_set is None else registry_method_set(method, method_set)[0]
    label = method if isinstance(method, str) else type(method).__name__
    runs = get_method(method) if own_only and method_set is not None else module  # whose settings count
    if "channel" in given_sensor and not reads_channel(runs):
        raise InputError(
            "channel", given_sensor["channel"], f"is read only by image methods (warping, mfdid), not by {label}"
        )
    for name in (k for k in method_names if options.get(k) is not None):  # before its value is checked
        if not owns(runs, name):
            raise InputError(name, options[name], f"is not a setting of the method {label}")
    settings = method_settings({k: v for k, v in options.items() if k in method_names}, extra, module)
    configured = configure(module, **settings)
    if not configured.reads_panorama():  # the relations between its settings, declared on the method
        configured.check_input(sensor.n_pix)
    width = sensor.n_pix if panorama_cols is None else panorama_cols  # 0: a database not read yet
    if width:
        check_tables(configured, width)  # before a trace builds them
    if configured.reads_panorama():
        if panorama_cols is None:  # a scene of rings: its cylinders rendered as panoramas (docs/images.md §10)
            configured.check_input(sensor.n_pix)
            if sensor.panorama is None:
                sensor = dataclasses.replace(sensor, panorama=scene_panorama(sensor.n_pix))
        elif panorama_cols:
            configured.check_input(panorama_cols)
    return configured, sensor
