"""Plain, per-point NumPy reference ("twin") of the delvjax methods (docs/model.md).

Follows docs/model.md (sections 1, 2, 3, 4.1, 4.2, 4.4, 5) literally,
with explicit Python loops over pixels, blobs, shifts and headings.  It is slow on
purpose: it is meant to be read and to check the vectorised JAX library against.

Conventions (docs/model.md §1): angles in radians, counter-clockwise, world angle 0 = +x;
wrap() maps to (-pi, pi]; a bearing is relative to the agent's heading; pixel j of
an n_pix ring image looks along bearing 2*pi*j/n_pix.  Landmarks: (L, 3) array of
[x, y, r].  Arena: [xmin, ymin, xmax, ymax].
"""

import math

import numpy as np

from tests.twins.sensing import (
    TWO_PI,
    _angle,
    _unit,
    estimate_distances_end,
    estimate_distances_start,
    extract_blobs,
    quantize,
    render,
    wrap,
)


# ----------------------------------------------------------------------------- docs/model.md §3.4
def _pairs(N, M, k):
    """Cyclic pairing for shift k: list of (reference index, current index)."""
    if M <= N:
        return [((j + k) % N, j) for j in range(M)]
    return [(i, (i + k) % M) for i in range(N)]


def home_frame_order(cur_bearings, alpha):
    """docs/model.md §3.3: the current blobs' indices sorted by home-frame bearing (b + alpha) mod 2 pi."""
    return sorted(range(len(cur_bearings)), key=lambda j: (float(cur_bearings[j]) + alpha + 1e-5) % TWO_PI)


def match_arrangement(ref_vecs, cur_vecs, alphas, min_pairs=2, cur_bearings=None):
    """Search shift k (outer) and heading alpha (inner) minimising var; returns
    (k, alpha, p, var) of the first strict minimum, or None when n < min_pairs or n = 0.
    min_pairs: 2 without a compass (one pair fits every heading), 1 with a fixed heading
    (one pair fixes p; with n = 1 every shift has var = 0 and k = 0 wins), docs/model.md §3.4.
    cur_bearings: the current vectors' bearings (agent frame); given, the current list is paired in
    its home-frame order under each alpha (docs/model.md §3.3), else in the order given."""
    ref = np.asarray(ref_vecs, dtype=float).reshape(-1, 2).tolist()  # plain floats: the loops below are hot
    cur = np.asarray(cur_vecs, dtype=float).reshape(-1, 2).tolist()
    N, M = len(ref), len(cur)
    if min(N, M) < max(min_pairs, 1):
        return None
    best = None
    for k in range(max(N, M)):
        pairs = _pairs(N, M, k)
        for alpha in alphas:
            order = list(range(M)) if cur_bearings is None else home_frame_order(cur_bearings, alpha)
            ca, sa = math.cos(alpha), math.sin(alpha)
            e = [
                (
                    ref[i][0] - (ca * cur[order[j]][0] - sa * cur[order[j]][1]),  # Eq 3.4: V^R_i - Rot(alpha) V_j
                    ref[i][1] - (sa * cur[order[j]][0] + ca * cur[order[j]][1]),
                )
                for (i, j) in pairs
            ]
            px, py = sum(x for x, _ in e) / len(e), sum(y for _, y in e) / len(e)  # Eq 3.5
            var = sum((x - px) ** 2 + (y - py) ** 2 for x, y in e)  # Eq 3.6
            if best is None or var < best[3]:
                best = (k, float(alpha), np.array([px, py]), var)
    return best


def delv_direction(
    home_start_b,
    home_end_b,
    here_start_b,
    here_end_b,
    d_hat_home,
    psi_hat_home,
    d_hat_here,
    psi_hat_here,
    levels=None,
    scale=1000.0,
    r_max=2000.0,
    n_heading=360,
    alpha_fixed=None,
    order="home",
):
    """docs/model.md §3.3-3.4: DELV homing direction in the agent frame (nan if undefined); `order`
    "home" pairs the current list in the home frame of each hypothesis, "agent" as sensed."""
    home_start_b, here_end_b = np.asarray(home_start_b), np.asarray(here_end_b)
    # Reference map: anchored at home (the START of the home unit move), R_P.
    R_P = estimate_distances_start(home_start_b, home_end_b, d_hat_home, psi_hat_home, r_max)
    R_P = quantize(R_P, levels, scale)
    ref = np.array([[R * math.cos(t), R * math.sin(t)] for R, t in zip(R_P, home_start_b)])
    # Current vectors: anchored at x (the END of the current unit move), R_C.
    R_C = estimate_distances_end(here_start_b, here_end_b, d_hat_here, psi_hat_here, r_max)
    R_C = quantize(R_C, levels, scale)
    cur = np.array([[R * math.cos(b), R * math.sin(b)] for R, b in zip(R_C, here_end_b)])
    if alpha_fixed is None:
        alphas = [TWO_PI * a / n_heading for a in range(n_heading)]
    else:
        alphas = [alpha_fixed]  # compass / visual compass: only k
    res = match_arrangement(
        ref,
        cur,
        alphas,
        min_pairs=2 if alpha_fixed is None else 1,
        cur_bearings=here_end_b if order == "home" else None,
    )
    if res is None:
        return math.nan, {"k": None, "alpha": None, "p": None, "var": None}
    k, alpha, p, var = res
    info = {"k": k, "alpha": alpha, "p": p, "var": var}
    if math.hypot(p[0], p[1]) == 0.0:
        return math.nan, info
    return wrap(_angle(-p) - alpha), info


