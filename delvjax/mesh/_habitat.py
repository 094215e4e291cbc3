"""A habitat of our own that ships (docs/mesh.md §4): grass tussocks (blades: triangles standing on the ground,
two corners 10 cm apart on it and an apex above, as the Seville world's) and a few trees, seeded, with a
meandering route from a start to a nest that passes between the tussocks. Sizes follow the Seville world
(a 10 m square, about 5000 triangles, blades a median 18 cm high). Input preparation on the host (NumPy's
seeded generator, as `envs.random_env`): the same seed gives the same habitat everywhere."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import InputError
from ..core.polyline import distance_to

BLADE_BASE = 10.0  # cm between a blade's two ground corners (the Seville world's)


@dataclass
class Habitat:
    """vertices (T, 3, 3) cm; shade (T,) grey level in [0, 1]; route (N, 3) [x cm, y cm, heading rad] every
    `route_step` cm from its start to the nest; arena (4,) [xmin, ymin, xmax, ymax] cm."""

    name: str
    vertices: np.ndarray
    shade: np.ndarray
    route: np.ndarray
    arena: np.ndarray


def meander(rng: np.random.Generator, start: np.ndarray, nest: np.ndarray, step: float) -> np.ndarray:
    """(N, 3) a smooth route from start to nest: the straight line bent by two random sine waves sideways."""
    v = nest - start
    length = float(np.hypot(*v))
    s = np.linspace(0.0, 1.0, max(int(length / step), 2) * 4 + 1)
    side = np.array([-v[1], v[0]]) / length
    amp = rng.uniform(0.04, 0.1, 2) * length
    bend = amp[0] * np.sin(np.pi * s) * rng.choice([-1, 1]) + amp[1] * np.sin(
        2 * np.pi * s + rng.uniform(0, np.pi)
    ) * np.sin(np.pi * s)
    dense = start + s[:, None] * v + bend[:, None] * side
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(dense, axis=0).T))])
    at = np.append(np.arange(0.0, arc[-1], step), arc[-1])
    xy = np.stack([np.interp(at, arc, dense[:, k]) for k in range(2)], -1)
    d = np.diff(xy, axis=0)
    heading = np.append(np.arctan2(d[:, 1], d[:, 0]), np.arctan2(d[-1, 1], d[-1, 0]))
    return np.column_stack([xy, heading])


def habitat(
    seed: int = 0,
    size: float = 1000.0,
    tussocks: int = 250,
    blades: int = 20,
    trees: int = 3,
    clearance: float = 25.0,
    route_step: float = 1.0,
) -> Habitat:
    """A seeded habitat (module docstring): `tussocks` tussocks of `blades` blades in a `size` cm square, none
    within `clearance` cm of the route, and `trees` trees (a trunk and a crown of 60 triangles) away from it."""
    for name, v in (("tussocks", tussocks), ("blades", blades), ("trees", trees)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
            raise InputError(name, v, "must be an integer >= 0")
    if not (np.isfinite(size) and size >= 200.0):
        raise InputError("size", size, "must be at least 200 cm")
    if tussocks * blades + 62 * trees == 0:
        raise InputError("tussocks", tussocks, "and trees give no triangle: an empty world")
    rng = np.random.default_rng(seed)
    start, nest = np.array([0.63, 0.845]) * size, np.array([0.51, 0.10]) * size  # the Seville routes' ends
    route = meander(rng, start, nest, route_step)
    centres = np.empty((0, 2))
    radius = rng.uniform(8.0, 25.0, tussocks)
    while len(centres) < tussocks:  # rejection sampling of the tussocks clear of the route: input preparation
        c = rng.uniform(0.0, size, (2 * tussocks, 2))
        r = radius[len(centres) : len(centres) + len(c)]
        keep = distance_to(c[: len(r)], route) > clearance + r + BLADE_BASE
        centres = np.concatenate([centres, c[: len(r)][keep]])[:tussocks]
    parts = [tussock_blades(rng, c, r, blades) for c, r in zip(centres, radius)]
    for _ in range(trees):
        c = rng.uniform(0.1 * size, 0.9 * size, 2)
        while distance_to(c[None], route)[0] < 150.0:
            c = rng.uniform(0.1 * size, 0.9 * size, 2)
        parts.append(tree(rng, c))
    vertices = np.concatenate([p[0] for p in parts]) if parts else np.empty((0, 3, 3))
    shade = np.concatenate([p[1] for p in parts]) if parts else np.empty(0)
    return Habitat(f"habitat{seed}", vertices, shade, route, np.array([0.0, 0.0, size, size]))


def tussock_blades(rng: np.random.Generator, centre: np.ndarray, radius: float, n: int):
    """n blades about `centre`: ground corners BLADE_BASE apart, apexes leaning outwards, heights log-normal."""
    a = rng.uniform(0, 2 * np.pi, n)
    at = centre + (radius * np.sqrt(rng.uniform(0, 1, n)))[:, None] * np.stack([np.cos(a), np.sin(a)], -1)
    turn = rng.uniform(0, np.pi, n)
    half = 0.5 * BLADE_BASE * np.stack([np.cos(turn), np.sin(turn)], -1)
    height = np.minimum(np.exp(rng.normal(np.log(18.0), 0.5, n)), 160.0)
    lean = at + rng.normal(0, 0.3, (n, 1)) * height[:, None] * np.stack([np.cos(a), np.sin(a)], -1)
    v = np.zeros((n, 3, 3))
    v[:, 0, :2], v[:, 1, :2], v[:, 2, :2], v[:, 2, 2] = at - half, at + half, lean, height
    base = rng.uniform(0.15, 0.8)
    return v, np.clip(base + rng.normal(0, 0.1, n), 0.07, 0.98)


def tree(rng: np.random.Generator, centre: np.ndarray):
    """A trunk (two crossed 20 cm wide triangles) and a crown of 60 triangles about a sphere."""
    h, r = rng.uniform(250, 450), rng.uniform(80, 150)
    trunk = np.array([[[-10, 0, 0], [10, 0, 0], [0, 0, h]], [[0, -10, 0], [0, 10, 0], [0, 0, h]]], float)
    d = rng.normal(size=(60, 3, 3))
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    crown = np.array([0, 0, h]) + r * (0.8 * d[:, :1] + 0.35 * d)  # each triangle near one point of the sphere
    v = np.concatenate([trunk, crown]) + np.array([*centre, 0.0])
    return v, np.concatenate([[0.3, 0.3], rng.uniform(0.1, 0.4, 60)])
