"""Angular errors, error classes, error point rates and error curves (thesis §4.2; docs/model.md §5)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array
from jax.typing import ArrayLike

from .geometry import angle_of, wrap

CLASS_EDGES_DEG = (45.0, 90.0)
CLASS_NAMES = ("<45", "45-90", ">90")


@jax.jit  # one compiled program per shape instead of an eager op each
def angular_error_deg(direction: Array, valid: Array, points: Array, home: Array) -> Array:
    """|wrap(direction - angle(home - x))| in degrees; an invalid point counts as 180 (docs/model.md §5)."""
    ideal = angle_of(home - points)
    err = jnp.degrees(jnp.abs(wrap(direction - ideal)))
    return jnp.where(valid, err, 180.0)


def error_class(error_deg: ArrayLike) -> ArrayLike:
    """Spatial error class of Fig 4.3: 0 (< 45), 1 (45-90), 2 (> 90)."""
    return (error_deg > CLASS_EDGES_DEG[0]).astype(jnp.int32) + (error_deg > CLASS_EDGES_DEG[1]).astype(jnp.int32)


def error_point_rates(error_deg: ArrayLike, included: ArrayLike) -> dict[str, float]:
    """% of grid points with error > 45 and > 90 degrees (Tables 5.1/5.2)."""
    e = np.asarray(error_deg)[np.asarray(included)]
    n = max(e.size, 1)
    return {"gt45_pct": 100.0 * float(np.sum(e > 45.0)) / n, "gt90_pct": 100.0 * float(np.sum(e > 90.0)) / n}


def t_quantile(n, confidence: float = 0.95):
    """Student-t quantile of a two-sided `confidence` interval with n - 1 degrees of freedom, for a
    count or an array of counts (NaN where n < 2): the one t quantile of every interval delvjax
    reports (error curves, sweep metrics, sweep figures)."""
    from scipy import stats  # scipy.stats: 0.6 s of CPU to import, loaded where a quantile is asked for

    n = np.asarray(n)
    return np.where(n >= 2, stats.t.ppf(0.5 + confidence / 2, np.maximum(n - 1, 1)), np.nan)


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


def error_curve(
    error_deg: ArrayLike,
    points: ArrayLike,
    home: ArrayLike,
    included: ArrayLike,
    bin_width: float = 50.0,
    confidence: float = 0.95,
) -> list[dict[str, float]]:
    """Mean angular error per distance-from-home bin with a Student-t CI (Fig 4.4).

    Rows: bin_lo, bin_hi, n, mean_deg, ci_lo_deg, ci_hi_deg (CI NaN where n < 2).
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
                "ci_lo_deg": mean - half,
                "ci_hi_deg": mean + half,
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
