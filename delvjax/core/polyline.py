"""Routes as polylines on the host (input preparation, NumPy): points every `spacing` cm along waypoints, the
direction of travel at each, a route's length and the distance of points from it (docs/familiarity.md §3)."""

from __future__ import annotations

import numpy as np


def resample(waypoints: np.ndarray, spacing: float) -> np.ndarray:
    """(N, 2): points every `spacing` cm along the polyline (the last waypoint included)."""
    seg = np.diff(waypoints, axis=0)
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*seg.T))])
    s = np.append(np.arange(0.0, cum[-1], spacing), cum[-1])
    s = s[np.append(np.diff(s) > 1e-6 * spacing, True)]
    return np.stack([np.interp(s, cum, waypoints[:, k]) for k in range(2)], -1)


def headings_along(points: np.ndarray) -> np.ndarray:
    """(N,) rad: the direction to the next point (the last repeats the one before)."""
    d = np.diff(points, axis=0)
    h = np.arctan2(d[:, 1], d[:, 0])
    return np.append(h, h[-1])


def route_length(points: np.ndarray) -> float:
    """cm along the polyline through `points` (N, 2)."""
    return float(np.sum(np.hypot(*np.diff(np.asarray(points, np.float64), axis=0).T)))


def distance_to(points: np.ndarray, route: np.ndarray) -> np.ndarray:
    """(P,) cm from every point (P, 2) to the route's polyline."""
    a, b = route[:-1, None, :2], route[1:, None, :2]
    ab = b - a
    t = np.clip(np.sum((points - a) * ab, -1) / np.maximum(np.sum(ab * ab, -1), 1e-12), 0.0, 1.0)
    return np.min(np.linalg.norm(a + t[..., None] * ab - points, axis=-1), 0)
