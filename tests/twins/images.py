"""Plain, per-pixel NumPy reference ("twin") of delvjax's image path (docs/images.md §1-§7): the ray
caster, the panoramic and catadioptric cameras, unwrapping, HSV, thresholds, band rings, blobs,
the database's unit moves and a nearest-snapshot rollout.

Written from docs/images.md in float64 with explicit Python loops; slow on purpose, meant to be
read. A world is a plain dict of NumPy arrays (`world_dict` turns a delvjax `World` into one).
"""

import math

import numpy as np

from tests.twins.sensing import TWO_PI, _wall_fraction, background_value

FAR = math.inf


def world_dict(world):
    """A delvjax `World` (or anything with its fields) as a dict of float64 NumPy arrays."""
    names = (
        "cylinders",
        "cylinder_rgb",
        "boxes",
        "box_rgb",
        "arena",
        "wall_height",
        "floor_rgb",
        "ceiling_rgb",
        "light",
        "ambient",
        "texture",
    )
    return {k: np.asarray(getattr(world, k), dtype=float) for k in names}


# ----------------------------------------------------------------------------- docs/images.md §3
def lambert(world, normal3):
    """a + (1 - a) max(0, n . l) for a unit 3D normal."""
    a = float(world["ambient"])
    return a + (1.0 - a) * max(0.0, float(np.dot(normal3, world["light"])))


def cylinder_distance(o, u, centre, r):
    """Horizontal distance t = b - sqrt(b^2 - c) to a cylinder side along u, 0 from inside, None if missed."""
    rel = centre - o
    b = float(u @ rel)
    c = float(rel @ rel) - r * r
    if c <= 0.0:
        return 0.0
    if b * b < c:
        return None
    t = b - math.sqrt(b * b - c)
    return t if t > 0.0 else None


def box_distance(o, u, box):
    """2D slab test: (t, horizontal face normal) of the first box side along u, or None if missed."""
    t_enter, t_exit, axis = -math.inf, math.inf, 0
    for k in range(2):
        lo, hi = box[k], box[k + 2]
        if u[k] == 0.0:
            if not lo <= o[k] <= hi:
                return None
            continue
        t0, t1 = (lo - o[k]) / u[k], (hi - o[k]) / u[k]
        if t0 > t1:
            t0, t1 = t1, t0
        if t0 > t_enter:
            t_enter, axis = t0, k
        t_exit = min(t_exit, t1)
    if t_enter > t_exit or t_exit <= 0.0:
        return None
    normal = np.zeros(2)
    normal[axis] = -math.copysign(1.0, u[axis])  # the face looks back along the ray
    return max(t_enter, 0.0), normal


def wall_distance(o, u, arena):
    """(t, inward normal) where the ray from o (inside the arena) leaves it."""
    best, normal = math.inf, None
    for k in range(2):
        if u[k] > 0:
            t, n = (arena[k + 2] - o[k]) / u[k], -1.0
        elif u[k] < 0:
            t, n = (arena[k] - o[k]) / u[k], 1.0
        else:
            continue
        if t < best:
            best, normal = t, np.zeros(2)
            normal[k] = n
    return best, normal


