"""Plain, per-landmark NumPy twin of the Cartwright & Collett snapshot model (landmarks only).

Same semantics as delvjax's `cc_home_vector` (see its module docstring for the equations),
written with explicit Python loops over the landmarks in float64, to be read and to check
the vectorised JAX version against.
"""

import math

import numpy as np

TWO_PI = 2.0 * math.pi


def wrap(a):
    """Map an angle to (-pi, pi]."""
    r = math.pi - (math.pi - a) % TWO_PI  # Python's % is in [0, 2pi), so r is in (-pi, pi] ...
    return r + TWO_PI if r <= -math.pi else r  # ... unless % rounded up to 2pi


def _unit(a):
    return np.array([math.cos(a), math.sin(a)])


def _sign(x):
    return (x > 0) - (x < 0)


def cc_home_vector_ref(ref_bearing, ref_width, ref_valid, cur_bearing, cur_width, cur_valid, radial_weight=1.0):
    """Home vector H (2,) float64 and validity (bool); invalid slots are skipped."""
    snapshot = [(float(b), float(s)) for b, s, ok in zip(ref_bearing, ref_width, ref_valid) if ok]
    current = [(float(a), float(w)) for a, w, ok in zip(cur_bearing, cur_width, cur_valid) if ok]
    h = np.zeros(2)
    if not snapshot or not current:
        return h, False
    for theta, s in snapshot:
        # the current landmark closest in bearing; on a tie the first one wins
        best = None
        for a, w in current:
            d = abs(wrap(a - theta))
            if best is None or d < best[0]:
                best = (d, a, w)
        _, c, w = best
        # tangential: a step along +u(c + pi/2) lowers the bearing c, so go against it
        # when the snapshot bearing theta is larger (counter-clockwise) than c
        tangential = -_sign(wrap(theta - c)) * _unit(c + math.pi / 2)
        # radial: looks smaller than in the snapshot -> too far -> toward the landmark
        radial = _sign(s - w) * _unit(c)
        h += tangential + radial_weight * radial
    return h, bool(math.hypot(h[0], h[1]) > 0)
