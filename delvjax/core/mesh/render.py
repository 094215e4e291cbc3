"""Panoramas of a triangle mesh, ray by ray (docs/mesh.md §2): the ray from the eye through every pixel centre
meets the nearest triangle in front of the eye, else the ground (z = 0, below the horizon), else the sky.

A ray along d from the eye meets triangle (a, b, c) (corners relative to the eye) where d lies in the cone the
corners span: the three edge-plane tests (a x b) . d, (b x c) . d, (c x a) . d share a sign (a triangle seen
from either side), and the hit is in front: t = (n . a) / (n . d) > 0, n = (b - a) x (c - a).

Most triangles of a habitat are small in the view, so each triangle is first placed in the image (its corners'
azimuth and elevation as fractional pixels). A small one (its corners within SPLAT x SPLAT pixel centres, with
a margin for the bulge of a great-circle edge) is tested against those pixels' rays only and its hits are
merged by a scatter-min of depth (then of the triangle's index among the nearest), SPLAT_CHUNK at a time and
only if a pixel centre lies within its bounds (most small ones fall between pixel centres: 60 % of habitat0's
in the ant eye); a middling one (within MID x MID) and a medium one (MEDIUM x MEDIUM) likewise; the large ones
(near the eye, around a pole, across the seam) are tested against every pixel, CHUNK at a time. The tiers are
`while_loop`s over the triangles of their tier, gathered in index order, that stop after the last. Every tier
is the exact ray test above, so the image is the brute-force one (ties to the lower index)."""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..geometry import wrap
from .eye import Eye
from .mesh import Mesh

SPLAT, SPLAT_CHUNK = 4, 1024  # a small triangle's candidate pixels: SPLAT x SPLAT, SPLAT_CHUNK of them at a time
MID, MID_CHUNK = 8, 64  # a middling one's: MID x MID
MEDIUM, MEDIUM_CHUNK = 16, 16  # a medium one's: MEDIUM x MEDIUM, MEDIUM_CHUNK of them at a time
CHUNK = 8  # large triangles tested side by side against every pixel
ROW_MARGIN, COL_MARGIN = 0.5, 0.05  # pixels added about a triangle's corners (an edge bulges in elevation)
FAR = 1e12


def corners(mesh: Mesh, origin: ArrayLike) -> list[list[Array]]:
    """The corners relative to `origin` (3,) by component: [corner][x, y, z], each (T,) (a CPU is slow on
    an axis of 3: the arithmetic is written out by component)."""
    o = jnp.asarray(origin, jnp.float32)
    return [[mesh.vertices[:, k, j] - o[j] for j in range(3)] for k in range(3)]


def cross(u: list[Array], v: list[Array]) -> list[Array]:
    """u x v by component."""
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def triangle_planes(mesh: Mesh, origin: ArrayLike) -> Array:
    """(13, T) per triangle relative to `origin` (3,): the edge-plane normals a x b, b x c, c x a, the normal
    n and n . a; a padding triangle gets a zero normal (never hit)."""
    a, b, c = corners(mesh, origin)
    n = cross([b[j] - a[j] for j in range(3)], [c[j] - a[j] for j in range(3)])
    n = [jnp.where(mesh.valid, x, 0.0) for x in n]
    return jnp.stack([*cross(a, b), *cross(b, c), *cross(c, a), *n, n[0] * a[0] + n[1] * a[1] + n[2] * a[2]])


def depth_of(p: tuple, dx: Array, dy: Array, dz: Array) -> Array:
    """Depth t of the ray (dx, dy, dz) against a triangle's 13 plane components (`triangle_planes`; each
    broadcast): FAR where it misses (written out by component: a reduction over an axis of 3 is slow on a CPU)."""
    s0 = dx * p[0] + dy * p[1] + dz * p[2]
    s1 = dx * p[3] + dy * p[4] + dz * p[5]
    s2 = dx * p[6] + dy * p[7] + dz * p[8]
    nd = dx * p[9] + dy * p[10] + dz * p[11]
    inside = ((s0 >= 0) & (s1 >= 0) & (s2 >= 0)) | ((s0 <= 0) & (s1 <= 0) & (s2 <= 0))
    t = p[12] / jnp.where(nd == 0, 1.0, nd)
    return jnp.where(inside & (nd != 0) & (t > 0), t, FAR)


