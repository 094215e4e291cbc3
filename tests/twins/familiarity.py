"""Plain NumPy twins of the familiarity models (docs/familiarity.md), written from bob_robotics'
definitions and Ardin et al. (2016), float64, explicit loops over snapshots, rotations and images;
plus a NumPy regeneration of BoB's random test images and of its libstdc++ initial InfoMax weights
(docs/familiarity.md §4), so that BoB's stored tables can be matched without shipping them."""

from __future__ import annotations

import math

import numpy as np


def roll_right(image, k):
    """out[:, x] = in[:, x - k]."""
    w = image.shape[1]
    return image[:, [(x - k) % w for x in range(w)]]


def diff(a, b, keep, kind):
    a, b = a[keep].astype(np.float64), b[keep].astype(np.float64)
    if a.size == 0:
        return math.nan
    if kind == "abs":
        return float(np.mean(np.abs(a - b)))
    if kind == "rms":
        return math.sqrt(float(np.sum((a - b) ** 2)) / a.size)
    sa, sb = a.std(), b.std()
    if sa == 0 or sb == 0:
        return math.nan
    return 1.0 - abs(float(np.mean((a - a.mean()) * (b - b.mean()))) / (sa * sb))


def ridf_table(view, snapshots, kind="abs", view_mask=None, snapshot_masks=None):
    h, w = view.shape
    vm = np.ones((h, w), bool) if view_mask is None else view_mask
    out = np.empty((len(snapshots), w))
    for s, snap in enumerate(snapshots):
        sm = np.ones((h, w), bool) if snapshot_masks is None else snapshot_masks[s]
        for i in range(w):
            out[s, i] = diff(roll_right(view, i), snap, roll_right(vm, i) & sm, kind)
    return out


def perfect_memory_choice(table, turns, select="best", n_best=3):
    """(turn, value / 255, best image) from a (S, R) table (BoB's RIDF processors)."""
    t = np.where(np.isnan(table), np.inf, table)
    best_col = [int(np.argmin(row)) for row in t]
    lowest = [float(row.min()) for row in t]
    s = int(np.argmin(lowest))
    if select == "best":
        return turns[best_col[s]], lowest[s] / 255.0, s
    order = sorted(range(len(lowest)), key=lambda k: (lowest[k], k))[:n_best]
    sx = sum((1 - lowest[k] / 255.0) * math.sin(turns[best_col[k]]) for k in order)
    cx = sum((1 - lowest[k] / 255.0) * math.cos(turns[best_col[k]]) for k in order)
    return math.atan2(sx, cx), lowest[s] / 255.0, s


def infomax_train(weights, images, rate):
    """One natural-gradient infomax step per image: W <- W + rate (I - (y + u) u^T) W."""
    w = np.array(weights, np.float64)
    eye = np.eye(w.shape[0])
    for img in images:
        x = img.reshape(-1) / 255.0
        u = w @ x
        y = np.tanh(u)
        w = w + rate * (eye - np.outer(y + u, u)) @ w
    return w


def infomax_unfamiliarity(weights, view):
    return float(np.sum(np.abs(weights @ (view.reshape(-1) / 255.0))))


def mushroom_code(wiring, view, n_active):
    x = view.reshape(-1).astype(np.float64)
    pn = (x - x.min()) / (x.max() - x.min()) if x.max() > x.min() else np.zeros_like(x)
    drive = np.array([pn[idx].mean() for idx in wiring])
    order = sorted(range(len(drive)), key=lambda k: (-drive[k], k))[:n_active]
    code = np.zeros(len(drive))
    code[order] = 1.0
    return code


def mushroom_train(wiring, weights, images, n_active):
    w = np.array(weights, np.float64)
    for img in images:
        w = w * (1.0 - mushroom_code(wiring, img, n_active))
    return w


def mushroom_unfamiliarity(wiring, weights, view, n_active):
    return float(mushroom_code(wiring, view, n_active) @ weights / n_active)


def ca_bounds(vals, goal):
    """BoB's calculate_ca (medfilt size 1), from its description: process np.diff, stop at a decrease."""

    def first(side):
        vec = np.diff(side)  # BoB's process_fun; an empty vector is a bound of 0
        if len(vec) == 0:
            return 0
        hits = [i for i, d in enumerate(vec) if d < 0]
        return hits[0] if hits else math.inf

    return goal - first(vals[goal::-1]), goal + first(vals[goal:])


def rca_bounds(errs, goal, thresh=45.0):
    """BoB's calculate_rca (medfilt size 1): drop the goal, stop at an error >= thresh."""

    def first(vec):
        if len(vec) == 0:
            return 0
        hits = [i for i, e in enumerate(vec) if e >= thresh]
        return hits[0] if hits else math.inf

    return goal - first(errs[goal::-1][1:]), goal + first(errs[goal:][1:])


def bob_images(n=100, rows=10, cols=90, seed=42):
    """BoB's random test images (tests/navigation/generate_images.h): std::mt19937(42) and
    uniform_int_distribution(0, 255), one draw per pixel, image by image, row-major. numpy's legacy
    generator is the same Mersenne twister; libstdc++ takes the top 8 bits of each 32-bit draw."""
    raw = np.random.RandomState(seed)._bit_generator.random_raw(n * rows * cols)
    return (raw >> 24).astype(np.uint8).reshape(n, rows, cols)


def bob_test_mask(rows=10, cols=90):
    m = np.ones((rows, cols), bool)
    m[:5, :10] = False
    return m


def _minstd(seed, n):
    """n outputs of libstdc++'s minstd_rand0 (x <- 16807 x mod 2^31 - 1), vectorised by blocks."""
    m, a = 2147483647, 16807
    block = 4096
    powers = np.empty(block, np.int64)
    p = 1
    for k in range(block):
        p = p * a % m
        powers[k] = p
    step = int(powers[-1])
    out = np.empty(n, np.int64)
    s = seed % m or 1
    for start in range(0, n, block):
        chunk = (s * powers) % m  # s * a^(k+1)
        take = min(block, n - start)
        out[start : start + take] = chunk[:take]
        s = s * step % m
    return out


def bob_initial_weights(n_inputs, n_hidden, seed=42):
    """BoB's `generateInitialWeights` as libstdc++ computes it: minstd_rand0, float uniforms, the
    Marsaglia polar method (y m first, then x m), an (N x M) column-major fill, every input's row
    centred and scaled to population SD 1 over the hidden units; returned as (M, N)."""
    need = n_inputs * n_hidden
    f32 = np.float32
    n_raw = 2 * need + 4096
    while True:
        raw = _minstd(seed, n_raw)
        u = (raw - 1).astype(f32) / f32(2147483646.0)
        u = np.where(u >= 1, np.nextafter(f32(1), f32(0)), u).astype(f32)
        x = (f32(2) * u[0::2] - f32(1)).astype(f32)
        y = (f32(2) * u[1::2] - f32(1)).astype(f32)
        r2 = (x * x + y * y).astype(f32)
        ok = (r2 <= 1) & (r2 != 0)
        mult = np.sqrt((f32(-2) * np.log(r2[ok])) / r2[ok]).astype(f32)
        z = np.stack([(y[ok] * mult).astype(f32), (x[ok] * mult).astype(f32)], -1).reshape(-1)
        if z.size >= need:
            break
        n_raw *= 2
    a = z[:need].astype(np.float64).reshape(n_hidden, n_inputs).T  # (N, M), column-major fill
    a = a - a.mean(1, keepdims=True)
    a = a / np.sqrt((a * a).mean(1, keepdims=True))
    return a.T
