"""Plain NumPy reference of homing on an image database (docs/images.md §6-7): the unit move ending at a
database point, the roll into its frame, and one nearest-snapshot rollout trial."""

import math

import numpy as np

from tests.twins.sensing import TWO_PI

# ----------------------------------------------------------------------------- docs/images.md §6
WEST_SOUTH_EAST_NORTH = [(-1.0, 0.0), (0.0, -1.0), (1.0, 0.0), (0.0, 1.0)]


def find_image(positions, target, spacing):
    """Index of the image nearest `target` if within 0.25 spacing, else None."""
    d = [math.hypot(p[0] - target[0], p[1] - target[1]) for p in positions]
    i = int(np.argmin(d))
    return i if d[i] <= 0.25 * spacing else None


def move_for_point(positions, headings, c, spacing, n_pix, home=False):
    """The unit move of database point c: (start, end, shift k, d_hat, ok, shift k_end). A point's move
    starts at its first neighbour west, south, east, north; the home record's move goes from home to
    its first neighbour east, north, west, south. k = round((m - h_P) / (2 pi / n_pix)) mod n_pix rolls
    the start view to the move direction m, k_end (with h_C) the end view: the agent moves straight."""
    positions = np.asarray(positions, dtype=float)
    order = WEST_SOUTH_EAST_NORTH[2:] + WEST_SOUTH_EAST_NORTH[:2] if home else WEST_SOUTH_EAST_NORTH
    for dx, dy in order:
        j = find_image(positions, positions[c] + spacing * np.array([dx, dy]), spacing)
        if j is not None:
            start, end = (c, j) if home else (j, c)
            delta = positions[end] - positions[start]
            m = math.atan2(delta[1], delta[0])
            k = int(round((m - float(headings[start])) / (TWO_PI / n_pix))) % n_pix
            k_end = int(round((m - float(headings[end])) / (TWO_PI / n_pix))) % n_pix
            return start, end, k, float(np.hypot(*delta)), True, k_end
    return c, c, 0, 0.0, False, 0


def rolled_snapshot(mask, gray, bearings, widths, k):
    """A ring snapshot seen with column k as column 0: rings rolled, bearings turned by k pixels and sorted."""
    n = len(mask)
    turned = [((b - k * TWO_PI / n) % TWO_PI, w) for b, w in zip(bearings, widths)]
    turned.sort()
    return (np.roll(mask, -k), np.roll(gray, -k), np.array([b for b, _ in turned]), np.array([w for _, w in turned]))


# ----------------------------------------------------------------------------- docs/images.md §7
SUCCESS, TIMEOUT, LANDMARK, ARENA, UNDEFINED = range(5)
RUNNING = -1


def trial_status(x, home, home_radius, arena, cylinders, boxes, tol=1e-3):
    """Landmark (inside an obstacle), else arena (outside), else success (within home_radius), else running."""
    for cx, cy, r in cylinders:
        if (x[0] - cx) ** 2 + (x[1] - cy) ** 2 < r * r:
            return LANDMARK
    for x0, y0, x1, y1 in boxes:
        if x0 < x[0] < x1 and y0 < x[1] < y1:
            return LANDMARK
    if not (arena[0] <= x[0] <= arena[2] and arena[1] <= x[1] <= arena[3]):
        return ARENA
    if math.hypot(x[0] - home[0], x[1] - home[1]) <= home_radius + tol:
        return SUCCESS
    return RUNNING


def rollout_trial(
    positions,
    direction,
    valid,
    home,
    arena,
    cylinders,
    boxes,
    start,
    draws,
    step,
    home_radius,
    heading_noise,
    step_noise,
    max_steps,
):
    """One nearest-snapshot trial: (outcome, steps, path (max_steps + 1, 2)). draws[t] = the two N(0, 1)
    numbers of move t (heading error, step error)."""
    positions = np.asarray(positions, dtype=float)
    x = np.asarray(start, dtype=float)
    code = trial_status(x, home, home_radius, arena, cylinders, boxes)
    path, steps = [x.copy()], 0
    for t in range(max_steps):
        if code == RUNNING:
            i = int(np.argmin([np.sum((p - x) ** 2) for p in positions]))
            if not valid[i]:
                code = UNDEFINED
            else:
                h = float(direction[i]) + heading_noise * draws[t][0]
                x = x + step * (1.0 + step_noise * draws[t][1]) * np.array([math.cos(h), math.sin(h)])
                steps += 1
                code = trial_status(x, home, home_radius, arena, cylinders, boxes)
        path.append(x.copy())
    return (TIMEOUT if code == RUNNING else code), steps, np.array(path)
