"""Angular errors, error classes, error point rates and error curves (thesis §4.2; docs/model.md §5), and the
one table of the metrics delvjax reports (`METRICS`: name, description, unit, formula; docs/sweeps.md "Metrics")."""

from __future__ import annotations

from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array
from jax.typing import ArrayLike

from .deprecation import keywords_after
from .geometry import angle_of, wrap

CLASS_EDGES_DEG = (45.0, 90.0)  # the one place of these thresholds: error classes and error point rates
CLASS_NAMES = ("<45", "45-90", ">90")


class Metric(NamedTuple):
    """One row of the metrics table: the name a sweep file, a summary and a CSV column use, what it means
    (a sweep's `long_name`), its CF units (`percent`, `degree`, `1`), how it is computed (text), and for an
    error point rate the threshold every path counts above (`over_edges`)."""

    name: str
    description: str
    unit: str
    formula: str
    edge_deg: float | None = None


_N = "n the directions counted (a vector map's included grid points; a catchment's first directions, points x masks)"
MAP_METRICS = (
    Metric(
        "gt45_pct",
        "% of grid points with angular error > 45 deg (Tables 5.1/5.2)",
        "percent",
        f"100 #(error > {CLASS_EDGES_DEG[0]:g} deg) / n, error = `angular_error_deg` (invalid = 180), {_N}",
        CLASS_EDGES_DEG[0],
    ),
    Metric(
        "gt90_pct",
        "% of grid points with angular error > 90 deg",
        "percent",
        f"100 #(error > {CLASS_EDGES_DEG[1]:g} deg) / n",
        CLASS_EDGES_DEG[1],
    ),
    Metric("mean_error_deg", "mean angular error over the grid points, invalid = 180 deg", "degree", "sum(error) / n"),
    Metric(
        "mean_error_ci95_deg",
        "half-width of the 95 % Student-t interval of that mean over this cell's grid points "
        "(the spread of one map's points, not over seeds or worlds: for that, sweep a seed axis)",
        "degree",
        "t(0.975, n - 1) s / sqrt(n), s^2 = (sum(error^2) - n mean^2) / (n - 1) (`t_quantile`; NaN for n < 2)",
    ),
    Metric("invalid_pct", "% of grid points without a homing direction", "percent", "100 #invalid / n"),
    Metric("points", "grid points evaluated", "1", "n"),
)
_COUNTED = "c the counted trials (counted points x masks; `rules.catchment_counted`)"
CATCHMENT_METRICS = (
    Metric(
        "catchment_pct",
        "% of counted grid points whose rollout reaches home, mean over the masks (Tables 5.3/5.4; "
        "under first_move = release the points at least d from every wall, docs/model.md section 5)",
        "percent",
        f"100 successes / c, {_COUNTED}",
    ),
    Metric(
        "catchment_physical_pct",
        "catchment_pct restated under collisions = fail from the same trials (a trial that "
        "touches a landmark fails; docs/model.md section 5): under collisions = ignore, the physical rules' catchment "
        "without a second run",
        "percent",
        "100 #(successes that never touched a landmark) / c (`rules.under_collisions`)",
    ),
    Metric(
        "catchment_min_pct", "the same under the worst mask", "percent", "100 min(successes per mask) / counted points"
    ),
    Metric(
        "catchment_max_pct", "the same under the best mask", "percent", "100 max(successes per mask) / counted points"
    ),
    Metric("catchment_points", "grid points counted in the catchment", "1", "counted points"),
    Metric("timeout_pct", "% of counted trials (points x masks) that ran out of moves", "percent", "100 #timeout / c"),
    Metric(
        "landmark_pct",
        "% of counted trials that ended inside a landmark (collisions = fail)",
        "percent",
        "100 #landmark / c",
    ),
    Metric("arena_pct", "% of counted trials that left the arena", "percent", "100 #arena / c"),
    Metric("mean_steps_success", "mean moves of the successful trials", "1", "sum(moves of successes) / successes"),
)
SUCCESS_METRICS = (
    Metric(
        "success_pct",
        "% of placed trials that reach home, per release distance (Figs 4.10b, 5.7b)",
        "percent",
        "100 successes / placed, per distance, pooled over the masks",
    ),
    Metric(
        "success_ci95_lo_pct",
        "lower end of its 95 % Wilson interval",
        "percent",
        "Wilson 95 % interval of successes / placed, lower end (`rollouts.success.wilson_pct`)",
    ),
    Metric(
        "success_ci95_hi_pct",
        "upper end of its 95 % Wilson interval",
        "percent",
        "the same, upper end",
    ),
    Metric("placed", "trials placed per distance (over every mask)", "1", "placed trials (`release_points`)"),
)
FOLLOWING_METRICS = (  # route following by familiarity (docs/familiarity.md §3.2)
    Metric(
        "route_success_pct",
        "% of route-following trials that end within 20 cm of the route's end (Ardin et al. 2016)",
        "percent",
        "100 successes / trials",
    ),
    Metric("route_success_ci95_lo_pct", "lower end of its 95 % Wilson interval", "percent", "Wilson, lower end"),
    Metric("route_success_ci95_hi_pct", "upper end of its 95 % Wilson interval", "percent", "the same, upper end"),
    Metric(
        "mean_route_errors",
        "returns to the route per trial (more than 20 cm off it, in an obstacle or out of the arena)",
        "1",
        "sum(errors) / trials",
    ),
    Metric("mean_moves", "moves per trial (successes and timeouts)", "1", "sum(moves) / trials"),
    Metric("trials_run", "route-following trials run", "1", "trials"),
)
METRICS = {m.name: m for m in MAP_METRICS + CATCHMENT_METRICS + SUCCESS_METRICS + FOLLOWING_METRICS}  # name -> row
RATES = tuple(m for m in MAP_METRICS if m.edge_deg is not None)  # the error point rates, gt45_pct and gt90_pct


