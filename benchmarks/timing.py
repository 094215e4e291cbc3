"""Shared timing of a jitted vector-map program: compile once, then warm runs (wall and CPU)."""

from __future__ import annotations

import time

import jax
import numpy as np

import delvjax
from delvjax.core import maps
from delvjax.core.sensor import Sensor
from delvjax.options._registry import METHODS


def time_map_program(env_name: str, method: str, sensor: Sensor, spacing: float, repeats: int) -> dict:
    """Compile `maps.homing_directions` of the registry method `method` for the full grid, then time
    `repeats` warm runs.

    Returns env, points, headings, compile_s, warm (list of wall seconds), cpu (list of CPU seconds).
    """
    env = delvjax.load_env(env_name).arrays()
    key = jax.random.PRNGKey(0)
    points = jax.numpy.asarray(maps.grid_points(env.arena, spacing))
    headings = maps.random_headings(key, points.shape[0])
    t0 = time.perf_counter()
    module = METHODS[method]
    compiled = maps.homing_directions.lower(env, points, headings, key, sensor, module).compile()
    compile_s = time.perf_counter() - t0
    jax.block_until_ready(compiled(env, points, headings, key, sensor, module))
    warm, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        jax.block_until_ready(compiled(env, points, headings, key, sensor, module))
        warm.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return {"env": env, "points": points, "headings": headings, "compile_s": compile_s, "warm": warm, "cpu": cpu}


def reference_seconds_per_point(reference_direction, run: dict, method: str, n_points: int, **kw) -> float:
    """Mean wall time of a per-point NumPy twin `reference_direction(landmarks, arena, home,
    point, heading, method, **kw)` on `n_points` points spread over the grid of `run`."""
    env, points, headings = run["env"], run["points"], run["headings"]
    lms, arena, home = np.asarray(env.landmarks), np.asarray(env.arena), np.asarray(env.home)
    idx = np.linspace(0, points.shape[0] - 1, n_points + 2).astype(int)[1:-1]
    t0 = time.perf_counter()
    for i in idx:  # the twin is per point by design
        reference_direction(lms, arena, home, np.asarray(points[i], float), float(headings[i]), method, **kw)
    return (time.perf_counter() - t0) / len(idx)
