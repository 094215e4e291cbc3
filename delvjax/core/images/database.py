"""Homing on an image database (docs/images.md §6): every snapshot reduced to a ring `Snapshot`,
unit moves between grid neighbours, and the vector map of any method over the database.

As in the thesis's robot experiments (§4.4.1: snapshots every 20 cm, unit move 20 cm), the unit
movement that ends at a database point C starts at a neighbour P one spacing away: the first of
the four axis neighbours (west, south, east, north of C; the agent moved east, north, west or
south) that is in the database. The agent moves straight: each snapshot is rolled by its own whole
pixels so that its column 0 looks along the move (exact for axis moves and headings that are
multiples of the pixel size); the odometry reports the true distance |C - P| and the turn left
between the two rolled views (zero on the pixel lattice, else under a pixel), and the compass reads
the heading exactly. So the answer does not depend on where each camera's column 0 looked.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array
from jax.typing import ArrayLike

from ..batching import fixed_width_map, item_width, local_mesh, over_devices
from ..errors import InputError
from ..estimation import reference_vectors
from ..geometry import rotate, wrap
from ..kernel import world_direction
from ..methods.base import HomingMethod
from ..metrics import angular_error_deg
from ..sensing import Snapshot, UnitMove, sort_blobs

# the agent moved east, north, west, south: the start is one spacing west, south, east, north
MOVES = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]], np.float32)
TOLERANCE = 0.25  # a neighbour within 0.25 spacing of the expected place counts


class RingDatabase(eqx.Module):
    """snapshots: a `Snapshot` with a leading axis N (one per image); positions: (N, 2) cm;
    headings: (N,) rad, world heading of every image's column 0."""

    snapshots: Snapshot
    positions: Array
    headings: Array


class MovePlan(eqx.Module):
    """The unit move that ends at every database point (host arrays of length N, `move_plan`):
    start, end: indices; shift, shift_end: whole-pixel rolls of the start and end views into the
    move's frame; d_hat: |C - P| cm; ok: the point has a neighbour (else its direction is invalid)."""

    start: ArrayLike
    end: ArrayLike
    shift: ArrayLike
    shift_end: ArrayLike
    d_hat: ArrayLike
    ok: ArrayLike


def neighbour(positions: np.ndarray, targets: np.ndarray, spacing: float) -> np.ndarray:
    """Index of the database point within TOLERANCE * spacing of each target, else -1 (k-d tree)."""
    from scipy.spatial import cKDTree  # scipy: loaded only where this is used, so that `import delvjax` stays light

    # the k-d tree counts strictly nearer points: the bound is nudged up so "within" includes it
    dist, idx = cKDTree(positions).query(targets, distance_upper_bound=np.nextafter(TOLERANCE * spacing, np.inf))
    return np.where(np.isfinite(dist), idx, -1)


def _plan(
    positions: np.ndarray, headings: np.ndarray, start: np.ndarray, end: np.ndarray, ok: np.ndarray, n_pix: int
) -> MovePlan:
    """The `MovePlan` of moves start -> end: the rolls turn column 0 of both views to the move."""
    delta = positions[end] - positions[start]
    move_dir = np.arctan2(delta[:, 1], delta[:, 0])
    pixel, heading = 2 * np.pi / n_pix, np.asarray(headings, np.float64)

    def roll(i: np.ndarray) -> np.ndarray:
        return np.round((move_dir - heading[i]) / pixel).astype(np.int64) % n_pix

    return MovePlan(
        start=start.astype(np.int32),
        end=end.astype(np.int32),
        shift=roll(start).astype(np.int32),
        shift_end=roll(end).astype(np.int32),
        d_hat=np.linalg.norm(delta, axis=-1).astype(np.float32),
        ok=ok,
    )


