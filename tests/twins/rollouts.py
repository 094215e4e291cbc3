"""Plain per-point NumPy reference of a noise-free homing rollout (docs/model.md §5), built from tests/twins/methods.py.

One trial at a time, one move at a time, in float64. At the release point the agent
computes the homing direction exactly as in the vector map: from a unit move of length d
along the release heading that *ends* at the start (start snapshot at start - d u(h), end
snapshot at the start, both with heading h). Under first_move="release" (the default, thesis
Algorithm 2) a DELV agent does not turn to it: it first moves d along the release heading; an
ALV or ACV agent (no unit movement needed) turns to it (keeps h if invalid), as every agent does
under first_move="homing". Then, repeatedly: move d along the heading, take the move just made
as the unit movement (start and end snapshots rendered at the true poses), ask the method for a
direction at the end point and turn to it.

Rules (docs/model.md §5): collisions="fail" ends a trial whose move ends inside a landmark
(distance to its centre < r) as LANDMARK, whereas with collisions="ignore" (the default)
landmarks are no obstacles. first_move="release", collisions="fail" are the physical rules.
"""

import math

import numpy as np

from tests.twins.methods import (
    acv_direction,
    alv_direction,
    delv_direction,
    extract_blobs,
    render,
    visual_compass,
    wrap,
)

SUCCESS, TIMEOUT, LANDMARK, ARENA = range(4)
FIRST_MOVES = ("release", "homing")
COLLISIONS = ("ignore", "fail")
HOME_TOLERANCE = 1e-3  # the library's inclusive "within home_radius" (delvjax.core.rollouts.rules)


def _unit(a):
    return np.array([math.cos(a), math.sin(a)])


class HomeRecord:
    """Blobs and gray image of the home unit move (from home along alpha_r, all landmarks seen)."""

    def __init__(self, landmarks, arena, home, d=50.0, alpha_r=0.0, background="distant", n_pix=360):
        home = np.asarray(home, float)
        s_mask, self.gray = render(landmarks, home, alpha_r, arena, background, n_pix)
        e_mask, _ = render(landmarks, home + d * _unit(alpha_r), alpha_r, arena, background, n_pix)
        self.start_b, self.end_b = extract_blobs(s_mask), extract_blobs(e_mask)
        self.d, self.alpha_r = d, alpha_r


def move_direction(
    record, landmarks, arena, start, end, heading, method, levels=None, background="distant", n_heading=360, n_pix=360
):
    """Agent-frame homing direction at `end` after the straight move start -> end with `heading` (nan if invalid).

    Odometry reports d_hat = d and no turn; the compass reads heading - alpha_r exactly."""
    s_mask, _ = render(landmarks, start, heading, arena, background, n_pix)
    e_mask, e_gray = render(landmarks, end, heading, arena, background, n_pix)
    start_b, end_b = extract_blobs(s_mask), extract_blobs(e_mask)
    compass = wrap(heading - record.alpha_r)
    if method.endswith("-visual"):
        compass = visual_compass(record.gray, e_gray)
    if method.startswith("delv"):
        fixed = None if method == "delv" else compass
        agent, _ = delv_direction(
            record.start_b,
            record.end_b,
            start_b,
            end_b,
            record.d,
            0.0,
            record.d,
            0.0,
            levels=levels,
            n_heading=n_heading,
            alpha_fixed=fixed,
        )
        return agent
    fn = alv_direction if method.startswith("alv") else acv_direction
    return fn(record.start_b, end_b, compass)


def release_direction(
    record, landmarks, arena, start, heading, method, d=50.0, levels=None, background="distant", n_heading=360
):
    """World homing direction at the release point `start` with release `heading` (nan if invalid):
    the vector map's direction there (a unit move of length d along `heading` that ends at `start`)."""
    start = np.asarray(start, float)
    agent = move_direction(
        record, landmarks, arena, start - d * _unit(heading), start, heading, method, levels, background, n_heading
    )
    return math.nan if math.isnan(agent) else float(wrap(heading + agent))


def status(landmarks_all, arena, home, pos, home_radius, collide=False):
    """docs/model.md §5: inside a landmark (failure, only if `collide`, the rule collisions="fail") or outside the
    arena (failure), at home (success), else None."""
    if collide:
        for x, y, r in landmarks_all:
            if math.hypot(pos[0] - x, pos[1] - y) < r:
                return LANDMARK
    if not (arena[0] <= pos[0] <= arena[2] and arena[1] <= pos[1] <= arena[3]):
        return ARENA
    if math.hypot(pos[0] - home[0], pos[1] - home[1]) <= home_radius + HOME_TOLERANCE:
        return SUCCESS
    return None


def reference_rollout(
    landmarks,
    arena,
    home,
    start,
    heading,
    method,
    d=50.0,
    home_radius=50.0,
    max_steps=50,
    visible=None,
    levels=None,
    background="distant",
    n_heading=360,
    record=None,
    first_move="release",
    collisions="ignore",
):
    """Noise-free rollout from `start` with release `heading` (rad): (outcome, steps, path list).

    `visible` (bool per landmark) hides landmarks from the views during homing (the home
    record sees all; with collisions="fail" hidden landmarks still block the way).
    `first_move` ("release" | "homing") and `collisions` ("ignore" | "fail"): the rules of
    the module docstring.
    """
    if first_move not in FIRST_MOVES:
        raise ValueError(f"first_move must be one of {FIRST_MOVES}, not {first_move!r}")
    if collisions not in COLLISIONS:
        raise ValueError(f"collisions must be one of {COLLISIONS}, not {collisions!r}")
    collide = collisions == "fail"
    landmarks = np.asarray(landmarks, float).reshape(-1, 3)
    seen = landmarks if visible is None else landmarks[np.asarray(visible, bool)]
    if record is None:
        record = HomeRecord(landmarks, arena, home, d, background=background)
    pos, h = np.asarray(start, float), float(heading)
    path = [pos.copy()]
    code = status(landmarks, arena, home, pos, home_radius, collide)
    if code is not None:
        return code, 0, path
    if first_move == "homing" or not method.startswith("delv"):  # turn to the direction at the release point
        direction = release_direction(record, seen, arena, pos, h, method, d, levels, background, n_heading)
        if not math.isnan(direction):
            h = direction
    for step in range(1, max_steps + 1):
        end = pos + d * _unit(h)
        path.append(end.copy())
        code = status(landmarks, arena, home, end, home_radius, collide)
        if code is not None:
            return code, step, path
        agent = move_direction(record, seen, arena, pos, end, h, method, levels, background, n_heading)
        if not math.isnan(agent):
            h = float(wrap(h + agent))
        pos = end
    return TIMEOUT, max_steps, path


if __name__ == "__main__":
    # four explicit cylinders (not a built-in environment, whose layout may change)
    lms = np.array([[330, 640, 30], [640, 720, 40], [720, 390, 25], [420, 300, 35]], float)
    arena, home = [0, 0, 1000, 1000], [500, 500]
    for method in ("alv", "acv", "delv-compass"):
        for rules in ({}, {"first_move": "release", "collisions": "fail"}):
            print(
                method,
                rules or "default rules",
                reference_rollout(lms, arena, home, [200, 200], 0.3, method, **rules)[:2],
            )