def ray_colour(world, origin, cam_height, phi, elevation):
    """RGB seen from (origin, cam_height) along world angle phi at `elevation` (rad), docs/images.md §3."""
    o = np.asarray(origin, dtype=float)
    u = np.array([math.cos(phi), math.sin(phi)])
    tan_e = math.tan(elevation)
    # 1-2. every object side met at t, seen if the ray's height there lies on it; nearest wins
    best_t, best_rgb = math.inf, None
    for (cx, cy, r, height), rgb in zip(world["cylinders"], world["cylinder_rgb"]):
        if height <= 0:
            continue  # padding
        t = cylinder_distance(o, u, np.array([cx, cy]), r)
        if t is None or not 0.0 <= cam_height + t * tan_e <= height:
            continue
        if t < best_t:
            n = (o + t * u - np.array([cx, cy])) / r
            best_t, best_rgb = t, rgb * lambert(world, np.array([n[0], n[1], 0.0]))
    for box, rgb in zip(world["boxes"], world["box_rgb"]):
        if box[4] <= 0:
            continue
        hit = box_distance(o, u, box)
        if hit is None:
            continue
        t, n = hit
        if not 0.0 <= cam_height + t * tan_e <= box[4]:
            continue
        if t < best_t:
            best_t, best_rgb = t, rgb * lambert(world, np.array([n[0], n[1], 0.0]))
    # 3. object, else floor, else wall, else ceiling
    t_wall, n_wall = wall_distance(o, u, world["arena"])
    t_floor = cam_height / math.tan(-elevation) if elevation < 0 else math.inf
    if best_t < min(t_wall, t_floor):
        return best_rgb
    if t_floor < t_wall:
        return world["floor_rgb"] * lambert(world, np.array([0.0, 0.0, 1.0]))
    if cam_height + t_wall * tan_e <= world["wall_height"]:
        f = _wall_fraction(o, u, world["arena"])  # docs/model.md §2.3 perimeter fraction
        grey = 0.5 + float(world["texture"]) * (background_value(TWO_PI * f) - 0.5)
        return np.full(3, grey * lambert(world, np.array([n_wall[0], n_wall[1], 0.0])))
    return world["ceiling_rgb"].copy()


# ----------------------------------------------------------------------------- docs/images.md §2
def row_elevations(rows, top_deg=30.0, bottom_deg=-30.0):
    """e_i = top - (i + 1/2) (top - bottom) / rows, rad."""
    step = (top_deg - bottom_deg) / rows
    return [math.radians(top_deg - (i + 0.5) * step) for i in range(rows)]


def panorama(world, pos, heading, rows, cols, cam_height=25.0, top_deg=30.0, bottom_deg=-30.0):
    """(rows, cols, 3): column j looks along heading + 2 pi j / cols, row i at elevation e_i."""
    out = np.zeros((rows, cols, 3))
    elev = row_elevations(rows, top_deg, bottom_deg)
    for i in range(rows):
        for j in range(cols):
            out[i, j] = ray_colour(world, pos, cam_height, heading + TWO_PI * j / cols, elev[i])
    return out


def donut_pixel(
    world, pos, heading, size, row, col, cam_height=25.0, inner=0.2, outer=0.95, e_in_deg=-30.0, e_out_deg=30.0
):
    """RGB of donut pixel (row, col): equiangular mirror, black outside inner <= rho <= outer."""
    c = (size - 1) / 2.0
    dx, dy = col - c, c - row  # image up is +y
    rho = math.hypot(dx, dy) / (size / 2.0)
    if not inner <= rho <= outer:
        return np.zeros(3)
    e = math.radians(e_in_deg + (rho - inner) / (outer - inner) * (e_out_deg - e_in_deg))
    azimuth = math.atan2(dy, dx) - math.pi / 2  # the robot's forward points up
    return ray_colour(world, pos, cam_height, heading + azimuth, e)


def donut(world, pos, heading, size, **mirror):
    """(size, size, 3) catadioptric image (`donut_pixel` of every pixel)."""
    return np.array(
        [[donut_pixel(world, pos, heading, size, r, c, **mirror) for c in range(size)] for r in range(size)]
    )


# ----------------------------------------------------------------------------- docs/images.md §5
def bilinear(image, y, x):
    """Bilinear sample of image (H, W, C) at (row y, column x); each corner outside the image reads 0."""
    h, w = image.shape[:2]
    y0, x0 = math.floor(y), math.floor(x)
    out = np.zeros(image.shape[2:])
    for yy, wy in ((y0, 1 - (y - y0)), (y0 + 1, y - y0)):
        for xx, wx in ((x0, 1 - (x - x0)), (x0 + 1, x - x0)):
            if 0 <= yy < h and 0 <= xx < w:
                out = out + wy * wx * image[yy, xx]
    return out


