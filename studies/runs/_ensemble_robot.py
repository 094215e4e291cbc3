"""The array programs of the `ensemble_robot` study: the robot world family's members (docs/model.md §6.1) as
image worlds, their snapshot databases rendered, and every method's image map, nearest-snapshot catchment and
ideal ring-model map, each one program over every member (docs/reproduce.md "Ensembles: the robot images").

A member is the built-in robot world (`delvjax.images._worlds.robot_arena`) with the member's cylinders. Every
member's database is padded to the whole 20 cm grid of the arena: a grid point within r + clearance of a
cylinder is rendered but kept out (`kept`), never a nearest snapshot, never a move's start; the camera noise of
a member's image i is that of image i of its own database (`render_in_memory`). Only the rows of the extractor's
band are rendered (the rings read no other row): the same rays and the same noise as the whole panorama's band
rows, so a member's rings are those `render_in_memory` gives (the masks equal, a few gray values one grey level of one
band pixel apart: another XLA fusion; tested).
"""

from __future__ import annotations

from dataclasses import dataclass

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from delvjax.core.geometry import rotate
from delvjax.core.images.database import MOVES, MovePlan, RingDatabase, _directions
from delvjax.core.images.pipeline import pixel_normals, rgb_to_hsv, ring_snapshot, segment, to_uint8
from delvjax.core.images.render import radiance
from delvjax.core.images.rollouts import Field, one_trial
from delvjax.core.maps import VectorMap, _vector_map, grid_points
from delvjax.core.rollouts import MAX_STEPS
from delvjax.core.scene import Env
from delvjax.envs import ensemble_envs
from delvjax.evaluate._vector_map import map_request
from delvjax.images import ImageSettings
from delvjax.images._load import with_channel
from delvjax.images._worlds import ImageWorld, robot_arena
from delvjax.options import make_setup

from ._images_common import CAMERA_NOISE, CHANNEL, IDEAL_GRID, IDEAL_HEADING_DEG, METHODS, ring_env

FAR = 1e6  # cm: where a padded (kept-out) database point is put for the nearest-snapshot search
MEMBER_BATCH = 4  # members rendered side by side (`lax.map` over groups of members): bounds the memory


def robot_layouts(members: int, seed: int) -> np.ndarray:
    """(members, 4, 3) the robot family's members [x, y, r] (cm), member i from fold_in(PRNGKey(seed), i)."""
    envs = ensemble_envs("robot", members, seed)
    return np.array([[[lm["x"], lm["y"], lm["r"]] for lm in e["landmarks"]] for e in envs])


@dataclass
class Members:
    """The padded databases of W worlds on one grid: points (P, 2); kept (W, P); home_index (W,); rings (a
    `RingDatabase` with leading axes (W, P)); plan (W, P) and home (W, 1) `MovePlan`s; cylinders (W, C, 3)."""

    names: list[str]
    worlds: list[ImageWorld]
    points: np.ndarray
    kept: np.ndarray
    home_index: np.ndarray
    rings: RingDatabase
    plan: MovePlan
    home: MovePlan
    cylinders: np.ndarray
    spacing: float
    arena: np.ndarray

    @property
    def home_points(self) -> np.ndarray:
        """(W, 2) each database's home point (its grid point nearest the world's home)."""
        return self.points[self.home_index]

    def included(self) -> np.ndarray:
        """(W, P) the points of each database but its home (the points a map's numbers count)."""
        return self.kept & (np.arange(len(self.points))[None] != self.home_index[:, None])


def member_worlds(layouts: np.ndarray, names: list[str]) -> list[ImageWorld]:
    """The robot world with each layout's cylinders (input preparation, one `ImageWorld` per member)."""
    return [robot_arena(lay, name) for lay, name in zip(layouts, names)]


def band_rows(settings: ImageSettings, iw: ImageWorld) -> tuple[int, int]:
    """(first, last + 1) of the panorama rows the extractor's band averages (`Extractor.band_weights`)."""
    w = np.asarray(iw.extractor.band_weights(settings.camera)) > 0
    rows = np.flatnonzero(w)
    if not len(rows) or rows[-1] - rows[0] + 1 != len(rows):
        raise ValueError("the extractor's band is not one run of rows")
    return int(rows[0]), int(rows[-1]) + 1