def over_edges(error_deg: ArrayLike) -> tuple:
    """(error > 45, error > 90) for NumPy or JAX errors, in degrees: the masks every error point rate counts
    (`RATES`, their `edge_deg`: `CLASS_EDGES_DEG`), the vector map's, a sweep cell's and a catchment's."""
    return tuple(error_deg > m.edge_deg for m in RATES)


@jax.jit  # one compiled program per shape instead of an eager op each
def angular_error_deg(direction: Array, valid: Array, points: Array, home: Array) -> Array:
    """|wrap(direction - angle(home - x))| in degrees; an invalid point counts as 180 (docs/model.md §5)."""
    ideal = angle_of(home - points)
    err = jnp.degrees(jnp.abs(wrap(direction - ideal)))
    return jnp.where(valid, err, 180.0)


def error_class(error_deg: ArrayLike) -> ArrayLike:
    """Spatial error class of Fig 4.3: 0 (< 45), 1 (45-90), 2 (> 90)."""
    low, high = over_edges(error_deg)
    return low.astype(jnp.int32) + high.astype(jnp.int32)


def error_point_rates(error_deg: ArrayLike, included: ArrayLike) -> dict[str, float]:
    """% of grid points with error > 45 and > 90 degrees (Tables 5.1/5.2)."""
    e = np.asarray(error_deg)[np.asarray(included)]
    n = max(e.size, 1)
    return {m.name: 100.0 * float(np.sum(over)) / n for m, over in zip(RATES, over_edges(e))}


def t_quantile(n, confidence: float = 0.95):
    """Student-t quantile of a two-sided `confidence` interval with n - 1 degrees of freedom, for a
    count or an array of counts (NaN where n < 2): the one t quantile of every interval delvjax
    reports (error curves, sweep metrics, sweep figures)."""
    from scipy.special import stdtrit  # what scipy.stats.t.ppf computes, without 0.5-1 s of importing scipy.stats

    n = np.asarray(n)
    return np.where(n >= 2, stdtrit(np.maximum(n - 1, 1), 0.5 + confidence / 2), np.nan)


def t_interval(values: np.ndarray, confidence: float = 0.95) -> tuple[float, float, int]:
    """Mean and Student-t half-width of a sample: (mean, half_width, n); half-width NaN for n < 2."""
    v = np.asarray(values, dtype=np.float64)
    n = v.size
    if n == 0:
        return float("nan"), float("nan"), 0
    mean = float(v.mean())
    if n < 2:
        return mean, float("nan"), n
    half = float(t_quantile(n, confidence) * v.std(ddof=1) / np.sqrt(n))
    return mean, half, n


@keywords_after(4, ("bin_width", "confidence"))
def error_curve(
    error_deg: ArrayLike,
    points: ArrayLike,
    home: ArrayLike,
    included: ArrayLike,
    *,
    bin_width: float = 50.0,
    confidence: float = 0.95,
) -> list[dict[str, float]]:
    """Mean angular error per distance-from-home bin with a Student-t CI (Fig 4.4).

    Rows: bin_lo, bin_hi, n, mean_deg, ci_lo_deg, ci_hi_deg (CI NaN where n < 2; clipped to the errors'
    range 0-180 deg, which a t interval of a few points near 0 would leave).
    """
    inc = np.asarray(included)
    e = np.asarray(error_deg)[inc]
    dist = np.linalg.norm(np.asarray(points)[inc] - np.asarray(home), axis=-1)
    rows = []
    if e.size == 0:
        return rows
    n_bins = int(np.floor(dist.max() / bin_width)) + 1
    for b in range(n_bins):  # a handful of bins: post-processing, not a hot path
        sel = (dist >= b * bin_width) & (dist < (b + 1) * bin_width)
        if not np.any(sel):
            continue
        mean, half, n = t_interval(e[sel], confidence)
        rows.append(
            {
                "bin_lo": b * bin_width,
                "bin_hi": (b + 1) * bin_width,
                "n": n,
                "mean_deg": mean,
                "ci_lo_deg": float(np.clip(mean - half, 0.0, 180.0)),  # NaN (n < 2) stays NaN
                "ci_hi_deg": float(np.clip(mean + half, 0.0, 180.0)),
            }
        )
    return rows


def summarize_map(error_deg: ArrayLike, valid: ArrayLike, included: ArrayLike) -> dict[str, float]:
    """Headline numbers of one vector map: point counts, invalid count, mean error, error point rates."""
    inc = np.asarray(included)
    e = np.asarray(error_deg)[inc]
    out = {
        "points": int(inc.sum()),
        "invalid": int((~np.asarray(valid)[inc]).sum()),
        "mean_error_deg": float(e.mean()) if e.size else float("nan"),
    }
    out.update(error_point_rates(error_deg, included))
    return out