def first_neighbours(
    positions: np.ndarray, points: np.ndarray, offsets: np.ndarray, spacing: float
) -> tuple[np.ndarray, np.ndarray]:
    """For each point index: the first of `points + spacing * offset` (in `offsets` order) in the
    database (the point itself where none is) and whether one was."""
    cands = np.stack([neighbour(positions, positions[points] + spacing * o, spacing) for o in offsets], -1)
    has = cands >= 0
    first = cands[np.arange(len(points)), np.argmax(has, -1)]
    return np.where(has.any(-1), first, points), has.any(-1)


def move_plan(positions: np.ndarray, headings: np.ndarray, spacing: float, n_pix: int) -> MovePlan:
    """The unit move ending at every database point (module docstring)."""
    positions = np.asarray(positions, np.float64)
    ends = np.arange(len(positions))
    start, ok = first_neighbours(positions, ends, -MOVES, spacing)
    return _plan(positions, headings, start, ends, ok, n_pix)


def home_plan(positions: np.ndarray, headings: np.ndarray, home_index: int, spacing: float, n_pix: int) -> MovePlan:
    """The home record's unit move (docs/model.md §3.3): from home to its first axis neighbour
    (east, north, west, south) in the database; its start view's heading is alpha_r."""
    positions = np.asarray(positions, np.float64)
    home = np.array([home_index])
    end, ok = first_neighbours(positions, home, MOVES, spacing)
    return _plan(positions, headings, home, end, ok, n_pix)


def route_checks(positions: np.ndarray, names: list[str], where: str) -> None:
    """A route (docs/images.md §6.1) needs two images or more and a move between every two consecutive
    ones: `InputError` naming the rows otherwise."""
    if len(positions) < 2:
        raise InputError("images", where, "is a route of one image: it has no unit move (two images or more)")
    step = np.linalg.norm(np.diff(np.asarray(positions, np.float64), axis=0), axis=-1)
    if (step == 0).any():
        i = int(np.argmax(step == 0))
        raise InputError(
            "images", where, f"route images {names[i]} and {names[i + 1]} share one position: no unit move between them"
        )


def route_plan(positions: np.ndarray, headings: np.ndarray, n_pix: int) -> MovePlan:
    """The unit move ending at every route image (docs/images.md §6.1): from the image before it along
    the route; the first image's move comes from the second (the route walked back one step)."""
    n = len(positions)
    ends = np.arange(n)
    start = np.where(ends > 0, ends - 1, 1)
    return _plan(np.asarray(positions, np.float64), headings, start, ends, np.ones(n, bool), n_pix)


def route_home_plan(positions: np.ndarray, headings: np.ndarray, home_index: int, n_pix: int) -> MovePlan:
    """The home record's unit move on a route: from home to the next image along it, or to the one
    before it where home is the last."""
    home = np.array([home_index])
    end = np.array([home_index + 1 if home_index + 1 < len(positions) else home_index - 1])
    return _plan(np.asarray(positions, np.float64), headings, home, end, np.ones(1, bool), n_pix)


def rolled(snap: Snapshot, shift: Array) -> Snapshot:
    """The snapshot seen with column `shift` as column 0 (rings rolled, bearings turned, re-sorted)."""
    n = snap.mask.shape[-1]
    turn = shift.astype(jnp.float32) * jnp.float32(2 * np.pi / n)
    bearing, valid, width = sort_blobs(snap.bearing - turn, snap.valid, snap.width)
    return Snapshot(
        mask=jnp.roll(snap.mask, -shift),
        gray=jnp.roll(snap.gray, -shift),
        bearing=bearing,
        width=width,
        valid=valid,
        channel=snap.channel,
        panorama=None if snap.panorama is None else jnp.roll(snap.panorama, -shift, axis=-1),
        elevations=snap.elevations,
    )


