"""The search of 2D-warping over movement direction alpha and rotation psi (Möller 2009 §3-4;
Möller, Krzykawski & Gerstmayr 2010 §3-4; docs/model.md §4.7).

Frames: columns count counter-clockwise, column j of a panorama at azimuth 2 pi j / w in its own
frame. Hypothesis (alpha, psi): the agent moved from home along alpha (snapshot frame) and turned
by psi (current heading minus snapshot heading). A point at snapshot azimuth theta = alpha + x
(x relative to the movement) seen from the current place at snapshot-frame azimuth alpha + x + y
lies in current column theta + y - psi. Triangle home, current place, point (law of sines):

    sigma = r' / r = sin x / sin(x + y),   rho = d / r = sin y / sin(x + y),

so y runs from 0 towards pi - x (x in (0, pi); towards -x on the other side). A template lists,
for every x, its entries (y, plane of sigma); MinWarping takes per snapshot column the minimum over
its entries (any distance, Möller 2009 Eq 11), 2D-Warping one entry per rho (every point at one
distance). The match of (alpha, psi) is the sum over the snapshot's columns (x = 0 and x = pi
carry no information and are left out, as the authors do).

How it is fast: in the arranged stack (`scale_planes.arranged`) one template entry reads one
contiguous (n_psi, n_alpha) block, so the search is a scan over template entries, U at a time,
each a vectorised min over whole blocks; no gather in the inner loop.
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array, lax

from ..types import Arrays
from .scale_planes import plane_of, skewed

UNROLL = 8  # template entries per scan step (padding repeats an entry: min is idempotent)


@functools.lru_cache(maxsize=32)
def min_template(w: int, scales: tuple[float, ...], threshold: float, rho_min: float, rho_max: float) -> np.ndarray:
    """(T, 3) int32 rows (x, y mod w, plane) of the MinWarping template, sorted by x: every
    displacement y of column x with rho in [rho_min, rho_max] and sigma <= threshold."""
    rows = []
    half = w // 2
    for ix in range(1, w):
        if 2 * ix == w:
            continue
        side = 1 if 2 * ix < w else -1
        n = half - ix if side > 0 else ix - (w + 1) // 2
        iy = side * np.arange(max(n, 0))
        x, y = 2 * np.pi * ix / w, 2 * np.pi * iy / w
        sigma, rho = np.sin(x) / np.sin(x + y), np.sin(y) / np.sin(x + y)
        plane = plane_of(sigma, np.asarray(scales), threshold)
        keep = (rho >= rho_min) & (rho <= rho_max) & (plane >= 0)
        rows += [(ix, iy[k] % w, plane[k]) for k in np.flatnonzero(keep)]
    return np.asarray(rows, np.int32).reshape(-1, 3)


@functools.lru_cache(maxsize=32)
def rho_template(w: int, scales: tuple[float, ...], rhos: tuple[float, ...]) -> np.ndarray:
    """(n_rho, w, 3) int32 rows (x, y mod w, plane) of 2D-Warping: every column at distance r = d / rho
    from home, y = atan2(rho sin x, 1 - rho cos x) to the nearest column, sigma = sqrt(1 + rho^2 -
    2 rho cos x) to the nearest plane (beyond the largest factor: the last plane)."""
    x = 2 * np.pi * np.arange(w) / w
    rho = np.asarray(rhos)[:, None]
    y = np.arctan2(rho * np.sin(x), 1.0 - rho * np.cos(x))
    y = np.where((rho == 1.0) & (x == 0.0), np.pi / 2, y)  # the point itself: the authors' limit
    iy = np.rint(y * w / (2 * np.pi)).astype(np.int64) % w
    sigma = np.sqrt(1.0 + rho**2 - 2.0 * rho * np.cos(x))
    plane = plane_of(sigma, np.asarray(scales), np.inf)
    ix = np.broadcast_to(np.arange(w), iy.shape)
    return np.stack([ix, iy, plane], -1).astype(np.int32)


def _padded_groups(entries: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The entries grouped by x in parts of UNROLL (a group padded by repeating its last entry: min is
    idempotent): (parts (S, UNROLL, 3), whether each part is the first and the last of its x)."""
    steps = []
    for ix in np.unique(entries[:, 0]):
        group = entries[entries[:, 0] == ix]
        pad = (-len(group)) % UNROLL
        group = np.concatenate([group, np.repeat(group[-1:], pad, 0)])
        parts = group.reshape(-1, UNROLL, 3)
        for k, part in enumerate(parts):
            steps.append((part, k == 0, k == len(parts) - 1))
    return np.stack([s[0] for s in steps]), np.array([s[1] for s in steps]), np.array([s[2] for s in steps])