def placement(mesh: Mesh, eye: Eye, origin: Array, turn: Array) -> tuple[Array, Array, Array]:
    """Per triangle: the first and last candidate pixel (row, col) and its size in pixels (the larger side; a
    huge number where its corners do not place it: across the seam of azimuth, around a pole)."""
    v = corners(mesh, origin)
    x, y, z = (jnp.stack([sum(v[k][j] * turn[j, i] for j in range(3)) for k in range(3)], -1) for i in range(3))
    az = jnp.arctan2(y, x)  # (T, 3) in the eye frame: turn^T (v - origin)
    az = az[:, :1] + wrap(az - az[:, :1])  # unwrapped about the first corner
    el = jnp.arctan2(z, jnp.hypot(x, y))
    row, col = eye.fractional_pixel(az, el)
    r0 = jnp.ceil(jnp.min(row, -1) - ROW_MARGIN)
    r1 = jnp.floor(jnp.max(row, -1) + ROW_MARGIN)
    c0 = jnp.ceil(jnp.min(col, -1) - COL_MARGIN)
    c1 = jnp.floor(jnp.max(col, -1) + COL_MARGIN)
    span = jnp.max(az, -1) - jnp.min(az, -1)
    placed = (span < jnp.pi / 2) & jnp.all(jnp.isfinite(row), -1) & mesh.valid
    size = jnp.where(placed, jnp.maximum(r1 - r0, c1 - c0) + 1, 1e9)
    first = jnp.stack([r0, c0], -1).astype(jnp.int32)
    return first, jnp.stack([r1, c1], -1).astype(jnp.int32), size


def window_hits(planes: Array, d: Array, first: Array, last: Array, ids: Array, live: Array, eye: Eye, size: int):
    """(t, index) (P,) of the nearest of triangles `ids` (K,) (`live` ones) along every ray, each tested at the
    size x size pixels from its first candidate: a scatter-min of depth, then of the index among the nearest."""
    k = jnp.arange(size)
    f, l_ = first[ids], last[ids]
    rr = f[:, 0, None, None] + k[None, :, None]  # (K, S, 1)
    cc = f[:, 1, None, None] + k[None, None, :]  # (K, 1, S)
    ok = live[:, None, None] & (rr <= l_[:, 0, None, None]) & (cc <= l_[:, 1, None, None])
    ok = ok & (rr >= 0) & (rr < eye.rows)
    cc = jnp.mod(cc, eye.cols) if eye.cyclic else cc
    ok = ok & (cc >= 0) & (cc < eye.cols)
    pix = jnp.where(ok, rr * eye.cols + cc, 0)  # (K, S, S)
    dp = d[pix]
    pl = planes[:, ids][:, :, None, None]  # (13, K, 1, 1)
    t = jnp.where(ok, depth_of(tuple(pl), dp[..., 0], dp[..., 1], dp[..., 2]), FAR)
    p = d.shape[0]
    zbuf = jnp.full(p, FAR, jnp.float32).at[pix.ravel()].min(t.ravel())
    n = planes.shape[1]
    won = (t < FAR) & (t == zbuf[pix])
    index = jnp.full(p, n, jnp.int32).at[pix.ravel()].min(jnp.where(won, ids[:, None, None], n).ravel())
    return zbuf, index


def nearer(a: tuple[Array, Array], b: tuple[Array, Array]) -> tuple[Array, Array]:
    """Per pixel the nearer of two (t, index) hits, ties to the lower index (an index of T: none)."""
    take_b = (b[0] < a[0]) | ((b[0] == a[0]) & (b[1] < a[1]))
    return jnp.where(take_b, b[0], a[0]), jnp.where(take_b, b[1], a[1])


