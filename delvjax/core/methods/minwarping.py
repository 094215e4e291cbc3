"""MinWarping: local visual homing by warping of two-dimensional panoramas (Möller 2009, Robotics
and Autonomous Systems 57; Möller, Krzykawski & Gerstmayr 2010, Autonomous Robots 29;
docs/model.md §4.7).

The home panorama (the snapshot) and the current one are compared column by column at every
vertical scale factor (the scale-plane stack, `scale_planes`); for every movement direction alpha
and rotation psi each snapshot column takes its best match among the current columns that the
movement allows, whatever the distance of what it shows (the minimum over the column's template
entries, `warping_search`), and the hypothesis with the smallest sum wins. The home direction in the
agent's frame is alpha + pi - psi; psi, the current heading minus the snapshot's, is a visual
compass (`MinWarpingCompass`).

Refinements (the authors' defaults, all on): `double` searches again with the images' roles
swapped and adds the two match tables (a hypothesis and its way back are scored together); `fine`
then tries every whole-pixel alpha and psi within one grid step of the best and keeps one only
where its match is strictly smaller. `stack_type="uint8"` quantises every column distance to
round(200 d / d_max) (the authors' byte stack; sums of bytes are exact, so the search is exactly
reproducible and ~7x faster on CPU); `float32` keeps them as they are.
"""

from __future__ import annotations

import functools
import math
from typing import ClassVar

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..errors import InputError
from ..geometry import TWO_PI, wrap
from ..search import first_argmin
from ..sensing import UnitMove
from ..settings import declared, setting
from ..types import Arrays
from . import scale_planes as sp
from . import warping_search as ws
from .base import HomingMethod

REFINEMENTS = ("none", "double", "fine", "double+fine")
STACK_TYPES = ("uint8", "float32")
LEVELS = 200  # quantisation levels of the byte stack (the authors' post-scale)
MEASURE_MAX = {"nsad": 1.0, "nssd": 2.0}  # the largest value of a normalised distance


# the settings MinWarping and 2D-Warping share: default and declaration, one place for both. The hypothesis
# counts default to 72, which divides every panorama width delvjax renders or the studies use (360 by default,
# 288 as the authors', 72 in the tests); the authors' 96 x 96 (on 288 columns) is `AUTHORS_GRID` (issue 53)
AUTHORS_GRID = {"n_alpha": 96, "n_psi": 96}
PANORAMA_SETTINGS = {
    "n_alpha": (
        72,
        {"check": "positive_int", "limit": 3_600, "help": "movement directions alpha (divides the panorama width)"},
    ),
    "n_psi": (72, {"check": "positive_int", "limit": 3_600, "help": "rotations psi (divides the panorama width)"}),
    "n_planes": (9, {"check": "positive_int", "limit": 63, "help": "scale planes, odd (1 in the middle)"}),
    "max_scale": (2.0, {"check": "positive", "help": "largest scale factor of the planes"}),
    "measure": ("nsad", {"check": "choice", "choices": sp.MEASURES, "help": "column distance"}),
    "preprocess": (
        "edges",
        {"check": "choice", "choices": ("edges", "none"), "help": "compare vertical edge images or the images"},
    ),
    "stack_type": ("uint8", {"check": "choice", "choices": STACK_TYPES, "help": "quantised byte stack or float32"}),
}


def panorama_setting(field: str, prefix: str):
    """The declaration of a setting both panorama methods have, under the field's name (`n_alpha`: one
    option that sets MinWarping's and Warping2D's); formerly `{prefix}_{field}` (`mw_n_alpha`,
    `w2d_stack` for `stack_type`), read with a DeprecationWarning (docs/options.md "Renamed options")."""
    default, meta = PANORAMA_SETTINGS[field]
    former = "stack" if field == "stack_type" else field
    return setting(default, static=True, formerly=f"{prefix}_{former}", **meta)


