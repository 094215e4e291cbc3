"""Plain, per-point NumPy twins of the holistic comparators (docs/model.md §4.3, §4.5).

* `warping_search` / `warping_direction`: predictive image matching (Franz et al. 1998;
  thesis §4.2; docs/model.md §4.3), written literally: for every (alpha, rho, psi) hypothesis, in
  (alpha, rho, psi) order, the predicted image C_pred(phi) = S(g - asin(rho*sin(g - alpha))),
  g = phi + psi, is sampled at the nearest pixel, compared with C by the sum of absolute
  differences, and the first strict minimum wins.  Only the loop over phi is vectorised;
  nothing is precomputed across hypotheses (about 1-2 s per point).
* `mfdid_direction`: matched-filter descent in image distances (Möller & Vardy 2006) for
  1D images with a compass, with explicit loops over pixels.

Nearest pixel (the rule the library documents): pixel index = round(angle * n / (2 pi))
mod n, round half to even (np.rint), angles in float64.

Both use `reference.render` for the images, so `reference_direction` below is a full
NumPy path from the scene to the world-frame homing direction.
"""

import math

import numpy as np

from tests.twins.methods import TWO_PI, render, wrap

N_ALPHA, N_PSI, N_RHO, RHO_MIN, RHO_MAX = 72, 72, 15, 0.10, 0.80


def rho_values(n_rho=N_RHO, rho_min=RHO_MIN, rho_max=RHO_MAX):
    """rho_i = rho_min + i * (rho_max - rho_min) / (n_rho - 1) (0.10, 0.15, ..., 0.80)."""
    if n_rho == 1:
        return np.array([float(rho_min)])
    return np.array([rho_min + i * (rho_max - rho_min) / (n_rho - 1) for i in range(n_rho)])


def nearest_pixel(angle, n):
    """Nearest pixel of an angle (radians): round(angle * n / 2pi) mod n, half to even."""
    return np.mod(np.rint(np.asarray(angle, float) * n / TWO_PI).astype(np.int64), n)


def warping_search(S, C, n_alpha=N_ALPHA, n_psi=N_PSI, n_rho=N_RHO, rho_min=RHO_MIN, rho_max=RHO_MAX):
    """First minimum of sum |C_pred - C| over (alpha, rho, psi), alpha outermost, psi innermost.

    S, C: (n,) home and current images (mask as 0/1, or gray).  Returns
    (min distance, alpha index, rho index, psi index).
    """
    S, C = np.asarray(S, float), np.asarray(C, float)
    n = len(S)
    phi = TWO_PI * np.arange(n) / n
    rhos = rho_values(n_rho, rho_min, rho_max)
    best = (math.inf, 0, 0, 0)
    for a in range(n_alpha):
        alpha = TWO_PI * a / n_alpha
        for r, rho in enumerate(rhos):
            for m in range(n_psi):
                psi = TWO_PI * m / n_psi
                g = phi + psi
                pred = S[nearest_pixel(g - np.arcsin(rho * np.sin(g - alpha)), n)]
                dist = float(np.sum(np.abs(pred - C)))
                if dist < best[0]:
                    best = (dist, a, r, m)
    return best


def warping_direction(S, C, **hyp):
    """Homing direction in the agent frame, alpha + pi - psi (docs/model.md §4.3); NaN if S is uniform."""
    S = np.asarray(S, float)
    if np.all(S == S[0]):
        return math.nan
    _, a, _, m = warping_search(S, C, **hyp)
    n_alpha, n_psi = hyp.get("n_alpha", N_ALPHA), hyp.get("n_psi", N_PSI)
    return wrap(TWO_PI * a / n_alpha + math.pi - TWO_PI * m / n_psi)


def mfdid_direction(S, C, compass):
    """MFDID home direction in the agent frame (Möller & Vardy 2006, 1D, with a compass).

    World-frame (alpha_r frame) angle of current pixel j: t_j = compass + 2 pi j / n.
    S is read at t_j by linear interpolation (circular); C'_j = (C[j+1] - C[j-1]) / 2
    (per pixel).  H = sum_j (S(t_j) - C_j) * C'_j * (-sin t_j, cos t_j) is minus the
    gradient of sum (C - S)^2 under the equal-distance flow template; NaN when H = 0.
    """
    S, C = np.asarray(S, float), np.asarray(C, float)
    n = len(S)
    H = np.zeros(2)
    for j in range(n):
        t = compass + TWO_PI * j / n
        x = (t * n / TWO_PI) % n  # position in S's pixel grid
        i0 = int(math.floor(x)) % n
        w = x - math.floor(x)
        s = (1 - w) * S[i0] + w * S[(i0 + 1) % n]
        dc = 0.5 * (C[(j + 1) % n] - C[j - 1])
        H += (s - C[j]) * dc * np.array([-math.sin(t), math.cos(t)])
    if H[0] == 0.0 and H[1] == 0.0:
        return math.nan
    return wrap(math.atan2(H[1], H[0]) - compass)


def reference_direction(
    landmarks, arena, home, point, heading, method, channel="mask", background="distant", alpha_r=0.0, n_pix=360, **hyp
):
    """Noise-free world-frame homing direction of `warping` or `mfdid` at `point`."""
    home, point, h = np.asarray(home, float), np.asarray(point, float), float(heading)
    s_mask, s_gray = render(landmarks, home, alpha_r, arena, background, n_pix)
    c_mask, c_gray = render(landmarks, point, h, arena, background, n_pix)
    S, C = (s_mask.astype(float), c_mask.astype(float)) if channel == "mask" else (s_gray, c_gray)
    if method == "warping":
        agent = warping_direction(S, C, **hyp)
    elif method == "mfdid":
        agent = mfdid_direction(S, C, wrap(h - alpha_r))
    else:
        raise ValueError(f"unknown method {method!r}")
    return math.nan if math.isnan(agent) else wrap(h + agent)
