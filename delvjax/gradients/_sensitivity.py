"""Sensitivity of homing loss to the world, the agent and the noise (docs/differentiable.md
"Sensitivity study"): which landmark matters most, and how loss responds to d, bearing,
odometry and compass noise, across DELV, ALV, ACV (gradients of the soft loss, reverse mode)
and warping (central differences of the ordinary loss, common random numbers: it has no
soft version)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.maps import SPACING
from ..core.scene import Env
from ..envs._presets import load_env
from ..evaluate import _vector_map as api
from ._loss import TAU, homing_loss, loss_problem
from ._profile import loss_profile
from ._smoothing import SAMPLES, SMOOTHING_CM, SMOOTHING_DEG, SMOOTHING_FRACTION, check_smoothing, homing_loss_grad

SENSITIVITY_METHODS = ("delv", "alv", "acv", "warping")
# the operating point at which sensitivities are taken: noise a real robot has (docs/differentiable.md)
NOMINAL = {"d": 50.0, "bearing_noise_deg": 1.0, "odometry_turn_noise_deg": 1.0, "compass_noise_deg": 2.0}
# the step each parameter's change is shown per (figure, `d_loss_per_step`): 10 cm of d, 1 degree of each sigma;
# `d_loss_per_setting_unit` (CSV, JSON, the study's numbers) is per cm of d and per degree, one unit per name
UNITS = {"d": 10.0, "bearing_noise_deg": 1.0, "odometry_turn_noise_deg": 1.0, "compass_noise_deg": 1.0}
SETTING_UNITS = {"d": "cm", "bearing_noise_deg": "deg", "odometry_turn_noise_deg": "deg", "compass_noise_deg": "deg"}
FD_STEP = {"d": 5.0, "bearing_noise_deg": 0.5, "odometry_turn_noise_deg": 0.5, "compass_noise_deg": 0.5}
FD_TEXT = ", ".join(f"{k} {v:g}" for k, v in FD_STEP.items())
READS = {"compass_noise_deg": ("alv", "acv")}  # parameters some methods never read (their sensitivity is 0)
RESOLVED_SE = 2.0  # a smoothed derivative is "resolved" when |value| > 2 standard errors: its sign is known


def resolved(value, se):
    """Whether a derivative's sign is known from its draws: |value| > RESOLVED_SE x its standard error
    (elementwise); "" where it has no standard error (the gradient at the point, a central difference)."""
    if se is None:
        return np.full(np.shape(value), "", dtype=object) if np.ndim(value) else ""
    out = np.abs(np.asarray(value)) > RESOLVED_SE * np.asarray(se)
    return out if np.ndim(out) else bool(out)


def unresolved_counts(result: dict) -> dict[str, tuple[int, int]]:
    """Per method whose derivatives carry standard errors: (how many are within RESOLVED_SE standard errors
    of 0, how many there are), over every landmark's x, y, r and every setting it reads."""
    out = {}
    for m in result["methods"]:
        flags = [r[f"resolved_d{c}"] for r in result["landmark_rows"] if r["method"] == m for c in "xyr"]
        flags += [r["resolved"] for r in result["parameter_rows"] if r["method"] == m]
        flags = [f for f in flags if f != ""]
        if flags:
            out[m] = (sum(not f for f in flags), len(flags))
    return out


def _options(method: str) -> dict:
    """The nominal options a method takes (no compass noise for methods without a compass)."""
    return {k: v for k, v in NOMINAL.items() if method in READS.get(k, (method,))}


def check_sensitivity(
    env: str | Path | Env,
    methods=SENSITIVITY_METHODS,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    smoothing_cm: float | None = SMOOTHING_CM,
    smoothing_deg: float = SMOOTHING_DEG,
    samples: int = SAMPLES,
) -> Env:
    """Validate everything `sensitivity` takes, before any work (`InputError` naming the field)."""
    env = load_env(env)
    check_smoothing(smoothing_cm, smoothing_deg, SMOOTHING_FRACTION, samples, env.arrays().arena)
    if isinstance(methods, str) or not methods:
        raise InputError("methods", methods, f"must be a non-empty list of {', '.join(SENSITIVITY_METHODS)}")
    for m in methods:
        if m not in SENSITIVITY_METHODS:
            raise InputError("methods", m, f"must be among {', '.join(SENSITIVITY_METHODS)}")
        if m == "warping":
            api.map_request(env, m, spacing=spacing, seed=seed, **_options(m))
        else:
            loss_problem(env, m, spacing=spacing, seed=seed, tau=tau, **_options(m))
    return env