MAX_WIDTH = 768  # the widest panorama MinWarping takes (`check_grid`: about 3 width^3 bytes a pair, 1.4 GB)


def hypothesis_counts(cols: int) -> list[int]:
    """The usual hypothesis counts (n_alpha, n_psi) that divide a panorama of `cols` columns, ascending."""
    return [k for k in (32, 36, 45, 48, 60, 64, 72, 90, 96, 120, 144) if cols % k == 0]


def check_grid(cfg, rows: int | None, cols: int) -> None:
    """`InputError` unless the hypothesis grid and scale planes suit (rows, cols) panoramas (trace
    time, and from the edge before any work; rows None: not known yet)."""
    name = {f: opt for opt, (f, _, _) in declared(type(cfg)).items()}  # field -> option, as users type it
    bad = [
        f
        for f in ("n_alpha", "n_psi")
        if isinstance(getattr(cfg, f), bool)
        or not isinstance(getattr(cfg, f), int)
        or getattr(cfg, f) < 1
        or cols % getattr(cfg, f)
    ]
    if bad:  # both named at once: 96 and 96 fail together on a 360-column panorama
        raise InputError(
            " and ".join(name[f] for f in bad),
            getattr(cfg, bad[0]) if len(bad) == 1 else tuple(getattr(cfg, f) for f in bad),
            f"must divide the panorama width {cols} (e.g. {hypothesis_counts(cols)})",
        )
    if cfg.n_planes < 3 or cfg.n_planes % 2 == 0:
        raise InputError(name["n_planes"], cfg.n_planes, "must be odd and >= 3 (symmetric scale factors around 1)")
    if not cfg.max_scale > 1.0:
        raise InputError(name["max_scale"], cfg.max_scale, "must be > 1")
    if getattr(cfg, "threshold", math.inf) <= 1.0:
        raise InputError(name["threshold"], cfg.threshold, "must be > 1 (the largest scale factor a column may take)")
    if "double" in getattr(cfg, "refine", "") and (cfg.n_alpha % cfg.n_psi or cfg.n_alpha % 2):
        raise InputError(name["n_psi"], cfg.n_psi, f"must divide n_alpha = {cfg.n_alpha} (even) for the double search")
    if rows is not None and rows < 3:
        raise InputError("panorama rows", rows, "must be >= 3")
    if cols > MAX_WIDTH:
        raise InputError(
            "panorama width",
            cols,
            f"is more than {MAX_WIDTH} columns: the search's memory grows as width^3 (about 3 width^3 bytes a "
            "pair; 7200 columns asked for 1.1 TB): use narrower panoramas (n_pix on a ring scene)",
        )


def quantised(stk: Arrays, measure: str, stack_type: str) -> Array:
    """The stack the search reads: uint8 round(LEVELS d / d_max) (d_max the measure's largest
    value, or the stack's for `sad`/`ssd`), or float32 as it is."""
    if stack_type == "float32":
        return stk
    top = MEASURE_MAX.get(measure)
    top = jnp.maximum(jnp.max(stk), 1e-30) if top is None else top
    return jnp.round(jnp.clip(stk / top, 0.0, 1.0) * LEVELS).astype(jnp.uint8)


@functools.lru_cache(maxsize=16)
def _steps(w: int, n_alpha: int, n_psi: int, scales: tuple, threshold: float):
    entries = ws.min_template(w, scales, threshold, 0.0, math.inf)
    return entries, ws.group_steps(ws.run_template(entries, w, len(scales)), w, n_alpha, n_psi)


@functools.lru_cache(maxsize=16)
def _groups(w: int, scales: tuple, threshold: float) -> dict:
    """The template grouped by column for the fine search (`ws.column_groups`)."""
    return ws.column_groups(ws.min_template(w, scales, threshold, 0.0, math.inf))


