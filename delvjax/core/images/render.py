"""Ray casting of a `World` (docs/images.md §3): the colour seen along any ray, then an
equirectangular panorama or a catadioptric donut at any pose.

Every object is a vertical prism standing on the floor, so a ray is cast in two steps: its
horizontal direction u meets each cylinder and box side at a horizontal distance t (one 2D
intersection per object and column), and its elevation decides at which height z = camera
height + t tan(elevation) it gets there; the nearest object whose side spans z is seen, else the
floor (below the horizon, before the wall), else the wall (below its top), else the ceiling.
Surfaces are Lambertian with an ambient share; there are no shadows.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
from jax import Array

from ..geometry import rotate
from ..sensing import background_of_angle, wall_coordinate
from .world import Camera, Catadioptric, World

FAR = 1e9  # cm, "no hit"


def cylinder_hits(cylinders: Array, origin: Array, u: Array) -> tuple[Array, Array]:
    """Horizontal distance to each cylinder side along u (..., 2): (t (..., C), unit normal (..., C, 2)).
    FAR where missed; 0 from inside a cylinder."""
    rel = cylinders[:, :2] - origin  # (C, 2)
    b = jnp.einsum("...k,ck->...c", u, rel)
    c2 = jnp.sum(rel * rel, -1) - cylinders[:, 2] ** 2
    disc = b * b - c2
    t = b - jnp.sqrt(jnp.maximum(disc, 0.0))
    hit = (c2 <= 0) | ((disc >= 0) & (t > 0))
    t = jnp.where(c2 <= 0, 0.0, jnp.where(hit, t, FAR))
    point = origin + t[..., None] * u[..., None, :]
    normal = (point - cylinders[:, :2]) / jnp.maximum(cylinders[:, 2:3], 1e-6)
    return t, normal


def box_hits(boxes: Array, origin: Array, u: Array) -> tuple[Array, Array]:
    """Horizontal distance to each box side along u (slab test): (t (..., K), unit normal (..., K, 2))."""
    safe = jnp.where(jnp.abs(u) < 1e-9, 1e-9, u)[..., None, :]  # (..., 1, 2)
    lo = (boxes[:, 0:2] - origin) / safe  # (..., K, 2)
    hi = (boxes[:, 2:4] - origin) / safe
    near, far = jnp.minimum(lo, hi), jnp.maximum(lo, hi)
    t_near, t_far = jnp.max(near, -1), jnp.min(far, -1)
    hit = (t_near <= t_far) & (t_far > 0)
    t = jnp.where(hit, jnp.maximum(t_near, 0.0), FAR)
    x_side = near[..., 0] >= near[..., 1]
    sign = -jnp.sign(safe)  # (..., 1, 2): faces look back along the ray
    normal = jnp.stack([jnp.where(x_side, sign[..., 0], 0.0), jnp.where(x_side, 0.0, sign[..., 1])], -1)
    return t, normal


def wall_hit(arena: Array, origin: Array, u: Array) -> tuple[Array, Array]:
    """Horizontal distance to the arena wall along u and the wall's inward unit normal."""
    safe = jnp.where(jnp.abs(u) < 1e-9, 1e-9, u)
    bound = jnp.where(safe > 0, arena[2:4], arena[0:2])
    t_axis = jnp.maximum((bound - origin) / safe, 0.0)  # (..., 2)
    x_side = t_axis[..., 0] <= t_axis[..., 1]
    t = jnp.minimum(t_axis[..., 0], t_axis[..., 1])
    normal = jnp.stack(
        [jnp.where(x_side, -jnp.sign(safe[..., 0]), 0.0), jnp.where(x_side, 0.0, -jnp.sign(safe[..., 1]))], -1
    )
    return t, normal


def lambert(world: World, normal: Array) -> Array:
    """Brightness of a vertical surface with horizontal unit `normal` (..., 2) (docs/images.md §3)."""
    lit = jnp.maximum(jnp.sum(normal * world.light[:2], -1), 0.0)
    return world.ambient + (1.0 - world.ambient) * lit