@keywords_after(2, ("spacing", "seed", "tau", "progress"))
def sensitivity(
    env: str | Path | Env,
    methods=SENSITIVITY_METHODS,
    *,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    smoothing_cm: float | None = SMOOTHING_CM,
    smoothing_deg: float = SMOOTHING_DEG,
    samples: int = SAMPLES,
    progress: Callable[[str], None] | None = None,
) -> dict:
    """Per method: loss at the operating point, its gradient with respect to every landmark
    [x, y, r] (soft methods, smoothed at `smoothing_cm` / `smoothing_deg` with its standard error;
    `homing_loss_grad`), and d loss per unit of d and of each noise sigma. Returns
    {"env", "smoothing", "methods": {name: {...}}, "landmark_rows", "parameter_rows"}."""
    env = load_env(env)
    scale = {"smoothing_cm": smoothing_cm, "smoothing_deg": smoothing_deg, "samples": samples}
    out: dict = {"env": env, "smoothing": scale, "methods": {}, "landmark_rows": [], "parameter_rows": []}
    for m in methods:
        if progress is not None:
            progress(m)
        opts = _options(m)
        if m == "warping":
            value = float(homing_loss(env, m, spacing=spacing, seed=seed, soft=False, **opts))
            per = {}
            for name in NOMINAL:
                if name not in opts:
                    per[name] = 0.0
                    continue
                h = FD_STEP[name]
                hi = float(
                    homing_loss(env, m, spacing=spacing, seed=seed, soft=False, **{**opts, name: opts[name] + h})
                )
                lo = float(
                    homing_loss(
                        env, m, spacing=spacing, seed=seed, soft=False, **{**opts, name: max(opts[name] - h, 0.0)}
                    )
                )
                per[name] = (hi - lo) / (opts[name] + h - max(opts[name] - h, 0.0))
            grads, se, how = None, None, f"central difference, hard loss (steps {FD_TEXT})"
        else:
            value, g = homing_loss_grad(
                env,
                m,
                spacing=spacing,
                seed=seed,
                tau=tau,
                smoothing_cm=smoothing_cm,
                smoothing_deg=smoothing_deg,
                samples=samples,
                **opts,
            )
            per = {name: float(g.get(name, 0.0)) if name in opts else 0.0 for name in NOMINAL}
            grads, se = g["landmarks"], g["standard_error"]
            how = (
                f"soft loss (tau {tau:g}) smoothed at {smoothing_cm:g} cm and {smoothing_deg:g} deg, {samples} draws"
                if smoothing_cm is not None
                else f"reverse mode at the point, soft loss (tau {tau:g})"
            )
        out["methods"][m] = {
            "loss": value,
            "per_setting_unit": per,
            "landmark_grad": grads,
            "landmark_se": None if se is None else se["landmarks"],
            "how": how,
        }
        for name in NOMINAL:
            out["parameter_rows"].append(
                {
                    "method": m,
                    "parameter": name,
                    "nominal": opts.get(name, 0.0),
                    "setting_unit": SETTING_UNITS[name],
                    "d_loss_per_setting_unit": per[name],
                    "step": f"{UNITS[name]:g} {SETTING_UNITS[name]}",
                    "d_loss_per_step": per[name] * UNITS[name],
                    "standard_error": float(se.get(name, 0.0)) if se is not None and name in opts else "",
                    "resolved": resolved(per[name], se.get(name)) if se is not None and name in opts else "",
                    "loss": value,
                    "how": how,
                }
            )
        if grads is not None:
            errors = np.full_like(np.asarray(grads), np.nan) if se is None else np.asarray(se["landmarks"])
            known = resolved(np.asarray(grads), None if se is None else errors)
            for i, ((gx, gy, gr), (ex, ey, er), (kx, ky, kr)) in enumerate(zip(np.asarray(grads), errors, known)):
                out["landmark_rows"].append(
                    {
                        "method": m,
                        "landmark": i,
                        "dq_dx_per_cm": float(gx),
                        "dq_dy_per_cm": float(gy),
                        "dq_dr_per_cm": float(gr),
                        "position_gradient_norm": float(np.hypot(gx, gy)),
                        "se_dx": float(ex),
                        "se_dy": float(ey),
                        "se_dr": float(er),
                        "resolved_dx": kx if kx == "" else bool(kx),
                        "resolved_dy": ky if ky == "" else bool(ky),
                        "resolved_dr": kr if kr == "" else bool(kr),
                        "smoothing_cm": "" if smoothing_cm is None else smoothing_cm,
                    }
                )
    return out


def sensitivity_profiles(
    env: str | Path | Env,
    methods=SENSITIVITY_METHODS,
    *,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    smoothing_cm: float | None = SMOOTHING_CM,
    smoothing_deg: float = SMOOTHING_DEG,
    samples: int = SAMPLES,
    progress: Callable[[str], None] | None = None,
) -> dict[str, list[dict]]:
    """Per soft method at the operating point: `loss_profile` of landmark 0's x at the point, 1 cm and
    `smoothing_cm` (over +-3 times the largest scale), the picture of what a sensitivity means."""
    scales = tuple(dict.fromkeys((None, 1.0, smoothing_cm)))
    extent = 3.0 * max(s for s in scales if s is not None) if any(scales[1:]) else 3.0
    out = {}
    for m in methods:
        if m == "warping":
            continue
        if progress is not None:
            progress(f"profile of {m} ...")
        problem = loss_problem(env, m, spacing=spacing, seed=seed, tau=tau, **_options(m))
        out[m] = loss_profile(problem, 0, "x", scales, extent=extent, samples=samples, deg=smoothing_deg)
    return out
