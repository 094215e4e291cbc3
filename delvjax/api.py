"""Python API for notebooks and scripts; mirrors the CLI (same names, same validation)."""

from __future__ import annotations

import math
from pathlib import Path

import jax
import jax.numpy as jnp

from . import maps
from .config import Config
from .errors import InputError
from .methods import get_method
from .options import finite, make_config, non_negative, positive, positive_int, seed_value
from .rollouts import catchment, success_rate, trajectories  # noqa: F401  (docs/model.md §5 rollouts)
from .scene import Env
from .scene import load_env as _load_env


def load_env(name_or_path: str | Path | Env) -> Env:
    """A preset (`env1`, `env2`, `env3`, `ring3`..`ring6`), a docs/model.md §7 JSON path, or an `Env` as is."""
    return name_or_path if isinstance(name_or_path, Env) else _load_env(name_or_path)


def resolve_headings(heading_deg: float | None, seed: int) -> tuple[float | None, jax.Array]:
    """(fixed heading in radians or None for seeded random headings, PRNG key)."""
    key = jax.random.PRNGKey(seed_value(seed))
    if heading_deg is None:
        return None, key
    return math.radians(finite(heading_deg, "heading_deg")), key


def visible_mask(env: Env, hidden: list[int] | tuple[int, ...] | None) -> jax.Array | None:
    """Boolean (L,) mask of the landmarks seen during homing, `hidden` ones occluded (docs/model.md §5)."""
    if not hidden:
        return None
    n = env.n_landmarks
    for i in hidden:
        if isinstance(i, bool) or not isinstance(i, int) or not 0 <= i < n:
            raise InputError("hide", i, f"must be a landmark index in 0..{n - 1}")
    return jnp.ones(env.landmarks.shape[0], bool).at[jnp.asarray(list(hidden))].set(False)


def scene_request(env: str | Path | Env, method: str, clearance: float, heading_deg: float | None, seed: int,
                  **config_kw) -> tuple[Env, Config, float | None, jax.Array, float]:
    """The options every evaluation shares, validated before any work: method name, grid
    clearance, `make_config` keywords, environment, heading/seed. Returns
    (env, config, heading rad | None, key, clearance)."""
    get_method(method)
    clearance = non_negative(clearance, "clearance")
    config = make_config(**config_kw)
    env = load_env(env)
    heading, key = resolve_headings(heading_deg, seed)
    return env, config, heading, key, clearance


def map_request(env: str | Path | Env, method: str = "delv", spacing: float = 25.0, heading_deg: float | None = None,
                seed: int = 0, levels: int | None = None, d: float = 50.0, background: str = "distant",
                channel: str = "mask", clearance: float = 10.0, n_heading: int = 360,
                hidden: list[int] | None = None, batch_size: int = maps.DEFAULT_BATCH, **noise: float) -> dict:
    """Validate the public options of a vector map (before any array work): keyword
    arguments of `maps.vector_map`. Raises `InputError` naming the field and value."""
    env, config, heading, key, clearance = scene_request(env, method, clearance, heading_deg, seed, d=d, levels=levels,
                                                         background=background, channel=channel,
                                                         n_heading=n_heading, **noise)
    spacing = positive(spacing, "spacing")
    batch_size = positive_int(batch_size, "batch_size")
    return dict(env=env, method=method, config=config, spacing=spacing, heading=heading, key=key,
                clearance=clearance, visible=visible_mask(env, hidden), batch_size=batch_size)


def vector_map(env: str | Path | Env, method: str = "delv", spacing: float = 25.0, heading_deg: float | None = None,
               seed: int = 0, levels: int | None = None, d: float = 50.0, background: str = "distant",
               channel: str = "mask", clearance: float = 10.0, n_heading: int = 360,
               hidden: list[int] | None = None, batch_size: int = maps.DEFAULT_BATCH, **noise: float) -> maps.VectorMap:
    """Homing direction of `method` at every docs/model.md §5 grid point, one jitted vmapped call.

    heading_deg fixes the heading at every point; otherwise headings are uniform random
    per point from `seed` (which also drives every noise source). Noise keywords:
    bearing_noise_deg, step_noise, turn_noise_deg, odometry_turn_noise_deg, compass_noise_deg.
    Warping hypotheses (docs/model.md §4.3) pass through the same keywords to `make_config`:
    n_alpha, n_psi, n_rho, rho_min, rho_max.
    `hidden` lists landmark indices invisible in the current views (occlusion).
    Returns a `VectorMap` pytree (points, included, heading, direction, valid, error_deg).
    """
    return maps.vector_map(**map_request(env, method, spacing, heading_deg, seed, levels, d, background, channel,
                                         clearance, n_heading, hidden, batch_size, **noise))
