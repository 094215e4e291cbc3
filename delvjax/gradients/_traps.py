"""Trap points of a method's homing field near its failed rollouts (docs/differentiable.md "Trap points").

    report = delvjax.find_traps("env1", "delv", levels=2)
    report.points       # rows: x, y, kind (sink | saddle | source | degenerate | discontinuity), ...
    report.summary      # failed rollouts, how many end within `near` cm of a sink, ...

The catchment (the ordinary, hard rollouts) gives the failed rollouts; their end points seed
optimistix's root finder on the soft field (`core.soft.traps`); zeros are merged within
MERGE_CM and classified from the Jacobian. A minimum of |H| that is not a zero is reported as a
discontinuity of the field; period-2 orbits of the rollout step (`two_cycles`) as limit cycles.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.checks import positive, positive_int
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.maps import SPACING
from ..core.rollouts import TIMEOUT, Catchment, Grid, Rules
from ..core.rollouts.rules import HOME_RADIUS
from ..core.scene import Env
from ..core.soft.traps import KINDS, field_zeros, two_cycles
from ..envs._presets import load_env
from ..evaluate._progress import Progress, with_callbacks
from ..evaluate._rollouts import catchment
from ._loss import TAU, loss_problem

MERGE_CM = 2.0  # zeros closer than this are one
CYCLE_CM = 1.0  # a period-2 orbit closes within this
CYCLE_MERGE_CM = 10.0  # orbits come in families along a line where the field flips: one row per 10 cm
RESIDUAL = 1e-3  # |H| at a zero, relative to the median |H| at the starts
START_CELL_CM = 5.0  # failed end points closer than this seed one start
MAX_STARTS = 256


@dataclass
class TrapReport:
    """What `find_traps` found: the catchment, the points (one dict per zero or discontinuity), the
    failed rollouts' end points and, per end point, the distance to the nearest sink; the summary."""

    env: Env
    method: str
    catchment: Catchment
    points: list[dict]
    failed_ends: np.ndarray
    nearest_sink_cm: np.ndarray
    summary: dict = field(default_factory=dict)


def _starts(ends: np.ndarray, home: np.ndarray, max_starts: int) -> np.ndarray:
    """One start per START_CELL_CM cell of the failed end points (at most `max_starts`), and home."""
    if len(ends):
        cells = np.unique(np.round(ends / START_CELL_CM), axis=0) * START_CELL_CM
        if len(cells) > max_starts - 1:
            cells = cells[np.linspace(0, len(cells) - 1, max_starts - 1).astype(int)]
    else:
        cells = np.zeros((0, 2))
    return np.concatenate([cells, home[None]]).astype(np.float32)


def _merge(points: np.ndarray, radius: float = MERGE_CM) -> list[list[int]]:
    """Groups of indices of points within `radius` of the group's first point (greedy, a few dozen points)."""
    groups: list[list[int]] = []
    for i, p in enumerate(points):  # post-processing of at most MAX_STARTS points
        for g in groups:
            if np.hypot(*(points[g[0]] - p)) <= radius:
                g.append(i)
                break
        else:
            groups.append([i])
    return groups


def _nearest(ends: np.ndarray, rows: list[dict], keep) -> np.ndarray:
    """Distance from each end point to the nearest point of `rows` that `keep` accepts (inf if none)."""
    pts = np.array([[r["x"], r["y"]] for r in rows if keep(r)]).reshape(-1, 2)
    if not len(pts) or not len(ends):
        return np.full(len(ends), np.inf)
    return np.min(np.hypot(*(ends[:, None, :] - pts[None]).transpose(2, 0, 1)), axis=1)


def failed_rollouts(c, m: int = 0) -> int:
    """Failed rollouts under mask m among the points the catchment counts (`Catchment.counted`, the
    points `catchment_pct` is over; a grid point within d of a wall is not released under the default
    first move and is no failure)."""
    return int((np.asarray(c.counted) & ~np.asarray(c.success)[m]).sum())