def search(ss: Arrays, cv: Arrays, elevations: Arrays, cfg: "MinWarping") -> tuple[Array, Array, Array]:
    """docs/model.md §4.7: (alpha, psi) in whole pixels and the match at the best hypothesis.

    ss, cv: (rows, cols) gray panoramas, snapshot and current view; elevations: (rows,) rad."""
    rows, w = ss.shape
    check_grid(cfg, rows, w)
    scales = tuple(float(s) for s in sp.scale_factors(cfg.n_planes, cfg.max_scale))
    entries, steps = _steps(w, cfg.n_alpha, cfg.n_psi, scales, float(cfg.threshold))
    stk = quantised(
        sp.stack(ss, cv, elevations, np.asarray(scales), cfg.measure, cfg.preprocess == "edges"),
        cfg.measure,
        cfg.stack_type,
    )
    double = "double" in cfg.refine
    inv = sp.inverted(stk) if double else None
    match = ws.min_match(ws.run_windows(sp.arranged(stk, cfg.n_alpha, cfg.n_psi)), steps, cfg.n_alpha, cfg.n_psi)
    if double:
        back = ws.min_match(ws.run_windows(sp.arranged(inv, cfg.n_alpha, cfg.n_psi)), steps, cfg.n_alpha, cfg.n_psi)
        im, ia = ws.inverse_index(cfg.n_alpha, cfg.n_psi)
        match = match + back[im, ia]
    best = first_argmin(match.reshape(-1))  # psi-major, alpha-minor: the first minimum wins
    m, a = best // cfg.n_alpha, best % cfg.n_alpha
    value = match.reshape(-1)[best]
    alpha, psi = a * (w // cfg.n_alpha), m * (w // cfg.n_psi)
    if "fine" in cfg.refine:
        groups = _groups(w, scales, float(cfg.threshold)) if jnp.issubdtype(stk.dtype, jnp.integer) else None
        alpha, psi, value = _fine(stk, inv, entries, groups, alpha, psi, value, w // cfg.n_alpha, w // cfg.n_psi)
    return alpha, psi, value


def _fine(stk, inv, entries, groups, alpha, psi, value, step_alpha: int, step_psi: int):
    """Every whole-pixel (alpha, psi) within one grid step of the best; a candidate replaces it only
    where its match is strictly smaller (so the minimum never grows). On the byte stack all candidates
    at once from windows of the stack (`fine_windows`, the same integers); on float32 one candidate
    at a time (the order of its float sums kept)."""
    w = stk.shape[-1]
    da = np.arange(-(step_alpha - 1), step_alpha)
    dp = np.arange(-(step_psi - 1), step_psi)
    off_p, off_a = (jnp.asarray(g.reshape(-1)) for g in np.meshgrid(dp, da, indexing="ij"))
    cand_a, cand_p = (alpha + off_a) % w, (psi + off_p) % w

    def score(a, p):
        v = ws.min_match_at(stk, entries, a, p)
        if inv is not None:  # the way back: alpha' = alpha + pi - psi, psi' = -psi
            v = v + ws.min_match_at(inv, entries, (a + w // 2 - p) % w, (-p) % w)
        return v

    if groups is None:
        values = jax.vmap(score)(cand_a, cand_p)
    else:
        values = fine_windows(stk, groups, alpha, psi, step_alpha, step_psi, inv is not None).reshape(-1)
    k = first_argmin(values)
    better = values[k] < value
    return jnp.where(better, cand_a[k], alpha), jnp.where(better, cand_p[k], psi), jnp.minimum(values[k], value)


def fine_windows(stk, groups: dict, alpha, psi, step_alpha: int, step_psi: int, double: bool) -> Array:
    """(2 step_psi - 1, 2 step_alpha - 1) int32 matches of every (alpha + da, psi + dp), [dp, da], as
    `ws.min_match_at` gives them one at a time (plus the way back with `double`).

    With g = `ws.window_stack(stk)`, g[s, t, u] = stk[s, t, t - u]: entry (x, y, plane) reads at
    hypothesis (a, p) stk[plane, x + a, x + a + y - p] = g[plane, x + a, p - y], and on the way back
    (a' = a + w/2 - p, p' = -p, the swapped stack plane S - 1 - s transposed, `sp.inverted`)
    stk[S - 1 - plane, x + y + a + w/2, x + a + w/2 - p] = g[S - 1 - plane, x + y + a + w/2, y + p]. Over
    da and dp both are one window of g per entry."""
    w, n_planes = stk.shape[-1], stk.shape[0]
    rows, cols = 2 * step_alpha - 1, 2 * step_psi - 1
    g = ws.window_stack(stk, rows, cols)
    x, y, plane = (jnp.asarray(groups[k]) for k in ("x", "y", "plane"))
    a0, p0 = alpha - (step_alpha - 1), psi - (step_psi - 1)
    out = ws.window_match(g, groups, plane, x + a0, p0 - y, rows, cols)
    if double:
        out = out + ws.window_match(g, groups, n_planes - 1 - plane, x + y + a0 + w // 2, y + p0, rows, cols)
    return out.T


class MinWarping(HomingMethod):
    """MinWarping on the gray panoramas of the two views (docs/model.md §4.7); no compass: psi is
    searched. Home direction alpha + pi - psi in the agent frame; invalid (NaN) where the home
    panorama is uniform."""

    n_alpha: int = panorama_setting("n_alpha", "mw")
    n_psi: int = panorama_setting("n_psi", "mw")
    n_planes: int = panorama_setting("n_planes", "mw")
    max_scale: float = panorama_setting("max_scale", "mw")
    threshold: float = setting(
        2.5, static=True, check="positive", help="largest scale factor a column may take", formerly="mw_threshold"
    )
    measure: str = panorama_setting("measure", "mw")
    preprocess: str = panorama_setting("preprocess", "mw")
    refine: str = setting(
        "double+fine", static=True, check="choice", choices=REFINEMENTS, help="search refinements", formerly="mw_refine"
    )
    stack_type: str = panorama_setting("stack_type", "mw")

    def estimate(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array, Array]:
        """(home direction in the agent frame, psi = current heading minus home heading, valid)."""
        ss, cv = panorama_of(home.start), panorama_of(view.end)
        alpha, psi, _ = search(ss, cv, home.start.elevations, self)
        w = ss.shape[-1]
        a, p = TWO_PI * alpha / w, TWO_PI * psi / w
        valid = jnp.any(ss != ss.reshape(-1)[0])
        return jnp.where(valid, wrap(a + math.pi - p), jnp.nan), jnp.where(valid, wrap(p), jnp.nan), valid

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        angle, _, valid = self.estimate(home, view)
        return angle, valid

    def reads_panorama(self) -> bool:
        return True

    def check_input(self, n_pix: int) -> None:
        check_grid(self, None, n_pix)


def panorama_of(snap) -> Array:
    """The gray panorama of a snapshot as float32 (bytes, as the image pipeline keeps them, to [0, 1])."""
    if getattr(snap, "panorama", None) is None:
        raise InputError(
            "method", "minwarping", "reads panoramas: run it on an image database or a rendered world (--images)"
        )
    p = snap.panorama
    return p.astype(jnp.float32) / 255.0 if p.dtype == jnp.uint8 else p.astype(jnp.float32)


class MinWarpingCompass(eqx.Module):
    """MinWarping's psi as a heading source (docs/model.md §4.4, §4.7): the estimate of h - alpha_r
    (NaN where the home panorama is uniform)."""

    reads_gray: ClassVar[bool] = False
    reads_panorama: ClassVar[bool] = True
    warping: MinWarping = MinWarping()

    def __call__(self, home: UnitMove, view: UnitMove) -> Array:
        return self.warping.estimate(home, view)[1]

    def check_input(self, n_pix: int) -> None:
        self.warping.check_input(n_pix)