def group_steps(entries: np.ndarray, w: int, n_alpha: int, n_psi: int) -> dict[str, np.ndarray]:
    """The template grouped by x into scan steps of UNROLL entries (`_padded_groups`): per step the
    block starts (plane, ry, t0, rx, qx), (steps, UNROLL), and whether the step is the first and the
    last of its x."""
    sa, sp = w // n_alpha, w // n_psi
    part, first, last = _padded_groups(entries)
    x, y, plane = part[..., 0], part[..., 1], part[..., 2]
    return {
        "plane": plane,
        "ry": y % sp,
        "t0": (-(y // sp)) % n_psi,
        "rx": x % sa,
        "qx": x // sa,
        "first": first,
        "last": last,
    }


# a read covers up to 2^RUN_LEVELS consecutive displacements (`run_template`, `run_windows`); 2 measured
# best (docs/model.md §4.7): 3 is 5 % slower at the authors' 288 columns, where 4 levels leave the cache
RUN_LEVELS = 2


def run_template(entries: np.ndarray, w: int, n_planes: int, levels: int = RUN_LEVELS) -> np.ndarray:
    """The MinWarping template as reads of windows (`run_windows`): (R, 3) rows (x, y, k n_planes + plane),
    each the minimum over displacements y .. y + 2^k - 1 (mod w) of one plane. Every run of consecutive
    displacements of one column and plane (the entries of `min_template` come in such runs, 11 long on
    average at 360 columns) is covered by windows of 2^k, k = min(floor(log2 run), levels), the last one
    overlapping; so each column's minimum over its reads is the minimum over its entries, exactly."""
    rows = []
    for ix in np.unique(entries[:, 0]):
        group = entries[entries[:, 0] == ix]
        start = 0
        for i in range(1, len(group) + 1):
            ends = i == len(group) or group[i, 2] != group[i - 1, 2]
            ends = ends or (group[i, 1] - group[i - 1, 1]) % w not in (1, w - 1)
            if not ends:
                continue
            run = group[start:i]
            n, plane = len(run), int(run[0, 2])
            low = int(run[0, 1]) if n == 1 or (run[1, 1] - run[0, 1]) % w == 1 else int(run[-1, 1])
            k = min(n.bit_length() - 1, levels)
            starts = sorted({*range(0, n - (1 << k) + 1, 1 << k), n - (1 << k)})
            rows += [(int(ix), (low + o) % w, k * n_planes + plane) for o in starts]
            start = i
    return np.asarray(rows, np.int32).reshape(-1, 3)


def run_windows(arr: Arrays, levels: int = RUN_LEVELS) -> Array:
    """The arranged stack (`scale_planes.arranged`, [s, ry, t, rx, q]) with its window minima stacked
    on the plane axis: level k, plane s holds at the block of displacement y the minimum over y .. y +
    2^k - 1 (`run_template`). Displacement y + c is (ry + c) mod step_psi, t - (ry + c) // step_psi (t
    of period n_psi, the doubled axis rolled whole), so each level is the last and its shift by 2^k."""
    step_psi = arr.shape[1]
    out = [arr]
    for k in range(levels):
        c = 1 << k
        prev = out[-1]
        shifted = jnp.stack(
            [jnp.roll(prev[:, (ry + c) % step_psi], (ry + c) // step_psi, axis=1) for ry in range(step_psi)], 1
        )
        out.append(jnp.minimum(prev, shifted))
    return jnp.concatenate(out, 0)


def _block(arr: Arrays, s: dict, u: int, n_alpha: int, n_psi: int, q0: Array | int = 0) -> Array:
    """Entry u of scan step s: its (n_psi, n_alpha) block of the arranged stack from column q0 of
    the q axis (0: the q frame; qx on an alpha-doubled stack: the alpha frame)."""
    start = (s["plane"][u], s["ry"][u], s["t0"][u], s["rx"][u], q0)
    return lax.dynamic_slice(arr, start, (1, 1, n_psi, 1, n_alpha)).reshape(n_psi, n_alpha)


def _to_alpha(block: Array, qx: Array) -> Array:
    """A block in the q frame (q = qx + a) -> the alpha frame: column a is q = (qx + a) mod n_alpha."""
    n_psi, n_alpha = block.shape
    return lax.dynamic_slice(jnp.concatenate([block, block], 1), (0, qx), (n_psi, n_alpha))


def min_match(arr: Arrays, steps: dict, n_alpha: int, n_psi: int) -> Array:
    """(n_psi, n_alpha) MinWarping match: sum over snapshot columns of the minimum over the column's
    template entries; `arr` the arranged stack."""

    def step(carry, s):
        run, acc = carry
        m = functools.reduce(jnp.minimum, [_block(arr, s, u, n_alpha, n_psi) for u in range(UNROLL)])
        run = jnp.where(s["first"], m, jnp.minimum(run, m))
        add = _to_alpha(run, s["qx"][0]).astype(acc.dtype)
        return (run, acc + jnp.where(s["last"], add, jnp.zeros_like(add))), None

    acc_type = jnp.float32 if jnp.issubdtype(arr.dtype, jnp.floating) else jnp.int32
    init = (jnp.zeros((n_psi, n_alpha), arr.dtype), jnp.zeros((n_psi, n_alpha), acc_type))
    xs = {k: jnp.asarray(v) for k, v in steps.items()}
    (_, acc), _ = lax.scan(step, init, xs)
    return acc


def sum_match(arr2: Arrays, steps: dict, n_alpha: int, n_psi: int) -> Array:
    """(n_psi, n_alpha) match of a one-entry-per-column template (2D-Warping at one rho): the sum
    of the blocks of all entries (padding entries weigh 0); `arr2` the arranged stack with its q
    axis doubled (`scale_planes.arranged(..., doubled=True)`), so every block is read in the alpha
    frame directly."""
    acc_type = jnp.float32 if jnp.issubdtype(arr2.dtype, jnp.floating) else jnp.int32

    def step(acc, s):
        for u in range(UNROLL):
            acc = acc + _block(arr2, s, u, n_alpha, n_psi, s["qx"][u]).astype(acc_type) * s["weight"][u]
        return acc, None

    xs = {k: jnp.asarray(v) for k, v in steps.items()}
    acc, _ = lax.scan(step, jnp.zeros((n_psi, n_alpha), acc_type), xs)
    return acc


def rho_steps(rows: np.ndarray, w: int, n_alpha: int, n_psi: int) -> dict[str, np.ndarray]:
    """One rho's template rows (x, y, plane) as scan steps of UNROLL entries, padding weighted 0."""
    pad = (-len(rows)) % UNROLL
    rows = np.concatenate([rows, np.repeat(rows[:1], pad, 0)]).reshape(-1, UNROLL, 3)
    weight = np.ones(rows.shape[:2], np.int32)
    weight.reshape(-1)[len(weight.reshape(-1)) - pad :] = 0
    sa, sp = w // n_alpha, w // n_psi
    x, y, plane = rows[..., 0], rows[..., 1], rows[..., 2]
    return {"plane": plane, "ry": y % sp, "t0": (-(y // sp)) % n_psi, "rx": x % sa, "qx": x // sa, "weight": weight}


def inverse_index(n_alpha: int, n_psi: int) -> tuple[np.ndarray, np.ndarray]:
    """Where hypothesis (psi_m, alpha_a) of the swapped search lies: psi' = -psi, alpha' = alpha + pi
    - psi (the way back, in the current frame); (n_psi, n_alpha) index arrays (m', a')."""
    m = np.arange(n_psi)[:, None]
    a = np.arange(n_alpha)[None, :]
    return np.broadcast_to((-m) % n_psi, (n_psi, n_alpha)), (a + n_alpha // 2 - m * n_alpha // n_psi) % n_alpha


def column_groups(entries: np.ndarray) -> dict[str, np.ndarray]:
    """The template's entries grouped by column x for the fine search (`window_match`, `_padded_groups`):
    x, y, plane (G, UNROLL) and `column` (G,), the index of the group's column among the template's
    columns."""
    part, first, _ = _padded_groups(entries)
    return {"x": part[..., 0], "y": part[..., 1], "plane": part[..., 2], "column": np.cumsum(first, dtype=np.int32) - 1}


def window_stack(stk: Arrays, rows: int, cols: int) -> Array:
    """(planes, w + rows - 1, w + cols - 1): out[s, t, u] = stk[s, t mod w, (t - u) mod w], wrapped
    around so that every (rows, cols) window starting in [0, w)^2 lies inside (`window_match`)."""
    w = stk.shape[-1]
    g = jnp.roll(jax.vmap(skewed)(stk)[:, :, ::-1], 1, axis=2)  # [s, t, u] = skewed[s, t, -u] = stk[s, t, t - u]
    return g[:, np.arange(w + rows - 1) % w][:, :, np.arange(w + cols - 1) % w]


def window_match(g: Arrays, groups: dict, plane: Array, row: Array, col: Array, rows: int, cols: int) -> Array:
    """(rows, cols) int32: for every offset (i, j) of a window, the sum over template columns of the
    minimum over the column's entries of g[plane, row + i, col + j] (`window_stack`; plane, row, col
    per entry, (G, UNROLL)). The fine search of all its hypotheses at once: each entry reads one
    contiguous window (one gather of windows, not one gather per hypothesis), and sums of integers are
    exact whatever their order."""
    w = g.shape[1] - rows + 1
    read = jax.vmap(lambda s, r, c: lax.dynamic_slice(g, (s, r % w, c % w), (1, rows, cols)).reshape(rows, cols))
    n_groups = plane.shape[0]
    least = read(plane.reshape(-1), row.reshape(-1), col.reshape(-1)).reshape(n_groups, UNROLL, rows, cols).min(1)
    per_column = jax.ops.segment_min(
        least.astype(jnp.int32),
        jnp.asarray(groups["column"]),
        num_segments=int(groups["column"][-1]) + 1,
        indices_are_sorted=True,
    )
    return jnp.sum(per_column, axis=0)


def entry_values(stk: Arrays, entries: np.ndarray, alpha: Arrays | int, psi: Arrays | int) -> Array:
    """(T,) stack values of every template entry at one off-grid hypothesis (alpha, psi in pixels)."""
    w = stk.shape[-1]
    x, y, plane = (jnp.asarray(entries[:, k]) for k in range(3))
    theta = (x + alpha) % w
    return stk[plane, theta, (theta + y - psi) % w]


def min_match_at(stk: Arrays, entries: np.ndarray, alpha: Arrays | int, psi: Arrays | int) -> Array:
    """MinWarping match of one hypothesis in whole pixels (the fine search), by per-column minima."""
    w = stk.shape[-1]
    acc_type = jnp.float32 if jnp.issubdtype(stk.dtype, jnp.floating) else jnp.int32
    # the minimum per column in 32 bits: a scatter-min on bytes is a rare path of XLA's CPU backend,
    # suspected (not proven) behind two CI aborts in unrelated compiles later; 32 bits cost nothing here
    values = entry_values(stk, entries, alpha, psi).astype(acc_type)
    col = jax.ops.segment_min(values, jnp.asarray(entries[:, 0]), num_segments=w)
    present = np.zeros(w, bool)
    present[entries[:, 0]] = True  # columns without entries (x = 0, pi) add nothing
    return jnp.sum(jnp.where(jnp.asarray(present), col, 0))