def unwrap(image, rows, cols, top_deg=30.0, bottom_deg=-30.0, inner=0.2, outer=0.95, e_in_deg=-30.0, e_out_deg=30.0):
    """Donut (S, S, 3) -> panorama (rows, cols, 3): pixel (i, j) samples radius rho(e_i), angle 2 pi j / W + pi / 2."""
    size = image.shape[0]
    c = (size - 1) / 2.0
    out = np.zeros((rows, cols, image.shape[2]))
    for i, e in enumerate(row_elevations(rows, top_deg, bottom_deg)):
        frac = (math.degrees(e) - e_in_deg) / (e_out_deg - e_in_deg)
        rho = (inner + frac * (outer - inner)) * size / 2.0
        for j in range(cols):
            theta = TWO_PI * j / cols + math.pi / 2
            out[i, j] = bilinear(image, c - rho * math.sin(theta), c + rho * math.cos(theta))
    return out


def rgb_to_hsv(rgb):
    """The hexcone for one pixel: (hue in [0, 1), red 0; saturation; value)."""
    r, g, b = (float(v) for v in rgb)
    v = max(r, g, b)
    c = v - min(r, g, b)
    s = c / v if v > 0 else 0.0
    if c == 0:
        h = 0.0
    elif v == r:
        h = ((g - b) / c) % 6.0
    elif v == g:
        h = 2.0 + (b - r) / c
    else:
        h = 4.0 + (r - g) / c
    return (h / 6.0) % 1.0, s, v


def hue_distance_deg(a_deg, b_deg):
    """Circular distance of two hues, degrees in [0, 180]."""
    d = abs(a_deg - b_deg) % 360.0
    return min(d, 360.0 - d)


def is_landmark(hsv, hue_deg=0.0, hue_width_deg=40.0, sat_min=0.5, val_min=0.15):
    """docs/images.md §5.4 threshold of one HSV pixel."""
    h, s, v = hsv
    return hue_distance_deg(h * 360.0, hue_deg) <= hue_width_deg / 2 and s >= sat_min and v >= val_min


def band_rows(rows, band_deg=0.0, band_height_deg=10.0, top_deg=30.0, bottom_deg=-30.0):
    """Rows whose centre elevation lies in the band; the nearest row(s) if none does."""
    off = [abs(math.degrees(e) - band_deg) for e in row_elevations(rows, top_deg, bottom_deg)]
    inside = [i for i, o in enumerate(off) if o <= band_height_deg / 2]
    return inside or [i for i, o in enumerate(off) if o == min(off)]


def band_rings(image, band_deg=0.0, band_height_deg=10.0, top_deg=30.0, bottom_deg=-30.0, **threshold):
    """(landmark share (cols,), mean value (cols,)) of a panorama's band of rows."""
    rows, cols = image.shape[:2]
    sel = band_rows(rows, band_deg, band_height_deg, top_deg, bottom_deg)
    share, gray = np.zeros(cols), np.zeros(cols)
    for j in range(cols):
        for i in sel:
            hsv = rgb_to_hsv(image[i, j])
            share[j] += is_landmark(hsv, **threshold)
            gray[j] += hsv[2]
    return share / len(sel), gray / len(sel)


def blob_runs(mask):
    """docs/model.md §2.4 blobs with widths: (bearings, widths), sorted by bearing in [0, 2pi)."""
    mask = np.asarray(mask, dtype=bool)
    n = len(mask)
    if mask.all():
        return np.array([0.0]), np.array([TWO_PI])
    blobs = []
    for j in range(n):
        if mask[j] and not mask[j - 1]:
            length = 0
            while mask[(j + length) % n]:
                length += 1
            blobs.append((((j + (length - 1) / 2.0) * TWO_PI / n) % TWO_PI, length * TWO_PI / n))
    blobs.sort()
    return np.array([b for b, _ in blobs]), np.array([w for _, w in blobs])


def ring_blobs(share, fill=0.5):
    """(mask, bearings, widths) of band rings: the mask is share >= fill."""
    mask = np.asarray(share) >= fill
    return (mask,) + blob_runs(mask)
