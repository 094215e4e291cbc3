"""The one place where user options (CLI flags, API keywords) become a validated `Config`.

Every check runs before any array work and raises `InputError` naming the field and value.
Public angles are in degrees; the core sees radians.
"""

from __future__ import annotations

import math

from .config import BACKGROUNDS, CHANNELS, Config, Noise
from .errors import InputError

NOISE_FIELDS_DEG = {  # public name -> Noise field (degrees converted to radians)
    "bearing_noise_deg": "bearing",
    "turn_noise_deg": "turn",
    "odometry_turn_noise_deg": "turn_odometry",
    "compass_noise_deg": "compass",
    "motion_heading_noise_deg": "motion_heading",
}
NOISE_FIELDS_FRACTION = {"step_noise": "step", "motion_step_noise": "motion_step"}
NOISE_OPTIONS = (*NOISE_FIELDS_DEG, *NOISE_FIELDS_FRACTION)


def finite(value: object, field: str) -> float:
    """`value` as a finite float, else `InputError`."""
    if isinstance(value, bool):
        raise InputError(field, value, "must be a number")
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(field, value, "must be a number") from None
    if not math.isfinite(v):
        raise InputError(field, value, "must be finite")
    return v


def positive(value: object, field: str) -> float:
    v = finite(value, field)
    if v <= 0:
        raise InputError(field, value, "must be > 0")
    return v


def non_negative(value: object, field: str) -> float:
    v = finite(value, field)
    if v < 0:
        raise InputError(field, value, "must be >= 0")
    return v


def positive_int(value: object, field: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value:
        raise InputError(field, value, "must be an integer")
    if value < 1:
        raise InputError(field, value, "must be >= 1")
    return int(value)


def occlusion_count(value: object, n_landmarks: int) -> int:
    """Number k of landmarks hidden during homing (docs/model.md §5 occlusion): an integer in 0..N."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value:
        raise InputError("occlude", value, "must be an integer")
    if not 0 <= value <= n_landmarks:
        raise InputError("occlude", value, f"must be in 0..{n_landmarks} (the number of landmarks)")
    return int(value)


def choice(value: object, field: str, options) -> str:
    if value not in options:
        raise InputError(field, value, f"must be one of {', '.join(options)}")
    return value  # type: ignore[return-value]


def seed_value(value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise InputError("seed", value, "must be a non-negative integer")
    return value


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
            fields[NOISE_FIELDS_DEG[name]] = math.radians(v)
        else:
            fields[NOISE_FIELDS_FRACTION[name]] = v
    return Noise(**fields)


def make_config(d: float = 50.0, levels: int | None = None, background: str = "distant", channel: str = "mask",
                n_heading: int = 360, scale: float = 1000.0, r_max: float = 2000.0, alpha_r_deg: float = 0.0,
                n_pix: int = 360, n_alpha: int = 72, n_psi: int = 72, n_rho: int = 15, rho_min: float = 0.10,
                rho_max: float = 0.80, mfdid_blur_deg: float = 0.0, **noise: float) -> Config:
    """Validated `Config` (SPEC defaults) from public options.

    n_alpha, n_psi, n_rho, rho_min, rho_max: the warping hypotheses (docs/model.md §4.3); n_psi must
    divide n_pix (rotations are whole pixels) and 0 < rho_min <= rho_max < 1.
    """
    n_pix = positive_int(n_pix, "n_pix")
    n_psi = positive_int(n_psi, "n_psi")
    if n_pix % n_psi:
        raise InputError("n_psi", n_psi, f"must divide n_pix = {n_pix} (psi hypotheses are whole-pixel rotations)")
    rho_min, rho_max = finite(rho_min, "rho_min"), finite(rho_max, "rho_max")
    if not 0.0 < rho_min < 1.0:
        raise InputError("rho_min", rho_min, "must be in (0, 1)")
    if not rho_min <= rho_max < 1.0:
        raise InputError("rho_max", rho_max, f"must be in [rho_min = {rho_min}, 1)")
    return Config(
        d=positive(d, "d"),
        scale=positive(scale, "scale"),
        r_max=positive(r_max, "r_max"),
        alpha_r=math.radians(finite(alpha_r_deg, "alpha_r_deg")),
        mfdid_blur_deg=non_negative(mfdid_blur_deg, "mfdid_blur_deg"),
        noise=make_noise(**noise),
        levels=None if levels is None else positive_int(levels, "levels"),
        n_pix=n_pix,
        n_heading=positive_int(n_heading, "n_heading"),
        n_alpha=positive_int(n_alpha, "n_alpha"),
        n_psi=n_psi,
        n_rho=positive_int(n_rho, "n_rho"),
        rho_min=rho_min,
        rho_max=rho_max,
        background=BACKGROUNDS.index(choice(background, "background", BACKGROUNDS)),
        channel=choice(channel, "channel", CHANNELS),
    )
