"""A plain NumPy ray caster of triangle meshes (docs/mesh.md), float64, written independently of
`core/mesh/render.py`: the Moller-Trumbore test of every pixel's centre ray against every triangle, a loop
over pixels, and the flag of pixels whose ray passes within `tol` (barycentric) of an edge of a triangle it
meets or nearly meets (where rounding may pick another triangle)."""

from __future__ import annotations

import math

import numpy as np


def eye_rays(rows, cols, width_deg, top_deg, bottom_deg, heading, pitch=0.0, roll=0.0):
    """(rows, cols, 3) world directions of the pixel centres (columns counter-clockwise from the right edge;
    for 360 deg column j at heading + 360 j / cols)."""
    if width_deg >= 360:
        az = np.radians(360.0 * np.arange(cols) / cols)
    else:
        az = np.radians(-width_deg / 2 + width_deg / cols * (np.arange(cols) + 0.5))
    el = np.radians(top_deg - (top_deg - bottom_deg) / rows * (np.arange(rows) + 0.5))
    out = np.zeros((rows, cols, 3))
    ch, sh, cp, sp, cr, sr = (f(a) for a in (heading, pitch, roll) for f in (math.cos, math.sin))
    rz = np.array([[ch, -sh, 0], [sh, ch, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, -sp], [0, 1, 0], [sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    turn = rz @ ry @ rx
    for i in range(rows):
        for j in range(cols):
            local = np.array([math.cos(el[i]) * math.cos(az[j]), math.cos(el[i]) * math.sin(az[j]), math.sin(el[i])])
            out[i, j] = turn @ local
    return out


def cast(vertices, origin, d, tol=1e-4):
    """(index of the nearest triangle hit in front, or -1; its depth; whether the ray is near an edge)."""
    v0, v1, v2 = vertices[:, 0] - origin, vertices[:, 1] - origin, vertices[:, 2] - origin
    e1, e2 = v1 - v0, v2 - v0
    p = np.cross(d, e2)
    det = np.sum(e1 * p, -1)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = -v0
    u = np.sum(s * p, -1) * inv
    q = np.cross(s, e1)
    v = np.sum(d * q, -1) * inv
    t = np.sum(e2 * q, -1) * inv
    w = 1.0 - u - v
    margin = np.minimum(np.minimum(u, v), w)
    hit = ok & (margin >= 0) & (t > 0)
    near = ok & (np.abs(margin) < tol) & (t > 0)
    if not hit.any():
        return -1, math.inf, bool(near.any())
    k = int(np.argmin(np.where(hit, t, np.inf)))
    close = np.abs(t - t[k]) < 1e-6 * max(t[k], 1.0)
    return k, float(t[k]), bool(near[t <= t[k] * (1 + 1e-6)].any() or np.sum(hit & close) > 1)


def render(vertices, rgb, ground, sky, pose, rows, cols, width_deg, top_deg, bottom_deg):
    """(rows, cols, 3) colours and (rows, cols) near-edge flags at pose (x, y, z, heading, pitch, roll)."""
    vertices = np.asarray(vertices, np.float64)
    origin = np.asarray(pose[:3], np.float64)
    rays = eye_rays(rows, cols, width_deg, top_deg, bottom_deg, *pose[3:])
    img = np.zeros((rows, cols, 3))
    flag = np.zeros((rows, cols), bool)
    for i in range(rows):
        for j in range(cols):
            d = rays[i, j]
            k, t, near = cast(vertices, origin, d)
            t_ground = -origin[2] / d[2] if d[2] < 0 else math.inf
            img[i, j] = rgb[k] if k >= 0 and t < t_ground else (ground if d[2] < 0 else sky)
            flag[i, j] = near or (k >= 0 and abs(t - t_ground) < 1e-6 * t) or abs(d[2]) < 1e-9
    return img, flag
