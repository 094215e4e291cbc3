"""Environments from user input: presets, JSON files and their validation (docs/model.md §6, §7).

The array form, `Env`, lives in the core (`delvjax.core.scene`); everything that reads a
file or checks a user's numbers happens here, once, before any array work.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import jax
import numpy as np

from ..core.errors import InputError
from ..core.scene import DEFAULT_ARENA, DEFAULT_HOME, Env


def make_env(landmarks, home=DEFAULT_HOME, arena=DEFAULT_ARENA, name: str = "env", pad_to: int | None = None) -> Env:
    """Build an `Env` from plain numbers (validated like a JSON file, docs/model.md §7)."""
    try:
        lms = np.asarray(landmarks, float).reshape(-1, 3)
    except (TypeError, ValueError, OverflowError):
        raise InputError("landmarks", landmarks, "must be rows of three numbers x, y, r") from None
    spec = {
        "name": name,
        "arena": _plain(arena),
        "home": _plain(home),
        "landmarks": [{"x": float(x), "y": float(y), "r": float(r)} for x, y, r in lms],
    }
    return env_from_dict(spec, pad_to=pad_to)


def _plain(value):
    """A NumPy array or sequence as a list of Python scalars (validation takes plain numbers); else as is."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [v.item() if isinstance(v, np.generic) else v for v in value]
    return value


ENV_FIELDS = {"name", "arena", "home", "landmarks"}
FLOAT32_MAX = float(np.finfo(np.float32).max)  # an Env holds float32: larger numbers would become inf