def _plan(points: np.ndarray, start: np.ndarray, end: np.ndarray, ok: np.ndarray, cols: int) -> MovePlan:
    """`core.images.database._plan` with headings 0, over (W, K) index arrays into the whole grid."""
    delta = points[end].astype(np.float64) - points[start]
    roll = np.round(np.arctan2(delta[..., 1], delta[..., 0]) / (2 * np.pi / cols)).astype(np.int64) % cols
    return MovePlan(
        start=start.astype(np.int32),
        end=end.astype(np.int32),
        shift=roll.astype(np.int32),
        shift_end=roll.astype(np.int32),
        d_hat=np.linalg.norm(delta, axis=-1).astype(np.float32),
        ok=ok,
    )


def lattice_plans(points, arena, spacing: float, kept: np.ndarray, home_index: np.ndarray, cols: int):
    """(plan (W, P), home plan (W, 1)) of every database (`core.images.database.move_plan`, `home_plan`): the
    move ending at a point starts at its first kept west, south, east, north neighbour; the home record's move
    ends at home's first kept east, north, west, south neighbour."""
    cell = np.round((points - np.asarray(arena)[:2] - spacing / 2) / spacing).astype(int)  # (P, 2)
    table = -np.ones(cell.max(0) + 1, int)
    table[cell[:, 0], cell[:, 1]] = np.arange(len(points))

    def neighbours(offsets: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        target = cell[at][..., None, :] + offsets.astype(int)  # (W, K, 4, 2)
        inside = np.all((target >= 0) & (target < np.array(table.shape)), -1)
        idx = np.where(
            inside,
            table[np.clip(target[..., 0], 0, table.shape[0] - 1), np.clip(target[..., 1], 0, table.shape[1] - 1)],
            -1,
        )
        has = (idx >= 0) & np.take_along_axis(
            kept[:, :, None], np.maximum(idx, 0).reshape(len(kept), -1, 1), 1
        ).reshape(idx.shape)
        first = np.take_along_axis(idx, np.argmax(has, -1)[..., None], -1)[..., 0]
        return np.where(has.any(-1), first, at), has.any(-1)

    every = np.broadcast_to(np.arange(len(points)), kept.shape)
    start, ok = neighbours(-MOVES, every)
    end, home_ok = neighbours(MOVES, home_index[:, None])
    return _plan(points, start, every, ok, cols), _plan(points, home_index[:, None], end, home_ok, cols)


def _member_snapshots(world, positions, index, key, rows: tuple[int, int], cam, noise, extractor):
    """The rings of one world's images at `positions` (P, 2), image i with the noise of database image
    index[i]: the band rows of `delvjax.images._render.render_images` + `extract_rings`, no other row."""
    lo, hi = rows
    a = cam.azimuths()
    u = rotate(jnp.stack([jnp.cos(a), jnp.sin(a)], -1), jnp.float32(0.0))[None]
    tan_e = jnp.tan(cam.elevations())[lo:hi, None]
    w = jnp.ones((hi - lo, 1), jnp.float32)

    def one(pos, i):
        img = radiance(world, pos, jnp.asarray(cam.height, jnp.float32), u, tan_e)
        k_gain, k_pix = jax.random.split(jax.random.fold_in(key, i))
        gain = 1.0 + noise[1] * jax.random.normal(k_gain)
        pixel = pixel_normals(k_pix, (cam.rows, cam.cols, 3))[lo:hi]
        img = to_uint8(jnp.clip(img * gain + noise[0] * pixel, 0.0, 1.0)).astype(jnp.float32) / 255.0
        hsv = rgb_to_hsv(img)
        mask = segment(hsv, extractor.hue_deg, extractor.hue_width_deg, extractor.sat_min, extractor.val_min)
        total = jnp.sum(w)
        return ring_snapshot(jnp.sum(w * mask, 0) / total, jnp.sum(w * hsv[..., 2], 0) / total, extractor)

    return jax.vmap(one)(positions, index)


@eqx.filter_jit
def _render_members(worlds, positions, index, keys, rows, cam, noise, extractor):
    """Rings (W, P) of every world (stacked `World`s, world w under keys[w]), MEMBER_BATCH worlds side by side."""
    run = lambda wik: _member_snapshots(wik[0], positions, wik[1], wik[2], rows, cam, noise, extractor)  # noqa: E731
    return jax.lax.map(run, (worlds, index, keys), batch_size=MEMBER_BATCH)


def render_members(worlds: list[ImageWorld], seeds, settings: ImageSettings = CAMERA_NOISE) -> Members:
    """Every world's database (the robot arena's grid, `Members`), world w rendered under seeds[w]
    (`render_in_memory`'s seed), as one program over the worlds."""
    iw = worlds[0]
    points = grid_points(np.asarray(iw.world.arena), iw.spacing)
    cyl = np.stack([np.asarray(w.world.cylinders)[:, :3] for w in worlds])  # (W, C, 3)
    gap = np.hypot(points[None, :, None, 0] - cyl[:, None, :, 0], points[None, :, None, 1] - cyl[:, None, :, 1])
    kept = np.all(gap > cyl[:, None, :, 2] + iw.clearance, -1)
    dist = np.where(kept, np.linalg.norm(points - np.asarray(iw.home), axis=-1)[None], np.inf)
    home_index = np.argmin(dist, -1)
    index = np.maximum(np.cumsum(kept, -1) - 1, 0).astype(np.int32)  # image i of the database: its noise
    stacked = jax.tree.map(lambda *a: jnp.stack(a), *[w.world for w in worlds])
    noise = jnp.asarray([settings.pixel_noise, settings.gain_noise], jnp.float32)
    snaps = _render_members(
        stacked,
        jnp.asarray(points),
        jnp.asarray(index),
        jax.vmap(jax.random.PRNGKey)(jnp.asarray(seeds, jnp.uint32)),
        band_rows(settings, iw),
        settings.camera,
        noise,
        iw.extractor,
    )
    cols = settings.camera.cols
    plan, home = lattice_plans(points, np.asarray(iw.world.arena), iw.spacing, kept, home_index, cols)
    positions = jnp.broadcast_to(jnp.asarray(points), kept.shape + (2,))
    rings = RingDatabase(snaps, positions, jnp.zeros(kept.shape, jnp.float32))
    return Members(
        [w.name for w in worlds],
        worlds,
        points,
        kept,
        home_index,
        rings,
        plan,
        home,
        cyl,
        iw.spacing,
        np.asarray(iw.world.arena, np.float64),
    )


@jax.jit
def _member_directions(rings, home, method, home_point, plan):
    """(direction, valid, error) (W, P) of `method` on every database (`core.images.database._directions`)."""
    return jax.vmap(lambda r, h, hp, p: _directions(r, r, h, method, hp, p))(rings, home, home_point, plan)


def image_maps(m: Members, method: str, **options) -> VectorMap:
    """The vector map (leading axis W) of `method` on every member's images (`_images_common.image_map`)."""
    module, sensor = make_setup(
        method, METHODS, n_pix=m.rings.snapshots.mask.shape[-1], **{"channel": CHANNEL, **options}
    )
    rings = with_channel(m.rings, sensor.channel)
    plan = jax.tree.map(jnp.asarray, m.plan)
    home = jax.tree.map(jnp.asarray, m.home)
    direction, valid, error = _member_directions(rings, home, module, jnp.asarray(m.home_points, jnp.float32), plan)
    valid = valid & jnp.asarray(m.kept)
    return VectorMap(
        points=jnp.broadcast_to(jnp.asarray(m.points), m.kept.shape + (2,)),
        included=jnp.asarray(m.included()),
        heading=jnp.zeros(m.kept.shape, jnp.float32),
        direction=direction,
        valid=valid,
        error_deg=jnp.where(valid, error, 180.0),
    )


@eqx.filter_jit
def _member_rollouts(fields, starts, key, step, home_radius, max_steps: int):
    """(outcome, steps) (W, T) of nearest-snapshot rollouts from every start of every member
    (`core.images.rollouts.nearest_snapshot_rollouts`; trial i draws from fold_in(key, i) in every member)."""
    keys = jax.vmap(lambda i: jax.random.fold_in(key, i))(jnp.arange(starts.shape[1]))
    noise = jnp.zeros(2, jnp.float32)

    def member(f, s):
        out = jax.vmap(lambda x, k: one_trial(f, x, k, step, home_radius, noise, max_steps))(s, keys)
        return out[0], out[1]

    return jax.vmap(member)(fields, starts)


def catchments(m: Members, vm: VectorMap, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(catchment % (W,), releases (W,)) of every member (`images.database_catchment`): a nearest-snapshot
    rollout from every database point farther than the spacing from home, step and home radius the spacing."""
    home = m.home_points
    far = np.linalg.norm(m.points[None] - home[:, None], axis=-1) > m.spacing
    release = m.kept & far  # (W, P): the releases; the others start at home (a success, not counted)
    starts = np.where(release[..., None], m.points[None], home[:, None]).astype(np.float32)
    # the database's own order: release j of a member is its j-th release point, trial j draws from fold_in(key, j)
    order = np.argsort(~release, axis=1, kind="stable")
    starts = np.take_along_axis(starts, order[..., None], 1)
    counted = np.take_along_axis(release, order, 1)
    w = len(m.names)
    fields = Field(
        jnp.asarray(np.where(m.kept[..., None], m.points[None], FAR), jnp.float32),
        vm.direction,
        vm.valid,
        jnp.asarray(home, jnp.float32),
        jnp.broadcast_to(jnp.asarray(m.arena, jnp.float32), (w, 4)),
        jnp.asarray(m.cylinders, jnp.float32),
        jnp.zeros((w, 0, 4), jnp.float32),
    )
    key = jax.random.fold_in(jax.random.PRNGKey(seed), 3)
    step = jnp.float32(m.spacing)
    outcome, _ = _member_rollouts(fields, jnp.asarray(starts), key, step, step, MAX_STEPS)
    ok = (np.asarray(outcome) == 0) & counted
    releases = counted.sum(1)
    return 100.0 * ok.sum(1) / np.maximum(releases, 1), releases


def _ideal_program(env: Env, method: str, iw: ImageWorld, **options):
    """(method module, sensor, heading, key, clearance) of `_images_common.ideal_map` (`map_request`)."""
    req = map_request(
        env, method, iw.spacing, IDEAL_HEADING_DEG, d=iw.spacing, clearance=iw.clearance, **{**IDEAL_GRID, **options}
    )
    return req["method"], req["sensor"], req["heading"], req["key"], req["clearance"]


def ideal_maps(m: Members, method: str, **options) -> VectorMap:
    """The ring model's vector map (leading axis W) of every member (`_images_common.ideal_map`), one program."""
    envs = [ring_env(w) for w in m.worlds]
    module, sensor, heading, key, clearance = _ideal_program(envs[0], method, m.worlds[0], **options)
    stacked = jax.tree.map(lambda *a: jnp.stack(a), *[Env(e.landmarks, e.valid, e.home, e.arena) for e in envs])
    rows = jnp.asarray(m.points)
    run = lambda env: _vector_map(env, rows, heading, key, sensor, module, clearance, None, 0)  # noqa: E731
    return jax.vmap(run)(stacked)


def map_numbers(vm: VectorMap) -> dict[str, np.ndarray]:
    """(W,) arrays of each member's mean error, e>45 and e>90 rates (%), points and invalid count
    (`core.metrics.summarize_map` per member, invalid points at 180°)."""
    inc = np.asarray(vm.included)
    e = np.where(inc, np.asarray(vm.error_deg), 0.0)
    n = inc.sum(-1)
    return {
        "mean_error_deg": e.sum(-1) / np.maximum(n, 1),
        "gt45_pct": 100.0 * ((e > 45.0) & inc).sum(-1) / np.maximum(n, 1),
        "gt90_pct": 100.0 * ((e > 90.0) & inc).sum(-1) / np.maximum(n, 1),
        "points": n,
        "invalid": (~np.asarray(vm.valid) & inc).sum(-1),
    }
