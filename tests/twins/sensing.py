"""Plain, per-point NumPy reference ("twin") of delvjax's sensing and distance estimation
(docs/model.md §1-§3.2): angles, ring images, blobs, sine-law distances, quantization.

Explicit Python loops over pixels and blobs; slow on purpose, meant to be read. The methods
built on it are in `methods.py`.
"""

import math

import numpy as np

TWO_PI = 2.0 * math.pi


# ----------------------------------------------------------------------------- docs/model.md §1
def wrap(a):
    """Map angle(s) to (-pi, pi]."""
    a = np.asarray(a, dtype=float)
    r = math.pi - np.mod(math.pi - a, TWO_PI)  # np.mod in [0, 2pi) -> r in (-pi, pi]
    r = np.where(r <= -math.pi, r + TWO_PI, r)  # guard against rounding to exactly -pi
    return float(r) if r.ndim == 0 else r


def _angle(v):
    return math.atan2(v[1], v[0])


def _unit(a):
    return np.array([math.cos(a), math.sin(a)])


# ----------------------------------------------------------------------------- docs/model.md §2
def background_value(phi):
    """docs/model.md §2.3 background as a function of an angle phi."""
    return 0.45 + 0.25 * np.sin(3 * phi) + 0.15 * np.sin(7 * phi + 1)


def _ray_cylinder(o, u, c, r):
    """Distance along the unit ray o + t*u to the cylinder (c, r), or None if missed.
    A ray starting inside the cylinder hits it at distance 0 (docs/model.md §2.2).
    Plain float arithmetic on the 2-vectors (a tiny NumPy array per call costs more than the sum)."""
    vx, vy = float(c[0]) - float(o[0]), float(c[1]) - float(o[1])
    dist2 = vx * vx + vy * vy
    if dist2 < r * r:
        return 0.0
    t_ca = vx * float(u[0]) + vy * float(u[1])  # distance along the ray to the closest approach
    perp2 = dist2 - t_ca * t_ca  # squared distance of the centre from the ray
    if t_ca <= 0.0 or perp2 > r * r:
        return None
    return t_ca - math.sqrt(max(r * r - perp2, 0.0))


def _wall_fraction(o, u, arena):
    """f = s / perimeter of the point where the ray from o (inside the arena) leaves it."""
    xmin, ymin, xmax, ymax = [float(v) for v in arena]
    W, H = xmax - xmin, ymax - ymin
    tx = (xmax - o[0]) / u[0] if u[0] > 0 else ((xmin - o[0]) / u[0] if u[0] < 0 else math.inf)
    ty = (ymax - o[1]) / u[1] if u[1] > 0 else ((ymin - o[1]) / u[1] if u[1] < 0 else math.inf)
    t = min(tx, ty)
    x = min(max(o[0] + t * u[0], xmin), xmax)
    y = min(max(o[1] + t * u[1], ymin), ymax)
    if tx < ty:  # leaves through a vertical wall
        s = W + (y - ymin) if u[0] > 0 else 2 * W + H + (ymax - y)  # right / left
    else:  # leaves through a horizontal wall (corners agree)
        s = W + H + (xmax - x) if u[1] > 0 else x - xmin  # top / bottom
    return s / (2 * W + 2 * H)


def render(landmarks, pos, heading, arena, background="distant", n_pix=360):
    """docs/model.md §2.2 ring image at pos with the given heading -> (mask bool, gray float)."""
    landmarks = [tuple(float(v) for v in lm) for lm in np.asarray(landmarks, dtype=float).reshape(-1, 3)]
    o = (float(pos[0]), float(pos[1]))
    mask = np.zeros(n_pix, dtype=bool)
    gray = np.zeros(n_pix, dtype=float)
    for j in range(n_pix):
        phi = heading + TWO_PI * j / n_pix  # world angle of pixel j's ray
        u = (math.cos(phi), math.sin(phi))
        best = math.inf  # nearest cylinder hit
        for cx, cy, r in landmarks:
            t = _ray_cylinder(o, u, (cx, cy), r)
            if t is not None and t < best:
                best = t
        if best < math.inf:
            mask[j], gray[j] = True, 1.0
        elif background == "distant":
            gray[j] = background_value(phi)
        elif background == "walls":
            gray[j] = background_value(TWO_PI * _wall_fraction(o, u, arena))
        elif background == "none":
            gray[j] = 0.0
        else:
            raise ValueError(f"unknown background {background!r}")
    return mask, gray


