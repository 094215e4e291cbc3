"""Plain NumPy twin of MinWarping and 2D-Warping (docs/model.md §4.7), written from the papers'
equations (Möller 2009; Möller, Krzykawski & Gerstmayr 2010), one image pair at a time, float64,
explicit loops over template entries and hypotheses; no layout tricks.

The one thing it shares with the JAX code is the quantisation rule of the byte stack (so the two
can be compared on one stack exactly): round(200 d / d_max).
"""

from __future__ import annotations

import math

import numpy as np

LEVELS = 200


def scale_factors(n_planes, max_scale):
    c = (n_planes - 1) // 2
    return np.array([max_scale ** ((k - c) / c) for k in range(n_planes)])


def nearest_plane(sigma, scales, threshold):
    """The scale plane of sigma: the nearest factor (ties to the smaller), None above threshold."""
    if sigma > threshold:
        return None
    for k in range(len(scales) - 1):
        if sigma <= 0.5 * (scales[k] + scales[k + 1]):
            return k
    return len(scales) - 1


def magnify(image, elevations, m):
    """out(e) = image(atan(tan(e) / m)), nearest row."""
    out = np.empty_like(image)
    step = elevations[0] - elevations[1]
    for r, e in enumerate(elevations):
        src = (elevations[0] - math.atan(math.tan(e) / m)) / step
        out[r] = image[min(max(int(math.floor(src + 0.5)), 0), image.shape[0] - 1)]
    return out


def edges(image):
    return image[1:] - image[:-1]


def distance(a, b, measure):
    """Column distance of two columns (1-D arrays)."""
    if measure == "nsad":
        return np.abs(a - b).sum() / (np.abs(a).sum() + np.abs(b).sum() + 1e-6)
    if measure == "nssd":
        return ((a - b) ** 2).sum() / ((a * a).sum() + (b * b).sum() + 1e-6)
    if measure == "sad":
        return np.abs(a - b).mean()
    return ((a - b) ** 2).mean()


def stack(ss, cv, elevations, scales, measure="nsad", use_edges=True):
    """(planes, w, w): snapshot column i against current column j, current distance = sigma x home."""
    ss, cv, elevations = np.asarray(ss, float), np.asarray(cv, float), np.asarray(elevations, float)
    if use_edges:
        ss, cv = edges(ss), edges(cv)
        elevations = 0.5 * (elevations[1:] + elevations[:-1])
    w = ss.shape[1]
    out = np.zeros((len(scales), w, w))
    for s, sigma in enumerate(scales):
        a = magnify(ss, elevations, 1.0 / sigma) if sigma < 1 else ss
        b = magnify(cv, elevations, sigma) if sigma > 1 else cv
        for i in range(w):
            for j in range(w):
                out[s, i, j] = distance(a[:, i], b[:, j], measure)
    return out


def quantise(stk, measure):
    top = {"nsad": 1.0, "nssd": 2.0}.get(measure, max(stk.max(), 1e-30))
    return np.rint(np.clip(stk / top, 0, 1) * LEVELS).astype(np.int64)


def min_template(w, scales, threshold):
    """{x: [(y, plane), ...]}: every y of column x (pixels) with x + y strictly between the movement
    line's two ends, sigma = sin x / sin(x + y) <= threshold."""
    out = {}
    for ix in range(1, w):
        if 2 * ix == w:
            continue
        x = 2 * math.pi * ix / w
        side = 1 if 2 * ix < w else -1
        entries, iy = [], 0
        while (2 * (ix + iy) < w) if side > 0 else (2 * (ix + iy) > w):
            y = 2 * math.pi * iy / w
            sigma = math.sin(x) / math.sin(x + y)
            plane = nearest_plane(sigma, scales, threshold)
            if plane is not None:
                entries.append((iy % w, plane))
            iy += side
        out[ix] = entries
    return out