def radiance(world: World, origin: Array, height: Array, u: Array, tan_e: Array) -> Array:
    """RGB seen from (origin, height) along horizontal direction u (..., 2) at elevation tan `tan_e`
    (broadcast against u's leading axes): (..., 3) in [0, 1]."""
    t_c, n_c = cylinder_hits(world.cylinders, origin, u)
    t_b, n_b = box_hits(world.boxes, origin, u)
    t_obj = jnp.concatenate([t_c, t_b], -1)  # (..., M)
    heights = jnp.concatenate([world.cylinders[:, 3], world.boxes[:, 4]])
    rgb = (
        jnp.concatenate([world.cylinder_rgb, world.box_rgb])
        * jnp.concatenate([lambert(world, n_c), lambert(world, n_b)], -1)[..., None]
    )  # (..., M, 3)
    tan_o = tan_e[..., None]
    z = height + t_obj * tan_o
    seen = (t_obj < FAR) & (z >= 0.0) & (z <= heights)
    t_seen = jnp.where(seen, t_obj, FAR)
    k = jnp.argmin(t_seen, -1)
    t_near = jnp.min(t_seen, -1)
    shape = t_near.shape
    obj_rgb = jnp.take_along_axis(jnp.broadcast_to(rgb, shape + rgb.shape[-2:]), k[..., None, None], -2)[..., 0, :]

    t_w, n_w = wall_hit(world.arena, origin, u)
    t_w = jnp.broadcast_to(t_w, shape)
    z_wall = height + t_w * tan_e
    t_floor = jnp.where(tan_e < 0, height / jnp.maximum(-tan_e, 1e-9), FAR)
    grey = 0.5 + world.texture * (background_of_angle(2.0 * jnp.pi * wall_coordinate(origin, u, world.arena)) - 0.5)
    wall_rgb = (grey * lambert(world, n_w))[..., None] * jnp.ones(3)
    floor_rgb = world.floor_rgb * (world.ambient + (1.0 - world.ambient) * jnp.maximum(world.light[2], 0.0))
    back = jnp.where(
        (t_floor < t_w)[..., None],
        floor_rgb,
        jnp.where(
            (z_wall <= world.wall_height)[..., None], jnp.broadcast_to(wall_rgb, shape + (3,)), world.ceiling_rgb
        ),
    )
    return jnp.where((t_near < jnp.minimum(t_w, t_floor))[..., None], obj_rgb, back)


def panorama(world: World, camera: Camera, pos: Array, heading: Array) -> Array:
    """Equirectangular colour panorama at `pos` (2,) facing `heading` (rad): (rows, cols, 3)."""
    a = camera.azimuths()
    u = rotate(jnp.stack([jnp.cos(a), jnp.sin(a)], -1), heading)[None]  # (1, cols, 2)
    tan_e = jnp.tan(camera.elevations())[:, None]  # (rows, 1)
    return radiance(world, pos, jnp.asarray(camera.height, jnp.float32), u, tan_e)


def panoramas(world: World, camera: Camera, pos: Array, heading: Array) -> Array:
    """`panorama` vmapped over poses: pos (P, 2), heading (P,) -> (P, rows, cols, 3)."""
    return jax.vmap(panorama, in_axes=(None, None, 0, 0))(world, camera, pos, heading)


def donut(world: World, mirror: Catadioptric, pos: Array, heading: Array) -> Array:
    """Catadioptric (donut) colour image at a pose: (size, size, 3), black outside the annulus."""
    azimuth, elevation, inside = mirror.pixel_rays()
    a = heading + azimuth
    u = jnp.stack([jnp.cos(a), jnp.sin(a)], -1)
    rgb = radiance(world, pos, jnp.asarray(mirror.height, jnp.float32), u, jnp.tan(elevation))
    return jnp.where(inside[..., None], rgb, 0.0)