def extract_blobs(mask):
    """docs/model.md §2.4: bearings (sorted, in [0, 2pi)) of maximal circular runs of mask pixels."""
    mask = np.asarray(mask, dtype=bool)
    n = len(mask)
    if mask.all():
        return np.array([0.0])
    if not mask.any():
        return np.zeros(0)
    bearings = []
    for j in range(n):
        if mask[j] and not mask[j - 1]:  # run starts at j (j-1 wraps for j=0)
            length = 0
            while mask[(j + length) % n]:
                length += 1
            mid = j + (length - 1) / 2.0  # midpoint of first and last pixel
            bearings.append((mid * TWO_PI / n) % TWO_PI)
    return np.array(sorted(bearings))


# ----------------------------------------------------------------------------- docs/model.md §3.1
TIE_RAD = 1e-5  # bearings sit on a half-pixel lattice: exact ties must not be decided by rounding


def _nearest(target, candidates):
    """Index of the candidate angle circularly nearest to target (first on ties within TIE_RAD)."""
    best_i, best_d = 0, math.inf
    for i, c in enumerate(candidates):
        dd = abs(wrap(target - c))
        if dd < best_d - TIE_RAD:
            best_i, best_d = i, dd
    return best_i


def _sin_on_lattice(a):
    """sin(a), exactly 0 for a landmark on the line of the move (a = 0 or pi up to rounding)."""
    s = math.sin(a)
    return 0.0 if abs(s) < 1e-6 else s


def _valid_or_rmax(R, sin_delta, r_max):
    # "negative" read as "not positive": a landmark on the line of the unit move gives
    # R = 0 by the sine law (no triangle), as undefined as sin(delta) = 0.
    if abs(sin_delta) < 1e-9 or not math.isfinite(R) or R <= 0 or R > r_max:
        return r_max
    return R


def estimate_distances_end(start_b, end_b, d_hat, psi_hat, r_max=2000.0):
    """R_C (distance from the END point C) for each end blob (Eq 3.2)."""
    out = np.full(len(end_b), float(r_max))
    if len(start_b) == 0:
        return out
    for j, beta in enumerate(end_b):
        beta_p = beta + psi_hat  # end bearing in the start frame
        theta = start_b[_nearest(beta_p, start_b)]  # partner: nearest start blob
        delta = wrap(beta_p - theta)  # parallax
        sd = math.sin(delta)
        R = d_hat * _sin_on_lattice(theta) / sd if abs(sd) >= 1e-9 else math.inf
        out[j] = _valid_or_rmax(R, sd, r_max)
    return out


def estimate_distances_start(start_b, end_b, d_hat, psi_hat, r_max=2000.0):
    """R_P (distance from the START point P) for each start blob (Eq 3.3, corrected:
    R_P = d*sin(theta + delta)/sin(delta))."""
    out = np.full(len(start_b), float(r_max))
    if len(end_b) == 0:
        return out
    end_p = [b + psi_hat for b in end_b]  # end bearings in the start frame
    for i, theta in enumerate(start_b):
        beta_p = end_p[_nearest(theta, end_p)]  # partner: nearest end blob
        delta = wrap(beta_p - theta)
        sd = math.sin(delta)
        R = d_hat * _sin_on_lattice(theta + delta) / sd if abs(sd) >= 1e-9 else math.inf
        out[i] = _valid_or_rmax(R, sd, r_max)
    return out


# ----------------------------------------------------------------------------- docs/model.md §3.2
def quantize(R, levels, scale=1000.0):
    """Eq 3.17: R -> a * clip(ceil(R*Q/a), 1, Q) / Q; levels None keeps R."""
    R = np.asarray(R, dtype=float)
    if levels is None:
        return R.copy()
    return scale * np.clip(np.ceil(R * levels / scale), 1, levels) / levels
