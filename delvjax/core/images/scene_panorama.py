"""Panoramas of a ring scene: its cylinders rendered as a colour world, for the methods that read
whole panoramas (MinWarping, 2D-Warping, the hybrid; docs/images.md §10).

A ring scene (`Env`) has no third dimension. `ScenePanorama` gives it one as `images._worlds.env_world` does
for a rendered database: every landmark a cylinder of `landmark_height` and `landmark_rgb`, the
arena's textured walls, floor and ceiling of `world`; a hidden landmark (occlusion) or a padding slot
has height 0 and is never hit. It renders at the agent's pose inside the traced program
(`sensing.snapshot`), so a vector map, a rollout (a panorama at every step) and a sweep run the
panorama methods as one array program, like every other method.
"""

from __future__ import annotations

import dataclasses

import equinox as eqx
import jax.numpy as jnp
from jax import Array

from ..scene import Env
from ..types import Real
from .pipeline import gray_bytes, to_uint8
from .render import panorama
from .world import RED, Camera, World, make_world

SCENE_ROWS = 48  # rows of a ring scene's panoramas (+-30 deg, 1.25 deg a row; docs/images.md §10)


class ScenePanorama(eqx.Module):
    """camera: the panoramic camera (its `cols` equal the sensor's n_pix); world: walls, floor,
    ceiling and light (its own objects are replaced by the scene's landmarks); landmark_rgb: (3,)
    colour of every landmark; landmark_height: cm."""

    camera: Camera
    world: World
    landmark_rgb: Array
    landmark_height: Real

    def world_of(self, env: Env, visible: Array) -> World:
        """The colour world of `env` with the landmarks where `visible & env.valid` (others height 0)."""
        shown = visible & env.valid
        height = jnp.where(shown, jnp.asarray(self.landmark_height, jnp.float32), 0.0)[:, None]
        n = env.landmarks.shape[0]
        return dataclasses.replace(
            self.world,
            cylinders=jnp.concatenate([env.landmarks.astype(jnp.float32), height], -1),
            cylinder_rgb=jnp.broadcast_to(jnp.asarray(self.landmark_rgb, jnp.float32), (n, 3)),
            boxes=jnp.zeros((1, 5), jnp.float32),
            box_rgb=jnp.zeros((1, 3), jnp.float32),
            arena=jnp.asarray(env.arena, jnp.float32),
        )

    def __call__(self, env: Env, visible: Array, pos: Array, heading: Array) -> tuple[Array, Array]:
        """(gray panorama (rows, cols) uint8, row elevations (rows,) rad) at `pos` facing `heading`: the
        bytes an image database of the same world holds (`images.render_in_memory`, no camera noise)."""
        image = to_uint8(panorama(self.world_of(env, visible), self.camera, pos, heading))
        return gray_bytes(image.astype(jnp.float32) / 255.0), self.camera.elevations()


def scene_panorama(
    n_pix: int, rows: int = SCENE_ROWS, height: float = 100.0, wall_height: float = 150.0
) -> ScenePanorama:
    """The renderer of a ring scene's panoramas: red cylinders of `height` cm in walls of `wall_height`
    (the worlds of `images._worlds.env_world`), a camera of `rows` x `n_pix` 25 cm above the floor (+-30 deg)."""
    return ScenePanorama(
        camera=Camera(rows=rows, cols=n_pix),
        world=make_world(wall_height=wall_height),
        landmark_rgb=jnp.asarray(RED, jnp.float32),
        landmark_height=jnp.float32(height),
    )
