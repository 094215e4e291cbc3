"""Sweep files (TOML, `tomllib`): axes, metrics, validation before any work (docs/sweeps.md)."""

from __future__ import annotations

import itertools
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from .core.errors import InputError

KINDS = ("vector-map",)
# axis -> what it sets (the public option of `delvjax.vector_map` of the same name)
AXES = {
    "env": "environment: preset name or JSON path",
    "method": "registry name",
    "spacing": "grid spacing, cm",
    "seed": "seed of headings and noise, 0..2^32-1",
    "d": "unit-movement step, cm",
    "levels": "DELV quantization levels Q (0 = continuous)",
    "n_heading": "DELV heading hypotheses",
    "background": "uniform | distant",
    "bearing_noise_deg": "sigma of every blob bearing, deg",
    "step_noise": "sigma of the unit move's length, fraction of d",
    "turn_noise_deg": "sigma of the body turn during the unit move, deg",
    "odometry_turn_noise_deg": "sigma of the odometry's report of that turn, deg",
    "compass_noise_deg": "sigma of every compass reading, deg",
}
ROLLOUT_ONLY = ("motion_heading_noise_deg", "motion_step_noise", "max_steps", "home_radius", "first_move",
                "collisions", "occlude", "trials")
METRICS = {
    "gt45_pct": "% of grid points with angular error > 45 deg (Tables 5.1/5.2)",
    "gt90_pct": "% of grid points with angular error > 90 deg",
    "mean_error_deg": "mean angular error over the grid points, invalid = 180 deg",
    "mean_error_ci95_deg": "half-width of the 95 % Student-t interval of that mean",
    "invalid_pct": "% of grid points without a homing direction",
    "points": "grid points evaluated",
}
DEFAULTS = {"env": ["env1"], "method": ["delv"], "spacing": [25.0], "seed": [0]}

EXAMPLE = '''# delvjax sweep file: every combination of the axes is one cell (docs/sweeps.md).
# Run: delvjax sweep this.toml --out results/sweep ; read: delvjax.load_sweep("results/sweep")

[sweep]
kind = "vector-map"                  # vector-map metrics of every cell
metrics = ["gt45_pct", "gt90_pct", "mean_error_deg", "mean_error_ci95_deg", "invalid_pct"]

[axes]                               # a list, or an inclusive range {start, stop, step} / {start, stop, num}
env = ["env1", "env2"]               # presets or JSON paths (default ["env1"])
method = ["delv", "delv-compass"]    # registry names (default ["delv"])
d = { start = 10, stop = 100, step = 30 }
bearing_noise_deg = [0.0, 2.0]
seed = { start = 0, stop = 2 }       # integer range, step 1 (default [0])
# spacing = [25]                     # grid spacing, cm (default 25)
# levels, n_heading, background, step_noise, turn_noise_deg, odometry_turn_noise_deg,
# compass_noise_deg: the options of `delvjax vector-map` of the same name
'''


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: axes in file order (name -> values), metrics, the file's text."""

    kind: str
    axes: dict[str, list]
    metrics: list[str]
    text: str

    def cells(self) -> list[dict]:
        """Every combination of the axes (the last axis varies fastest)."""
        names = list(self.axes)
        return [dict(zip(names, combo)) for combo in itertools.product(*self.axes.values())]

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.axes.values())


def _values(name: str, raw) -> list:
    field = f"axes.{name}"
    if isinstance(raw, dict):
        unknown = sorted(set(raw) - {"start", "stop", "step", "num"})
        if unknown or "start" not in raw or "stop" not in raw or ("step" in raw and "num" in raw):
            raise InputError(field, raw, "a range is {start, stop, step} or {start, stop, num}")
        start, stop = raw["start"], raw["stop"]
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                   for v in (start, stop, raw.get("step", 1), raw.get("num", 2))):
            raise InputError(field, raw, "range bounds must be finite numbers")
        if "num" in raw:
            num = raw["num"]
            if not isinstance(num, int) or num < 1:
                raise InputError(field, raw, "num must be an integer >= 1")
            values = [start + (stop - start) * i / max(num - 1, 1) for i in range(num)]
        else:
            step = raw.get("step", 1)
            if step <= 0 or stop < start:
                raise InputError(field, raw, "is empty (need start <= stop and step > 0)")
            values = [start + i * step for i in range(int(math.floor((stop - start) / step + 1e-9)) + 1)]
    elif isinstance(raw, list):
        values = raw
    else:
        values = [raw]
    if not values:
        raise InputError(field, raw, "is empty")
    if len(set(map(repr, values))) != len(values):
        raise InputError(field, raw, "repeats a value")
    kinds = {type(v) for v in values} - {bool}
    if name in ("env", "method", "background") and kinds != {str}:
        raise InputError(field, raw, "must be names (strings)")
    if name not in ("env", "method", "background") and not kinds <= {int, float}:
        raise InputError(field, raw, "must be numbers")
    return values


def parse_sweep(text: str, source: str = "sweep") -> SweepSpec:
    """Validate a sweep file's text (structure, axes, metrics); `InputError` naming the field."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(source, source, f"is not valid TOML ({exc})") from None
    unknown = sorted(set(data) - {"sweep", "axes"})
    if unknown:
        raise InputError(unknown[0], source, "unknown table (a sweep file has [sweep] and [axes])")
    head, axes = data.get("sweep", {}), data.get("axes", {})
    if not isinstance(head, dict) or not isinstance(axes, dict):
        raise InputError("sweep", source, "[sweep] and [axes] must be tables")
    for key in sorted(set(head) - {"kind", "metrics"}):
        raise InputError(f"sweep.{key}", head[key], "unknown field (kind, metrics)")
    kind = head.get("kind", "vector-map")
    if kind not in KINDS:
        raise InputError("sweep.kind", kind, f"must be one of {', '.join(KINDS)} (catchment and success-rate "
                                             "sweeps are not implemented yet)")
    metrics = head.get("metrics", list(METRICS))
    if not isinstance(metrics, list) or not metrics:
        raise InputError("sweep.metrics", metrics, "must be a non-empty list")
    for i, m in enumerate(metrics):
        if m not in METRICS:
            raise InputError(f"sweep.metrics[{i}]", m, f"unknown metric (choose from {', '.join(METRICS)})")
    for name in axes:
        if name in ROLLOUT_ONLY:
            raise InputError(f"axes.{name}", axes[name], "belongs to rollouts (not a vector-map sweep)")
        if name not in AXES:
            raise InputError(f"axes.{name}", axes[name], f"unknown axis (choose from {', '.join(AXES)})")
    values = {name: _values(name, raw) for name, raw in axes.items()}
    for name, default in DEFAULTS.items():
        values.setdefault(name, default)
    return SweepSpec(kind=kind, axes=values, metrics=list(dict.fromkeys(metrics)), text=text)


def read_sweep(path: str | Path) -> SweepSpec:
    """A sweep file from disk (`parse_sweep`)."""
    p = Path(path)
    try:
        text = p.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("sweep", str(path), f"cannot be read ({getattr(exc, 'strerror', None) or exc})") from None
    return parse_sweep(text, str(path))