def _number(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(field, value, "must be a number")
    try:
        v = float(value)  # an int beyond float range (JSON allows any number of digits) overflows
    except OverflowError:
        v = math.inf
    if not math.isfinite(v) or abs(v) > FLOAT32_MAX:
        raise InputError(field, value, f"must be finite (|value| <= {FLOAT32_MAX:.4g}, float32)")
    return v


# An Env holds float32 coordinates: their resolution at |x| is np.spacing(float32(x)); beyond
# MAX_COORD_CM it is coarser than RESOLUTION_CM and the numbers change with a shift of the whole
# scene (docs/reliability.md "Coordinates"), so such coordinates are refused, not silently rounded.
RESOLUTION_CM = 0.01
MAX_COORD_CM = 2.0**17  # 131072 cm (1.3 km): float32 resolves 0.0078 cm below it, 0.0156 cm from it


def _coordinate(value, field: str) -> float:
    v = _number(value, field)
    if abs(v) >= MAX_COORD_CM:
        step = float(np.spacing(np.float32(abs(v))))
        raise InputError(
            field,
            value,
            f"is too far from (0, 0): coordinates are float32, which resolve only {step:.3g} cm there (more than "
            f"{RESOLUTION_CM} cm, so results would change with the shift); shift the whole environment so that "
            f"|x|, |y| < {MAX_COORD_CM:.0f} cm (e.g. home at (0, 0))",
        )
    return v


def _pair(value, field: str, n: int, number=_number) -> list[float]:
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise InputError(field, value, f"must be a list of {n} numbers")
    return [number(v, f"{field}[{i}]") for i, v in enumerate(value)]


def validate_env_dict(spec: object) -> dict:
    """Check an environment description (docs/model.md §7); return it normalised. Raises `InputError`."""
    if not isinstance(spec, dict):
        raise InputError("environment", type(spec).__name__, "must be a JSON object")
    for key in ("arena", "home", "landmarks"):
        if key not in spec:
            raise InputError(key, None, "missing required field")
    unknown = sorted(set(spec) - ENV_FIELDS, key=str)
    if unknown:
        raise InputError(
            unknown[0], spec[unknown[0]], f"unknown field (an environment has {', '.join(sorted(ENV_FIELDS))})"
        )
    name = spec.get("name", "env")
    if not isinstance(name, str) or not name:
        raise InputError("name", name, "must be a non-empty string")
    xmin, ymin, xmax, ymax = _pair(spec["arena"], "arena", 4, _coordinate)
    if not (xmax > xmin and ymax > ymin):
        raise InputError("arena", spec["arena"], "must be [xmin, ymin, xmax, ymax] with xmax > xmin and ymax > ymin")
    hx, hy = _pair(spec["home"], "home", 2, _coordinate)
    if not (xmin < hx < xmax and ymin < hy < ymax):
        raise InputError("home", spec["home"], f"must lie inside the arena {spec['arena']}")
    raw = spec["landmarks"]
    if not isinstance(raw, list) or not raw:
        raise InputError("landmarks", raw, "must be a non-empty list of {x, y, r}")
    lms = []
    for i, lm in enumerate(raw):
        if not isinstance(lm, dict):
            raise InputError(f"landmarks[{i}]", lm, "must be an object {x, y, r}")
        for key in ("x", "y", "r"):
            if key not in lm:
                raise InputError(f"landmarks[{i}].{key}", None, "missing required field")
        extra = sorted(set(lm) - {"x", "y", "r"}, key=str)
        if extra:
            raise InputError(f"landmarks[{i}].{extra[0]}", lm[extra[0]], "unknown field (a landmark has x, y, r)")
        x, y, r = (_number(lm[k], f"landmarks[{i}].{k}") for k in ("x", "y", "r"))
        if r < RESOLUTION_CM:  # float32 would round a smaller radius to nothing (1e-50 became 0)
            raise InputError(f"landmarks[{i}].r", lm["r"], f"must be >= {RESOLUTION_CM} cm (float32 coordinates)")
        if math.hypot(x - hx, y - hy) <= r:
            raise InputError(f"landmarks[{i}]", lm, f"covers home {spec['home']}")
        if not (xmin <= x - r and x + r <= xmax and ymin <= y - r and y + r <= ymax):
            raise InputError(f"landmarks[{i}]", lm, "must lie inside the arena")
        lms.append((x, y, r))
    _check_overlaps(np.asarray(lms, np.float64), raw)
    return {"name": name, "arena": [xmin, ymin, xmax, ymax], "home": [hx, hy], "landmarks": lms}


def _check_overlaps(lms: np.ndarray, raw: list) -> None:
    """`InputError` for the first landmark (in file order) that overlaps an earlier one; blocks of rows
    at a time, so 10,000 landmarks take a second, not minutes."""
    block = max(1, 2_000_000 // len(lms))
    for start in range(0, len(lms), block):  # input validation: a few blocks of rows
        rows = lms[start : start + block]
        gap = np.hypot(rows[:, None, 0] - lms[None, :, 0], rows[:, None, 1] - lms[None, :, 1])
        earlier = np.arange(len(lms))[None, :] < np.arange(start, start + len(rows))[:, None]
        hit = earlier & (gap < rows[:, None, 2] + lms[None, :, 2])
        if hit.any():
            i, j = np.argwhere(hit)[0]
            raise InputError(f"landmarks[{start + i}]", raw[start + i], f"overlaps landmarks[{j}]")


def random_env(
    seed: int,
    n_landmarks: int,
    radius=(15.0, 45.0),
    region=(150.0, 850.0),
    min_home_gap: float = 40.0,
    min_gap: float = 20.0,
    pad_to: int | None = None,
    name: str | None = None,
) -> Env:
    """A reproducible random layout (thesis Fig 4.8 "arbitrary layouts"): `n_landmarks`
    non-overlapping cylinders in the default arena, none within r + `min_home_gap` of home."""
    rng = np.random.default_rng(seed)
    out: list[tuple[float, float, float]] = []
    while len(out) < n_landmarks:  # rejection sampling of a handful of landmarks: input preparation
        x, y = rng.uniform(*region, size=2)
        r = rng.uniform(*radius)
        if math.hypot(x - DEFAULT_HOME[0], y - DEFAULT_HOME[1]) < r + min_home_gap:
            continue
        if any(math.hypot(x - a, y - b) < r + c + min_gap for a, b, c in out):
            continue
        out.append((float(x), float(y), float(r)))
    return make_env(out, name=name or f"random{seed}-{n_landmarks}", pad_to=pad_to)


MAX_PAD = 10_000  # landmark slots of a padded Env: a bound, so that a typo cannot ask for gigabytes


def env_from_dict(spec: object, pad_to: int | None = None) -> Env:
    """Validated `Env` from a docs/model.md §7 dictionary, landmarks padded to `pad_to`."""
    s = validate_env_dict(spec)
    lms = np.asarray(s["landmarks"], dtype=np.float32).reshape(-1, 3)
    n = lms.shape[0]
    pad = n if pad_to is None else pad_to
    if isinstance(pad, bool) or not isinstance(pad, (int, np.integer)):
        raise InputError("pad_to", pad_to, "must be an integer")
    if not n <= pad <= MAX_PAD:
        raise InputError("pad_to", pad_to, f"must be in {n}..{MAX_PAD} (>= the number of landmarks)")
    # Padding rows sit far outside any arena with a tiny radius; the mask hides them.
    padded = np.tile(np.array([[1e9, 1e9, 1e-3]], np.float32), (pad, 1))
    padded[:n] = lms
    put = jax.device_put  # host to device without an eager op (those compile once per shape)
    return Env(
        landmarks=put(padded),
        valid=put(np.arange(pad) < n),
        home=put(np.asarray(s["home"], np.float32)),
        arena=put(np.asarray(s["arena"], np.float32)),
        name=s["name"],
    )


def env_to_dict(env: Env) -> dict:
    """The docs/model.md §7 dictionary of an `Env` (padding dropped)."""
    lms = np.asarray(env.landmarks)[np.asarray(env.valid)]
    return {
        "name": env.name,
        "arena": [float(v) for v in np.asarray(env.arena)],
        "home": [float(v) for v in np.asarray(env.home)],
        "landmarks": [{"x": float(x), "y": float(y), "r": float(r)} for x, y, r in lms],
    }


def _ring(
    n: int, distance: float = 250.0, radius: float = 30.0, first_deg: float = 90.0
) -> list[tuple[float, float, float]]:
    hx, hy = DEFAULT_HOME
    return [
        (
            round(hx + distance * math.cos(math.radians(first_deg + 360.0 * i / n)), 3),
            round(hy + distance * math.sin(math.radians(first_deg + 360.0 * i / n)), 3),
            radius,
        )
        for i in range(n)
    ]


# Thesis §4.2 / docs/model.md §6 describe these layouts but give no coordinates; ours follow the
# descriptions (README documents and draws them). Home (500, 500), arena 1000 x 1000 cm.
PRESETS: dict[str, list[tuple[float, float, float]]] = {
    # env1: four landmarks of different sizes around home, asymmetric (docs/model.md §6; docs/env1.md):
    # bearings from home 23.5/142.3/207.8/289.8 deg (gaps 118.8/65.6/82.0/93.6), distances
    # 289/196/204/324 cm, none within 20 deg of the home unit move's line. No rotation by
    # 90/180/270 deg about home brings the centres within 150 cm of the layout
    # (`rotation_mismatch`), so DELV without a compass does not confuse those rotations.
    "env1": [(765.0, 615.0, 20.0), (345.0, 620.0, 40.0), (320.0, 405.0, 30.0), (610.0, 195.0, 45.0)],
    # env2: four landmarks at 90 degree spacing seen from home (45, 135, 225, 315 deg).
    "env2": [(676.777, 676.777, 30.0), (323.223, 676.777, 30.0), (323.223, 323.223, 30.0), (676.777, 323.223, 30.0)],
    # env3: all four landmarks on one side (east) of home.
    "env3": [(640.0, 700.0, 30.0), (760.0, 590.0, 40.0), (740.0, 400.0, 25.0), (630.0, 290.0, 35.0)],
    # ringL: L landmarks equally spaced at 250 cm around home, radius 30, the first due
    # north; ring4's first at 45 deg, so that no landmark lies on the line of the home
    # unit move (0/180 deg from home along alpha_r = 0), which gives no parallax (docs/model.md §3.1).
    **{f"ring{n}": _ring(n, first_deg=45.0 if n == 4 else 90.0) for n in range(3, 7)},
}

PRESET_DESCRIPTIONS = {
    "env1": "4 landmarks of different sizes around home, asymmetric: gaps 119/66/82/94 deg, 196-324 cm (thesis env 1)",
    "env2": "4 equal landmarks 250 cm from home at 45/135/225/315 deg (thesis env 2)",
    "env3": "4 landmarks all east of home (thesis env 3)",
    **{f"ring{n}": f"{n} landmarks equally spaced 250 cm around home (Tables 5.1-5.4)" for n in range(3, 7)},
}


def preset_dict(name: str) -> dict:
    if name not in PRESETS:
        raise InputError("env", name, f"unknown preset (choose from {', '.join(PRESETS)}) and no such file")
    return {
        "name": name,
        "arena": list(DEFAULT_ARENA),
        "home": list(DEFAULT_HOME),
        "landmarks": [{"x": x, "y": y, "r": r} for x, y, r in PRESETS[name]],
    }


def load_env(name_or_path: str | Path | Env, pad_to: int | None = None) -> Env:
    """A preset by name (`env1`, `env2`, `env3`, `ring3`..`ring6`), a docs/model.md §7 JSON file, or an
    `Env` as it is."""
    if isinstance(name_or_path, Env) and pad_to is None:
        return name_or_path
    key = str(name_or_path)
    if key in PRESETS:
        return env_from_dict(preset_dict(key), pad_to=pad_to)
    path = Path(key)
    if path.is_dir():
        raise InputError("env", str(path), "is a folder: give an environment JSON file or a preset name")
    if not path.is_file():
        preset_dict(key)  # raises the "unknown preset" error
    try:
        spec = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise InputError("env", str(path), f"is not valid JSON ({exc.msg} at line {exc.lineno})") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("env", str(path), f"cannot be read ({exc})") from None
    except (ValueError, RecursionError) as exc:  # a number of too many digits, arrays nested too deep
        raise InputError("env", str(path), f"is not readable JSON ({type(exc).__name__}: {str(exc)[:80]})") from None
    if isinstance(spec, dict) and "name" not in spec:
        spec = {**spec, "name": path.stem}
    try:
        return env_from_dict(spec, pad_to=pad_to)
    except InputError as exc:  # which file: a sweep or a study reads several
        raise InputError(exc.field, exc.value, f"{exc.expected} (in {path})", file_key=True) from None