def chunked(members: Array, width: int, hits, init: tuple[Array, Array]) -> tuple[Array, Array]:
    """`hits(ids, live)` over the `members` triangles `width` at a time (a `while_loop` that stops after the last),
    merged with `nearer`."""
    n = members.shape[0]
    count = jnp.sum(members)
    at = jnp.where(members, jnp.cumsum(members) - 1, n + width)  # the members first, in index order
    order = jnp.zeros(n + width, jnp.int32).at[at].set(jnp.arange(n, dtype=jnp.int32), mode="drop")

    def body(carry):
        best, start = carry
        ids = jax.lax.dynamic_slice(order, (start,), (width,))
        return nearer(best, hits(ids, start + jnp.arange(width) < count)), start + width

    best, _ = jax.lax.while_loop(lambda c: c[1] < count, body, (init, jnp.int32(0)))
    return best


def every_pixel_hits(planes: Array, d: Array, ids: Array, live: Array) -> tuple[Array, Array]:
    """(t, index) (P,) of the nearest of triangles `ids` (K,) (`live` ones) along every ray: each against every pixel."""
    pl = jnp.where(live[None], planes[:, ids], 0.0)[:, None, :]  # (13, 1, K); a dead one has a zero normal
    t = depth_of(tuple(pl), d[:, 0:1], d[:, 1:2], d[:, 2:3])  # (P, K)
    k = jnp.argmin(t, -1)
    return jnp.min(t, -1), jnp.where(jnp.min(t, -1) < FAR, ids[k], planes.shape[1])


def mesh_colours(mesh: Mesh, eye: Eye, pose: ArrayLike) -> Array:
    """(rows * cols, 3) the colour of every pixel at `pose` (module docstring)."""
    pose = jnp.asarray(pose, jnp.float32)
    origin, turn = pose[:3], eye.orientation(pose[3:])
    d = eye.rays(pose[3:]).reshape(-1, 3)
    planes = triangle_planes(mesh, origin)
    first, last, size = placement(mesh, eye, origin, turn)
    n = planes.shape[1]
    seen = (last[:, 0] >= first[:, 0]) & (last[:, 1] >= first[:, 1]) & (last[:, 0] >= 0) & (first[:, 0] < eye.rows)
    if not eye.cyclic:
        seen = seen & (last[:, 1] >= 0) & (first[:, 1] < eye.cols)  # a candidate pixel in view
    init = (jnp.full(d.shape[0], FAR, jnp.float32), jnp.full(d.shape[0], n, jnp.int32))
    tier = lambda w: lambda ids, live: window_hits(planes, d, first, last, ids, live, eye, w)  # noqa: E731
    best = chunked(seen & (size <= SPLAT), SPLAT_CHUNK, tier(SPLAT), init)
    best = chunked(seen & (size > SPLAT) & (size <= MID), MID_CHUNK, tier(MID), best)
    medium = (size > MID) & (size <= MEDIUM)
    best = chunked(
        medium, MEDIUM_CHUNK, lambda ids, live: window_hits(planes, d, first, last, ids, live, eye, MEDIUM), best
    )
    large = (size > MEDIUM) & mesh.valid
    t, i = chunked(large, CHUNK, lambda ids, live: every_pixel_hits(planes, d, ids, live), best)
    below = d[:, 2] < 0
    t_ground = jnp.where(below, -origin[2] / jnp.where(below, d[:, 2], -1.0), FAR)
    back = jnp.where(below[:, None], mesh.ground_rgb, mesh.sky_rgb)
    return jnp.where(((i < n) & (t < t_ground))[:, None], mesh.rgb[jnp.minimum(i, n - 1)], back)


def mesh_panorama(mesh: Mesh, eye: Eye, pose: ArrayLike) -> Array:
    """(rows, cols, 3) colour panorama at `pose` = (x, y, z, heading[, pitch, roll]) (cm, rad; `Eye.rays`)."""
    return mesh_colours(mesh, eye, pose).reshape(eye.rows, eye.cols, 3)


def mesh_panoramas(mesh: Mesh, eye: Eye, poses: ArrayLike, batch: int = 16) -> Array:
    """`mesh_panorama` at every pose (N, 4..6): (N, rows, cols, 3), `batch` poses side by side (memory bounded)."""
    return jax.lax.map(lambda p: mesh_panorama(mesh, eye, p), jnp.asarray(poses, jnp.float32), batch_size=batch)
