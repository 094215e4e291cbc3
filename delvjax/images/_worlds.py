"""The built-in colour worlds of the image experiments (docs/images.md §8) and colour worlds of
any docs/model.md environment.

`robot` follows thesis §4.4.1 (Fig 4.15): a 1.8 m x 1.8 m arena, four red cylinders, a camera
25 cm above the floor, snapshots every 20 cm, a 20 cm unit move. `natural` follows §4.4.2
(Figs 4.22-4.24): a room with a table, a lecture desk, a flower pot and a drawer, home at
(500, 500). The thesis gives no coordinates for either: ours are documented in docs/images.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core.errors import InputError
from ..core.images import Extractor
from ..core.images.scene_panorama import scene_panorama
from ..core.images.world import RED, World, make_world
from ..core.scene import Env
from ..envs._presets import PRESETS, load_env


@dataclass(frozen=True)
class ImageWorld:
    """A world with what a database of it needs: home, grid spacing (= the unit move d) and the
    extractor that finds its landmarks."""

    name: str
    world: World
    home: tuple[float, float]
    spacing: float
    extractor: Extractor = field(default_factory=Extractor)
    clearance: float = 10.0

    def obstacles(self) -> dict[str, list]:
        """Cylinders [x, y, r] and boxes [xmin, ymin, xmax, ymax] of nonzero height (for rollouts and plots)."""
        c = np.asarray(self.world.cylinders)
        b = np.asarray(self.world.boxes)
        return {"cylinders": c[c[:, 3] > 0, :3].tolist(), "boxes": b[b[:, 4] > 0, :4].tolist()}

    def clear(self, points: np.ndarray) -> np.ndarray:
        """(N,) True where a point (N, 2) is inside the arena and clear of every obstacle by `clearance`."""
        a = np.asarray(self.world.arena)
        x, y = points[:, 0], points[:, 1]
        keep = (x >= a[0]) & (x <= a[2]) & (y >= a[1]) & (y <= a[3])
        obs, c = self.obstacles(), self.clearance
        for cx, cy, r in obs["cylinders"]:
            keep &= np.hypot(x - cx, y - cy) > r + c
        for x0, y0, x1, y1 in obs["boxes"]:
            keep &= ~((x > x0 - c) & (x < x1 + c) & (y > y0 - c) & (y < y1 + c))
        return keep


ROBOT_LANDMARKS = ((45.0, 135.0, 8.0), (130.0, 150.0, 8.0), (145.0, 55.0, 8.0), (55.0, 42.0, 8.0))  # x, y, r cm
ROBOT_HEIGHT = 50.0  # cm, the robot world's cylinders


def robot_arena(landmarks=ROBOT_LANDMARKS, name: str = "robot") -> ImageWorld:
    """The robot world (thesis §4.4.1) with its cylinders at `landmarks` (rows x, y, r cm): red, ROBOT_HEIGHT cm
    tall, in the 1.8 m arena with 60 cm walls, home at its centre, snapshots every 20 cm (a member of the
    `robot` world family, docs/model.md §6.1, is one of these)."""
    cyl = [(float(x), float(y), float(r), ROBOT_HEIGHT) for x, y, r in np.asarray(landmarks, float).reshape(-1, 3)]
    world = make_world(cylinders=cyl, cylinder_rgb=[RED] * len(cyl), arena=(0.0, 0.0, 180.0, 180.0), wall_height=60.0)
    return ImageWorld(name, world, (90.0, 90.0), 20.0, Extractor(max_blobs=len(cyl)))


def _robot() -> ImageWorld:
    return robot_arena()


def _natural() -> ImageWorld:
    boxes = [
        (620.0, 560.0, 740.0, 640.0, 75.0),  # table
        (560.0, 300.0, 640.0, 360.0, 110.0),  # lecture desk
        (280.0, 330.0, 340.0, 400.0, 100.0),
    ]  # drawer
    box_rgb = [(0.55, 0.33, 0.12), (0.80, 0.62, 0.08), (0.12, 0.28, 0.72)]
    world = make_world(
        cylinders=[(330.0, 640.0, 20.0, 70.0)],
        cylinder_rgb=[(0.12, 0.55, 0.18)],
        boxes=boxes,
        box_rgb=box_rgb,
        arena=(0.0, 0.0, 1000.0, 1000.0),
        wall_height=250.0,
    )
    # any saturated colour is a landmark: walls, floor and ceiling are grey (docs/images.md §8)
    return ImageWorld(
        "natural",
        world,
        (500.0, 500.0),
        40.0,
        Extractor(hue_width_deg=360.0, sat_min=0.45, max_blobs=6),
        clearance=15.0,
    )


BUILT_IN = {"robot": _robot, "natural": _natural}
DESCRIPTIONS = {
    "robot": "thesis §4.4.1: 4 red cylinders in a 1.8 m arena, snapshots every 20 cm",
    "natural": "thesis §4.4.2: table, desk, flower pot and drawer in a 10 m room, every 40 cm",
}


def env_world(
    name_or_path: str | Env, height: float = 100.0, wall_height: float = 150.0, spacing: float = 25.0
) -> ImageWorld:
    """A docs/model.md environment (preset, JSON file or an `Env`) as red cylinders of `height` cm: the world a ring
    scene's panoramas show (`scene_panorama`)."""
    env = load_env(name_or_path)
    world = scene_panorama(1, height=height, wall_height=wall_height).world_of(env, env.valid)
    n = max(env.n_landmarks, 1)
    return ImageWorld(env.name, world, tuple(float(v) for v in np.asarray(env.home)), spacing, Extractor(max_blobs=n))


def image_world(name: str) -> ImageWorld:
    """A built-in image world, or any environment `load_env` reads (preset name or JSON file)."""
    if name in BUILT_IN:
        return BUILT_IN[name]()
    try:
        return env_world(name)
    except InputError:
        raise InputError(
            "env", name, f"is no image world ({', '.join(BUILT_IN)}), preset ({', '.join(PRESETS)}) or environment file"
        ) from None
