"""2D-Warping: the full search over movement direction alpha, rotation psi and relative distance rho
on gray panoramas (Möller 2009 §3; Möller, Krzykawski & Gerstmayr 2010 §3.4; docs/model.md §4.7).

Every point is assumed at one distance r from home (the equal-distance assumption of 1-D warping,
docs/model.md §4.3), rho = d / r. A snapshot column at x from the movement direction then appears
y = atan2(rho sin x, 1 - rho cos x) further on (the nearest column) at the distance ratio
sigma = r' / r = sqrt(1 + rho^2 - 2 rho cos x) (the nearest scale plane): one template entry per
column and rho (`warping_search.rho_template`), read from the same scale-plane stack as MinWarping.
The match of (alpha, psi, rho) is the sum over all columns; the first minimum in (rho, psi, alpha)
order wins. Home direction alpha + pi - psi in the agent frame. No double or fine search: the
authors define them for MinWarping.
"""

from __future__ import annotations

import functools
import math

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..errors import InputError
from ..geometry import TWO_PI, wrap
from ..search import first_argmin
from ..sensing import UnitMove
from ..settings import setting
from ..types import Arrays
from . import scale_planes as sp
from . import warping_search as ws
from .base import HomingMethod
from .minwarping import check_grid, panorama_of, panorama_setting, quantised


@functools.lru_cache(maxsize=16)
def _steps(w: int, n_alpha: int, n_psi: int, scales: tuple, rhos: tuple) -> dict[str, np.ndarray]:
    rows = ws.rho_template(w, scales, rhos)
    parts = [ws.rho_steps(r, w, n_alpha, n_psi) for r in rows]
    return {k: np.stack([p[k] for p in parts]) for k in parts[0]}


def rho_values(cfg: "Warping2D") -> tuple[float, ...]:
    """n_rho values from rho_min to rho_max (rho_min alone for n_rho = 1)."""
    if cfg.n_rho == 1:
        return (float(cfg.rho_min),)
    return tuple(float(v) for v in np.linspace(cfg.rho_min, cfg.rho_max, cfg.n_rho))


def search(ss: Arrays, cv: Arrays, elevations: Arrays, cfg: "Warping2D") -> tuple[Array, Array, Array, Array]:
    """(alpha, psi) in whole pixels, the rho index and the match at the best hypothesis."""
    rows, w = ss.shape
    check_grid(cfg, rows, w)
    scales = tuple(float(s) for s in sp.scale_factors(cfg.n_planes, cfg.max_scale))
    steps = _steps(w, cfg.n_alpha, cfg.n_psi, scales, rho_values(cfg))
    stk = sp.stack(ss, cv, elevations, np.asarray(scales), cfg.measure, cfg.preprocess == "edges")
    arr = sp.arranged(quantised(stk, cfg.measure, cfg.stack_type), cfg.n_alpha, cfg.n_psi, doubled=True)
    tables = jax.lax.map(
        lambda s: ws.sum_match(arr, s, cfg.n_alpha, cfg.n_psi), {k: jnp.asarray(v) for k, v in steps.items()}
    )
    best = first_argmin(tables.reshape(-1))  # rho-major, then psi, then alpha
    per_rho = cfg.n_psi * cfg.n_alpha
    r, m, a = best // per_rho, (best % per_rho) // cfg.n_alpha, best % cfg.n_alpha
    return a * (w // cfg.n_alpha), m * (w // cfg.n_psi), r, tables.reshape(-1)[best]


class Warping2D(HomingMethod):
    """2D-Warping on the gray panoramas of the two views (docs/model.md §4.7); no compass. Home
    direction alpha + pi - psi in the agent frame; invalid (NaN) where the home panorama is uniform."""

    n_alpha: int = panorama_setting("n_alpha", "w2d")
    n_psi: int = panorama_setting("n_psi", "w2d")
    n_rho: int = setting(
        20, static=True, check="positive_int", limit=1_000, help="values of rho = d / r", formerly="w2d_n_rho"
    )
    rho_min: float = setting(0.0, static=True, check="non_negative", help="smallest rho", formerly="w2d_rho_min")
    rho_max: float = setting(1.0, static=True, check="non_negative", help="largest rho (<= 1)", formerly="w2d_rho_max")
    n_planes: int = panorama_setting("n_planes", "w2d")
    max_scale: float = panorama_setting("max_scale", "w2d")
    measure: str = panorama_setting("measure", "w2d")
    preprocess: str = panorama_setting("preprocess", "w2d")
    stack_type: str = panorama_setting("stack_type", "w2d")

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        ss, cv = panorama_of(home.start), panorama_of(view.end)
        alpha, psi, _, _ = search(ss, cv, home.start.elevations, self)
        w = ss.shape[-1]
        valid = jnp.any(ss != ss.reshape(-1)[0])
        angle = wrap(TWO_PI * alpha / w + math.pi - TWO_PI * psi / w)
        return jnp.where(valid, angle, jnp.nan), valid

    def reads_panorama(self) -> bool:
        return True

    def check_input(self, n_pix: int) -> None:
        check_grid(self, None, n_pix)
        if not self.rho_min <= self.rho_max <= 1.0:
            raise InputError("rho_max", self.rho_max, f"must be in [rho_min = {self.rho_min}, 1]")
