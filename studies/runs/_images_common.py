"""What the image studies share (docs/images.md §8): rendered databases in memory, the methods
compiled into one program, the numbers of a map, and the ideal rings of the ring model."""

from __future__ import annotations

import numpy as np

import delvjax
from delvjax import Grid
from delvjax.core.maps import VectorMap
from delvjax.core.metrics import error_curve, summarize_map
from delvjax.core.scene import Env
from delvjax.envs import make_env
from delvjax.images import ImageSettings, LoadedDatabase, database_vector_map, image_world, render_in_memory
from delvjax.images._worlds import ImageWorld

# the methods of the image studies, one compiled program (`options.method_set`)
METHODS = ("delv", "alv", "acv", "warping")
LABEL = {"delv": "DELV", "alv": "ALV", "acv": "ACV", "warping": "image matching", "minwarping": "MinWarping"}
# MinWarping (docs/model.md §4.7) reads whole panoramas: its own program, its grid on 360 columns
MINWARPING = {"n_alpha": 90, "n_psi": 90}
# Image matching reads the gray ring (the band's mean value): on a camera image that is what it has.
# On the mask ring it sees four narrow blobs and errs by about 60° (images and ideal rings alike).
# The landmark methods read blobs, so the channel does not change them.
CHANNEL = "gray"
ROBOT_SCALE = 180.0  # cm: DELV's quantization scale a in the 1.8 m arena (1000 cm in the 10 m one)
CAMERA_NOISE = ImageSettings(pixel_noise=0.02, gain_noise=0.03)  # "realistic camera noise" of the studies


def preview(ctx) -> bool:
    """A preview run (`--quick`, or the tests' coarse settings): fewer settings, the same programs."""
    return ctx.config.quick or ctx.config.spacing >= 100


def database(name: str, settings: ImageSettings = CAMERA_NOISE, seed: int = 0, **kw) -> LoadedDatabase:
    """A built-in world rendered in memory (ring for ring what its files would give)."""
    return render_in_memory(name, settings=settings, seed=seed, **kw)


def image_map(db: LoadedDatabase, method: str, **options) -> VectorMap:
    """The vector map of `method` on `db`, through the shared program of METHODS (gray channel unless
    `channel` is given); MinWarping on its own, on the panoramas (`database(..., panoramas=True)`)."""
    if method == "minwarping":
        return database_vector_map(db, method, **{**MINWARPING, **options})
    return database_vector_map(db, method, method_set=METHODS, **{"channel": CHANNEL, **options})


def numbers(vm: VectorMap) -> dict:
    """Mean error, invalid count and error point rates of a map."""
    return summarize_map(vm.error_deg, vm.valid, vm.included)


def curve(vm: VectorMap, home, bin_width: float) -> list[dict]:
    """The error curve (Fig 4.19 style: mean and 95 % t interval per distance bin)."""
    return error_curve(vm.error_deg, vm.points, home, vm.included, bin_width=bin_width)


def ring_env(iw: ImageWorld) -> Env:
    """The ring model's scene of an image world: its cylinders, home and arena."""
    obs = iw.obstacles()
    return make_env(
        [tuple(c) for c in obs["cylinders"]],
        home=iw.home,
        arena=tuple(float(v) for v in np.asarray(iw.world.arena)),
        name=iw.name,
    )


IDEAL_HEADING_DEG = 0.0  # every grid point faces east
IDEAL_GRID = {"method_set": METHODS, "channel": CHANNEL, "background": "walls"}


def ideal_map(world: str | ImageWorld, method: str, **options) -> VectorMap:
    """The ring model's vector map (docs/model.md: ideal rings, exact blobs) on the world's cylinders,
    on the database's grid (spacing = unit move, heading along +x as the database's west neighbour move),
    gray channel over the docs/model.md §2.3 `walls` background (the images' wall texture)."""
    iw = image_world(world) if isinstance(world, str) else world
    return delvjax.vector_map(
        ring_env(iw),
        method,
        d=iw.spacing,
        grid=Grid(spacing=iw.spacing, clearance=iw.clearance, heading_deg=IDEAL_HEADING_DEG),
        **{**IDEAL_GRID, **options},
    )