def view_of(
    db: RingDatabase, start: Array, end: Array, shift: Array, shift_end: Array, d_hat: Array, alpha_r: Array
) -> tuple[UnitMove, Array]:
    """The unit move from database point `start` to `end`, its views rolled by `shift` and `shift_end`
    into the move's frame (module docstring), and the world heading of its end view's column 0."""
    pixel = jnp.float32(2 * np.pi / db.snapshots.mask.shape[-1])
    pick = lambda i, k: rolled(jax.tree.map(lambda a: a[i], db.snapshots), k)  # noqa: E731
    heading_start = db.headings[start] + shift.astype(jnp.float32) * pixel
    heading_end = db.headings[end] + shift_end.astype(jnp.float32) * pixel
    view = UnitMove(
        start=pick(start, shift),
        end=pick(end, shift_end),
        d_hat=d_hat,
        psi_hat=wrap(heading_end - heading_start),
        compass=wrap(heading_end - alpha_r),
    )
    return view, heading_end


def home_view(db: RingDatabase, plan: MovePlan) -> tuple[UnitMove, Array]:
    """(home record, alpha_r): the home move of `home_plan`; alpha_r is its start view's heading."""
    n = db.snapshots.mask.shape[-1]
    alpha_r = db.headings[plan.start[0]] + plan.shift[0] * jnp.float32(2 * np.pi / n)
    view, _ = view_of(db, plan.start[0], plan.end[0], plan.shift[0], plan.shift_end[0], plan.d_hat[0], alpha_r)
    return view, alpha_r


def database_directions(
    db: RingDatabase, plan: MovePlan, home_db: RingDatabase, home: MovePlan, method: HomingMethod, home_point: Array
) -> tuple[Array, Array, Array]:
    """World homing direction (rad, NaN where invalid), validity and angular error (deg, 180 where
    invalid) at every point of `plan` (docs/images.md §6). The home record is the move `home` in
    `home_db` (the same database, or another rendering of it). The points are split over the local
    devices (`batching.over_devices`); each device runs the same per-point program, so the numbers
    do not depend on how many there are."""
    mesh = local_mesh()
    if mesh is None:
        return _directions(db, home_db, home, method, home_point, plan)
    n = int(np.shape(plan.start)[0])
    m = -(-n // mesh.size) * mesh.size
    padded_plan = jax.tree.map(
        lambda a: jnp.concatenate([jnp.asarray(a), jnp.repeat(jnp.asarray(a)[:1], m - n, 0)]), plan
    )
    out = over_devices(_directions, mesh, 5, db, home_db, home, method, home_point, padded_plan)
    return jax.tree.map(lambda a: a[:n], out)


@jax.jit
def _directions(
    db: RingDatabase, home_db: RingDatabase, home: MovePlan, method: HomingMethod, home_point: Array, plan: MovePlan
) -> tuple[Array, Array, Array]:
    """`database_directions` on one device, `batching.item_width` points at a time."""
    record, alpha_r = home_view(home_db, home)

    def one(start, end, shift, shift_end, d_hat, ok):
        view, heading_end = view_of(db, start, end, shift, shift_end, d_hat, alpha_r)
        direction, valid = world_direction(method, record, view, heading_end)
        valid = valid & ok
        return jnp.where(valid, direction, jnp.nan), valid

    xs = (plan.start, plan.end, plan.shift, plan.shift_end, plan.d_hat, plan.ok)
    direction, valid = fixed_width_map(one, xs, width=item_width(method.reads_panorama()))
    return direction, valid, angular_error_deg(direction, valid, db.positions[plan.end], home_point)


@jax.jit
def perceived_landmarks(home_db: RingDatabase, home: MovePlan, settings) -> tuple[Array, Array]:
    """World positions of the landmarks in DELV's reference map (docs/model.md §3.3; thesis Fig 4.20):
    home + Rot(alpha_r) V^R_i with `settings` (a `DELV`: levels, scale, r_max): ((B, 2), (B,))."""

    record, alpha_r = home_view(home_db, home)
    vectors, valid = reference_vectors(record, settings)
    return home_db.positions[home.start[0]] + rotate(vectors, alpha_r), valid
