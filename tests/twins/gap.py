"""NumPy twin of gap-aware DELV arrangement matching (delv_gap.match_arrangement_gapped), float64.

Every order-preserving cyclic pairing: an n-subset of the larger list (n = min(N, M)), in
the order of itertools.combinations, paired with the smaller list under each shift
k < n; for each pairing and alpha, Eqs 3.4-3.6 are evaluated directly. The first strict
minimum in (subset, shift, alpha) order wins.
"""

from __future__ import annotations

import itertools
import math

import numpy as np


def gapped_pairs(N, M, subset, k):
    """(reference index, current index) pairs for one subset of the larger list and shift k."""
    n = len(subset)
    if M <= N:  # the reference list is the larger one: current j pairs reference subset[(j + k) % n]
        return [(subset[(j + k) % n], j) for j in range(n)]
    return [(i, subset[(i + k) % n]) for i in range(n)]


def candidates(ref_vecs, cur_vecs, alphas):
    """Yield every (subset, k, alpha, (px, py), var) in search order; nothing when n = 0."""
    ref = np.asarray(ref_vecs, dtype=float).reshape(-1, 2).tolist()  # Python floats: fast scalar loops
    cur = np.asarray(cur_vecs, dtype=float).reshape(-1, 2).tolist()
    N, M = len(ref), len(cur)
    n = min(N, M)
    if n == 0:
        return
    for subset in itertools.combinations(range(max(N, M)), n):
        for k in range(n):
            pairs = gapped_pairs(N, M, subset, k)
            for alpha in alphas:
                ca, sa = math.cos(alpha), math.sin(alpha)
                e = []
                for i, j in pairs:  # Eq 3.4: e = V^R_i - Rot(alpha) V_j
                    (rx, ry), (cx, cy) = ref[i], cur[j]
                    e.append((rx - (ca * cx - sa * cy), ry - (sa * cx + ca * cy)))
                px = sum(x for x, _ in e) / n  # Eq 3.5
                py = sum(y for _, y in e) / n
                var = sum((x - px) ** 2 + (y - py) ** 2 for x, y in e)  # Eq 3.6
                yield subset, k, float(alpha), (px, py), var


def match_arrangement_gapped(ref_vecs, cur_vecs, alphas):
    """(p, alpha, var, n) of the first strict minimum, or None when n = min(N, M) = 0."""
    best = None
    for subset, k, alpha, p, var in candidates(ref_vecs, cur_vecs, alphas):
        if best is None or var < best[2]:
            best = (np.array(p), alpha, var, len(subset))
    return best