@keywords_after(2, ("spacing", "seed", "tau", "near", "max_starts", "home_radius", "announce"))
def find_traps(
    env: str | Path | Env,
    method: str = "delv",
    *,
    spacing: float = SPACING,
    seed: int = 0,
    tau: float = TAU,
    near: float | None = None,
    max_starts: int = MAX_STARTS,
    home_radius: float = HOME_RADIUS,
    progress: Progress | None = None,
    **options,
) -> TrapReport:
    """Zeros of the soft homing field of `method` near the end points of the failed (timed-out)
    rollouts of its catchment. `near` (default d): a failed rollout counts as ending at a sink
    within this distance (a trapped agent circles its sink in steps of d). `options` as in
    `delvjax.catchment` (noise sigmas, levels, d, ...); `progress`: the catchment's `Progress` (the
    `announce=` callback of earlier releases still works for one release, with a DeprecationWarning)."""
    report = with_callbacks(progress, options, "find_traps")
    if not isinstance(method, str):
        raise InputError("method", method, "must be a registry name")
    env = load_env(env)
    problem = loss_problem(env, method, spacing=spacing, seed=seed, tau=tau, **options)  # validates first
    max_starts = positive_int(max_starts, "max_starts")
    near = float(problem.sensor.d) if near is None else positive(near, "near")
    c = catchment(
        env,
        method,
        seed=seed,
        progress=report,
        grid=Grid(spacing=spacing),
        rules=Rules(home_radius=home_radius),
        **options,
    )
    inc = np.asarray(c.included)
    timeout = inc & (np.asarray(c.outcome)[0] == TIMEOUT)
    ends = np.asarray(c.end)[0][timeout]
    home = np.asarray(problem.env.home, np.float64)
    starts = _starts(ends, home, max_starts)
    z, _, kind, jac, residual = (
        np.asarray(a)
        for a in field_zeros(
            problem.env, starts, problem.sensor, problem.method, problem.key, problem.tau, problem.sharpness
        )
    )
    arena = np.asarray(problem.env.arena)
    lm = np.asarray(problem.env.landmarks)[np.asarray(problem.env.valid)]
    inside = (
        np.all(np.isfinite(z), axis=1)
        & (z[:, 0] >= arena[0])
        & (z[:, 0] <= arena[2])
        & (z[:, 1] >= arena[1])
        & (z[:, 1] <= arena[3])
    )
    inside &= ~np.any(np.hypot(*(z[:, None, :] - lm[None, :, :2]).transpose(2, 0, 1)) < lm[None, :, 2], axis=1)
    rows = []
    for group in _merge(np.where(inside[:, None], z, np.nan)):
        i = group[0]
        if not inside[i]:
            continue
        zero = residual[i] < RESIDUAL
        label = KINDS[int(np.bincount(kind[group]).argmax())] if zero else "discontinuity"
        rows.append(
            {
                "x": float(z[i, 0]),
                "y": float(z[i, 1]),
                "kind": label,
                "zero": bool(zero),
                "home": bool(np.hypot(*(z[i] - home)) <= home_radius),
                "det_jacobian": float(np.linalg.det(jac[i])),
                "trace_jacobian": float(np.trace(jac[i])),
                "relative_residual": float(residual[i]),
                "starts": len(group),
            }
        )
    cx, cy, cres = (
        np.asarray(a)
        for a in two_cycles(
            problem.env, starts, problem.sensor, problem.method, problem.key, problem.tau, problem.sharpness
        )
    )
    away = (np.hypot(*(cx - home).T) > home_radius) & (np.hypot(*(cy - home).T) > home_radius)  # else: home reached
    closed = np.all(np.isfinite(cx), axis=1) & (cres < CYCLE_CM) & away
    for group in _merge(np.where(closed[:, None], cx, np.nan), CYCLE_MERGE_CM):  # a family of orbits: one row
        i = group[0]
        if closed[i] and not any(
            r["kind"] == "2-cycle" and np.hypot(r["x"] - cy[i, 0], r["y"] - cy[i, 1]) <= CYCLE_MERGE_CM for r in rows
        ):
            rows.append(
                {
                    "x": float(cx[i, 0]),
                    "y": float(cx[i, 1]),
                    "kind": "2-cycle",
                    "zero": False,
                    "home": False,
                    "partner_x": float(cy[i, 0]),
                    "partner_y": float(cy[i, 1]),
                    "relative_residual": float(cres[i]),
                    "starts": len(group),
                }
            )
    nearest = _nearest(ends, rows, lambda r: r["kind"] == "sink" and not r["home"])
    near_jump = _nearest(ends, rows, lambda r: r["kind"] == "discontinuity")
    near_cycle = np.minimum(
        _nearest(ends, rows, lambda r: r["kind"] == "2-cycle"),
        _nearest(
            ends, [{"x": r["partner_x"], "y": r["partner_y"]} for r in rows if r["kind"] == "2-cycle"], lambda r: True
        ),
    )
    summary = {
        "env": env.name,
        "method": method,
        "grid_points": int(inc.sum()),
        "catchment_pct": float(c.catchment_pct()[0]),
        "counted_points": int(np.asarray(c.counted).sum()),
        "failed_rollouts": failed_rollouts(c),
        "timed_out": int(timeout.sum()),
        "starts": int(len(starts)),
        "near_cm": near,
        "timed_out_within_near_of_a_sink": int((nearest <= near).sum()),
        "timed_out_within_near_of_a_discontinuity": int(((near_jump <= near) & (nearest > near)).sum()),
        "timed_out_on_a_2_cycle": int((near_cycle <= near).sum()),
        "two_cycles": sum(r["kind"] == "2-cycle" for r in rows),
        "sinks": sum(r["kind"] == "sink" and not r["home"] for r in rows),
        "home_sinks": sum(r["kind"] == "sink" and r["home"] for r in rows),
        "saddles": sum(r["kind"] == "saddle" for r in rows),
        "sources": sum(r["kind"] == "source" for r in rows),
        "discontinuities": sum(r["kind"] == "discontinuity" for r in rows),
        "tau": tau,
    }
    return TrapReport(
        env=env, method=method, catchment=c, points=rows, failed_ends=ends, nearest_sink_cm=nearest, summary=summary
    )