def min_match(stk, template, n_alpha, n_psi):
    """M[m, a] = sum over x of min over (y, s) of stk[s, theta, theta + y - psi], theta = x + alpha."""
    w = stk.shape[-1]
    M = np.zeros((n_psi, n_alpha), stk.dtype)
    for m in range(n_psi):
        psi = m * (w // n_psi)
        for a in range(n_alpha):
            alpha = a * (w // n_alpha)
            M[m, a] = match_at(stk, template, alpha, psi)
    return M


def match_at(stk, template, alpha, psi):
    w = stk.shape[-1]
    total = 0
    for ix, entries in template.items():
        if entries:
            theta = (ix + alpha) % w
            total += min(stk[s, theta, (theta + iy - psi) % w] for iy, s in entries)
    return total


def first_min(M):
    """(m, a) of the first minimum in psi-major, alpha-minor order."""
    k = int(np.argmin(M.reshape(-1)))
    return divmod(k, M.shape[1])


def search(
    ss,
    cv,
    elevations,
    n_alpha=96,
    n_psi=96,
    n_planes=9,
    max_scale=2.0,
    threshold=2.5,
    measure="nsad",
    use_edges=True,
    double=True,
    fine=True,
    stacks=None,
):
    """MinWarping: (alpha, psi) in pixels and the match. `stacks`: (stack, swapped stack) to search
    instead of the twin's own (quantised or not, as given)."""
    w = ss.shape[1]
    scales = scale_factors(n_planes, max_scale)
    if stacks is None:
        fwd = quantise(stack(ss, cv, elevations, scales, measure, use_edges), measure)
        back = quantise(stack(cv, ss, elevations, scales, measure, use_edges), measure)
    else:
        fwd, back = stacks
    template = min_template(w, scales, threshold)
    sa, sp = w // n_alpha, w // n_psi

    def score(alpha, psi):
        v = match_at(fwd, template, alpha, psi)
        if double:  # the way back: from the current place along alpha + pi - psi, turned by -psi
            v += match_at(back, template, (alpha + w // 2 - psi) % w, (-psi) % w)
        return v

    M = np.array([[score(a * sa, m * sp) for a in range(n_alpha)] for m in range(n_psi)])
    m, a = first_min(M)
    alpha, psi, value = a * sa, m * sp, M[m, a]
    if fine:
        best = (value, alpha, psi)
        for dp in range(-(sp - 1), sp):
            for da in range(-(sa - 1), sa):
                v = score((alpha + da) % w, (psi + dp) % w)
                if v < best[0]:
                    best = (v, (alpha + da) % w, (psi + dp) % w)
        value, alpha, psi = best
    return alpha, psi, value


def rho_search(
    ss,
    cv,
    elevations,
    n_alpha=96,
    n_psi=96,
    rhos=None,
    n_planes=9,
    max_scale=2.0,
    measure="nsad",
    use_edges=True,
    stk=None,
):
    """2D-Warping: every column at one distance from home, rho = d / r; (alpha, psi, rho index, match)
    of the first minimum in (rho, psi, alpha) order."""
    w = ss.shape[1]
    scales = scale_factors(n_planes, max_scale)
    rhos = np.linspace(0.0, 1.0, 20) if rhos is None else rhos
    if stk is None:
        stk = quantise(stack(ss, cv, elevations, scales, measure, use_edges), measure)
    sa, sp = w // n_alpha, w // n_psi
    best = None
    for r, rho in enumerate(rhos):
        cols = []
        for ix in range(w):
            x = 2 * math.pi * ix / w
            y = math.pi / 2 if (rho == 1.0 and ix == 0) else math.atan2(rho * math.sin(x), 1 - rho * math.cos(x))
            sigma = math.sqrt(1 + rho * rho - 2 * rho * math.cos(x))
            cols.append((ix, int(np.rint(y * w / (2 * math.pi))) % w, nearest_plane(sigma, scales, math.inf)))
        for m in range(n_psi):
            for a in range(n_alpha):
                alpha, psi = a * sa, m * sp
                v = sum(stk[s, (ix + alpha) % w, (ix + alpha + iy - psi) % w] for ix, iy, s in cols)
                if best is None or v < best[3]:
                    best = (alpha, psi, r, v)
    return best


def home_direction(alpha, psi, w):
    """The home direction in the current agent frame (rad, wrapped to [-pi, pi))."""
    ang = 2 * math.pi * alpha / w + math.pi - 2 * math.pi * psi / w
    return (ang + math.pi) % (2 * math.pi) - math.pi