# ----------------------------------------------------------------------------- docs/model.md §4.1
def alv_direction(home_b, here_b, compass):
    """ALV: H = sum u(here, home frame) - sum u(home); agent-frame direction."""
    if len(home_b) == 0 or len(here_b) == 0:
        return math.nan
    H = np.zeros(2)
    for b in here_b:
        H += _unit(b + compass)
    for b in home_b:
        H -= _unit(b)
    if math.hypot(H[0], H[1]) == 0.0:
        return math.nan
    return wrap(_angle(H) - compass)


# ----------------------------------------------------------------------------- docs/model.md §4.2
def acv_direction(home_b, here_b, compass):
    """ACV: pair sorted bearings by the best cyclic shift, sum correction vectors."""
    theta = sorted(float(b) % TWO_PI for b in home_b)  # reference (N)
    a = sorted(float(b + compass) % TWO_PI for b in here_b)  # current (M)
    N, M = len(theta), len(a)
    if N == 0 or M == 0:
        return math.nan
    best_pairs, best_cost = None, math.inf
    for k in range(max(N, M)):
        pairs = _pairs(N, M, k)
        cost = sum(wrap(theta[i] - a[j]) ** 2 for (i, j) in pairs)
        if cost < best_cost:
            best_pairs, best_cost = pairs, cost
    HV = np.zeros(2)
    for i, j in best_pairs:
        w = wrap(theta[i] - a[j])
        ang = a[j] + math.pi / 2 if w < 0 else a[j] - math.pi / 2
        HV += abs(w) * _unit(ang)
    if math.hypot(HV[0], HV[1]) == 0.0:
        return math.nan
    return wrap(_angle(HV) - compass)


# ----------------------------------------------------------------------------- docs/model.md §4.4
def visual_compass(home_gray, here_gray):
    """Estimate of h - alpha_r from the gray channels (first minimum shift)."""
    S, C = np.asarray(home_gray, float), np.asarray(here_gray, float)
    n = len(S)
    best_k, best_cost = 0, math.inf
    for k in range(n):
        cost = float(np.sum(np.abs(np.roll(C, -k) - S)))  # sum over j of |C[(j + k) % n] - S[j]|
        if cost < best_cost:
            best_k, best_cost = k, cost
    return wrap(-TWO_PI * best_k / n)


# ----------------------------------------------------------------------------- docs/model.md §5
def reference_direction(
    landmarks,
    arena,
    home,
    point,
    heading,
    method,
    d=50.0,
    levels=None,
    background="distant",
    alpha_r=0.0,
    scale=1000.0,
    r_max=2000.0,
    n_heading=360,
    n_pix=360,
    visible=None,
):
    """Noise-free world-frame homing direction at `point` with heading `heading`.
    `visible` (bool per landmark, default all): the landmarks seen in the current views
    (occlusion, docs/model.md §5); the home snapshots always see every landmark."""
    home, point, h = np.asarray(home, float), np.asarray(point, float), float(heading)
    seen = np.asarray(landmarks, float).reshape(-1, 3)
    if visible is not None:
        seen = seen[np.asarray(visible, bool)]
    # Home unit move: from home along alpha_r, heading unchanged (psi = 0, d_hat = d).
    hs_mask, hs_gray = render(landmarks, home, alpha_r, arena, background, n_pix)
    he_mask, _ = render(landmarks, home + d * _unit(alpha_r), alpha_r, arena, background, n_pix)
    # Current unit move ending at point with heading h throughout.
    xs_mask, _ = render(seen, point - d * _unit(h), h, arena, background, n_pix)
    xe_mask, xe_gray = render(seen, point, h, arena, background, n_pix)
    home_start_b, home_end_b = extract_blobs(hs_mask), extract_blobs(he_mask)
    here_start_b, here_end_b = extract_blobs(xs_mask), extract_blobs(xe_mask)
    compass = wrap(h - alpha_r)
    if method in ("delv", "delv-compass", "delv-visual"):
        alpha_fixed = None  # full heading search
        if method == "delv-compass":
            alpha_fixed = compass
        elif method == "delv-visual":
            alpha_fixed = visual_compass(hs_gray, xe_gray)
        agent, _ = delv_direction(
            home_start_b,
            home_end_b,
            here_start_b,
            here_end_b,
            d,
            0.0,
            d,
            0.0,
            levels=levels,
            scale=scale,
            r_max=r_max,
            n_heading=n_heading,
            alpha_fixed=alpha_fixed,
        )
    elif method in ("alv", "acv", "alv-visual", "acv-visual"):
        if method.endswith("-visual"):
            compass = visual_compass(hs_gray, xe_gray)
        fn = alv_direction if method.startswith("alv") else acv_direction
        agent = fn(home_start_b, here_end_b, compass)
    else:
        raise ValueError(f"unknown method {method!r}")
    if math.isnan(agent):
        return math.nan
    return wrap(h + agent)


def angular_error_deg(direction_world, point, home):
    """|wrap(direction - angle(home - point))| in degrees; nan counts as 180."""
    if direction_world is None or math.isnan(direction_world):
        return 180.0
    to_home = math.atan2(home[1] - point[1], home[0] - point[0])
    return math.degrees(abs(wrap(direction_world - to_home)))
