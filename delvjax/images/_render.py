"""Image databases from the Python API (docs/images.md): render a world into a database, load any
database into ring snapshots, and evaluate any method on it (vector maps, nearest-snapshot
rollouts). Options are validated before any work (`InputError` naming the field and value);
work runs in chunks of `chunk` images, each image from its own key, so the numbers do not
depend on the chunking and the memory is bounded by the chunk.
"""

from __future__ import annotations

import math
import shutil
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..core.batching import fixed_width_map, pad_rows, traced_floats
from ..core.checks import angle_deg, non_negative, positive, positive_int, seed_value
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.images import Camera, Catadioptric, Extractor, camera_noise, donut, panorama, to_uint8, unwrap
from ..core.images.database import RingDatabase
from ..core.maps import grid_points
from ..core.types import Real
from ..options._limits import MAX_POINTS, check_size, grid_count
from ..outputs._files import check_folder
from ._worlds import ImageWorld, image_world
from ._writer import DatabaseWriter

DEFAULT_CHUNK = 256  # images per host-side chunk
IMAGE_WIDTH = 16  # images rendered or reduced side by side (`fixed_width_map`): bounds a group's memory
RENDER_BUDGET = 2**31  # bytes: a group of images being rendered, and a chunk of rendered images, stay under this
RENDER_BYTES_PER_PIXEL = 24  # XLA's working memory per pixel of an image being rendered (measured: 20.5)


def render_sizes(pixels: int, chunk: int) -> tuple[int, int]:
    """(images rendered side by side, images per chunk) for images of `pixels` pixels: IMAGE_WIDTH and
    `chunk`, fewer where a group's working memory or a chunk's uint8 RGB images would pass
    RENDER_BUDGET (the largest image allowed renders one at a time). The numbers do not depend on
    either: image i's noise comes from its index."""
    width = max(1, min(IMAGE_WIDTH, RENDER_BUDGET // (pixels * RENDER_BYTES_PER_PIXEL)))
    return width, max(1, min(chunk, RENDER_BUDGET // (pixels * 3)))


PIXEL_NOISE = 0.02  # default camera noise of rendered databases, per pixel (docs/images.md §5.1)


@dataclass
class ImageSettings:
    """How images are rendered and read: the camera (rows, cols, elevations, height), a donut
    camera instead of a panorama, camera noise, the light's azimuth (None: the world's)."""

    camera: Camera = field(default_factory=Camera)
    mirror: Catadioptric | None = None
    pixel_noise: Real = PIXEL_NOISE
    gain_noise: Real = 0.0
    light_azimuth_deg: float | None = None


def camera(
    rows: int = 60, cols: int = 360, elev_top_deg: float = 30.0, elev_bottom_deg: float = -30.0, height: float = 25.0
) -> Camera:
    """A validated panoramic `Camera`."""
    rows, cols = positive_int(rows, "rows"), positive_int(cols, "cols")
    if rows > 4096 or cols > 16384:
        raise InputError("cols" if cols > 16384 else "rows", max(rows, cols), "is larger than an image delvjax renders")
    if cols % 4:
        raise InputError("cols", cols, "must be a multiple of 4 (unit moves along the grid axes are whole-pixel turns)")
    if not -90 < elev_bottom_deg < elev_top_deg < 90:
        raise InputError("elevation", (elev_top_deg, elev_bottom_deg), "must satisfy -90 < bottom < top < 90 deg")
    return Camera(
        height=positive(height, "camera_height"),
        elev_top_deg=float(elev_top_deg),
        elev_bottom_deg=float(elev_bottom_deg),
        rows=rows,
        cols=cols,
    )


def lit(world, light_azimuth_deg: float | None):
    """The world with the light turned to `light_azimuth_deg` (same elevation), or as it is."""
    if light_azimuth_deg is None:
        return world
    light = np.asarray(world.light)
    el = math.atan2(light[2], math.hypot(light[0], light[1]))
    az = math.radians(float(light_azimuth_deg))
    return eqx.tree_at(
        lambda w: w.light,
        world,
        jnp.asarray([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)], jnp.float32),
    )


def light_angles(world) -> list[float]:
    """[azimuth, elevation] in degrees of the world's light (recorded in a rendered database's metadata)."""
    x, y, z = (float(v) for v in np.asarray(world.light))
    return [round(math.degrees(math.atan2(y, x)), 6), round(math.degrees(math.atan2(z, math.hypot(x, y))), 6)]


def render_images(
    world,
    settings_camera: Camera,
    mirror: Catadioptric | None,
    positions,
    headings,
    index,
    key,
    pixel_noise,
    gain_noise,
    width: int = IMAGE_WIDTH,
):
    """uint8 images (k, H, W, 3) at poses, image i with camera noise from fold_in(key, index[i]);
    `width` images at a time (`render_sizes`). The noise sigmas are traced: one program for every level."""
    noise = traced_floats((pixel_noise, gain_noise))
    return _render_images(world, settings_camera, mirror, positions, headings, index, key, *noise, width)


@eqx.filter_jit
def _render_images(world, settings_camera, mirror, positions, headings, index, key, pixel_noise, gain_noise, width):
    def one(pos, heading, i):
        img = panorama(world, settings_camera, pos, heading) if mirror is None else donut(world, mirror, pos, heading)
        return to_uint8(camera_noise(jax.random.fold_in(key, i), img, pixel_noise, gain_noise))

    return fixed_width_map(one, (positions, headings, index), width=width)


def extract_rings(images, cam: Camera, mirror: Catadioptric | None, extractor: Extractor):
    """Ring `Snapshot`s (k leading) of uint8 images (panoramas, or donuts unwrapped with `mirror`). The
    extractor's numbers are traced: one program for every threshold and band."""
    return _extract_rings(images, cam, mirror, traced_floats(extractor))


@eqx.filter_jit
def _extract_rings(images, cam, mirror, extractor):
    def one(image):
        img = image.astype(jnp.float32) / 255.0
        return extractor(img if mirror is None else unwrap(img, mirror, cam), cam)

    return fixed_width_map(one, (images,), width=IMAGE_WIDTH)


def chunks(n: int, chunk: int):
    """(lo, hi) of the host-side chunks of n items, `chunk` at a time."""
    for lo in range(0, n, chunk):
        yield lo, min(n, lo + chunk)


def head(tree, n: int):
    """The first n rows of every array of a pytree (a chunk without its padding)."""
    return jax.tree.map(lambda a: a[:n], tree)


def rendered_chunks(world, settings: "ImageSettings", positions, headings, key, chunk: int):
    """(lo, hi, uint8 images (size, H, W, 3)) of every chunk of poses (`render_images`); every chunk has
    the same size (`full`): rows from hi - lo on are padding."""
    cam, mirror = settings.camera, settings.mirror
    width, chunk = render_sizes(cam.rows * cam.cols if mirror is None else mirror.size**2, chunk)
    size = min(chunk, len(positions))
    for lo, hi in chunks(len(positions), size):
        imgs = render_images(
            world,
            settings.camera,
            settings.mirror,
            jnp.asarray(pad_rows(positions[lo:hi], size)),
            jnp.asarray(pad_rows(headings[lo:hi], size)),
            jnp.arange(lo, lo + size),
            key,
            settings.pixel_noise,
            settings.gain_noise,
            width,
        )
        yield lo, hi, imgs


def world_grid(iw: ImageWorld, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Grid points of the world's arena (docs/model.md §5 cells) clear of every obstacle by the world's
    clearance, and their integer grid indices."""
    pts = grid_points(np.asarray(iw.world.arena), spacing)
    keep = iw.clear(pts)
    a = np.asarray(iw.world.arena)
    grid = np.round((pts - a[:2] - spacing / 2) / spacing).astype(int)
    return pts[keep], grid[keep]


def render_rings(
    iw: ImageWorld,
    settings: ImageSettings,
    positions: np.ndarray,
    headings: np.ndarray,
    key,
    extractor: Extractor | None = None,
    chunk: int = DEFAULT_CHUNK,
) -> RingDatabase:
    """Render and reduce to rings in memory (no files): the database `render_database` would write and
    `load_database` read back, ring for ring (docs/images.md §6)."""
    world, ex = lit(iw.world, settings.light_azimuth_deg), extractor or iw.extractor
    parts = [
        head(extract_rings(imgs, settings.camera, settings.mirror, ex), hi - lo)
        for lo, hi, imgs in rendered_chunks(world, settings, positions, headings, key, chunk)
    ]
    snaps = jax.tree.map(lambda *a: jnp.concatenate(a), *parts)
    return RingDatabase(snaps, jnp.asarray(positions, jnp.float32), jnp.asarray(headings, jnp.float32))


def check_render(
    env: str | ImageWorld, spacing: float | None, settings: ImageSettings, seed: int, max_points: int, chunk: int
) -> tuple[ImageWorld, float]:
    """Validate a render before any work: the world (a name, or an `ImageWorld`), spacing, noise, seed, size."""
    iw = env if isinstance(env, ImageWorld) else image_world(env)
    spacing = iw.spacing if spacing is None else positive(spacing, "spacing")
    non_negative(settings.pixel_noise, "pixel_noise")
    non_negative(settings.gain_noise, "gain_noise")
    seed_value(seed)
    positive_int(chunk, "chunk")
    if settings.light_azimuth_deg is not None:
        angle_deg(settings.light_azimuth_deg, "light_deg")
    check_size(grid_count(np.asarray(iw.world.arena), spacing), max_points, "spacing", spacing)
    if not len(world_grid(iw, spacing)[0]):
        raise InputError("spacing", spacing, "leaves no grid point in the arena clear of the obstacles")
    return iw, spacing


PNG_SHARE = 0.75  # a noisy rendered image compresses to about this share of its raw size


def check_disk(out: str | Path, n: int, settings: ImageSettings) -> None:
    """`InputError` naming --out when n images would not fit on its disk (estimated before any work)."""

    base = check_folder(out, "--out", str(out))
    cam, mirror = settings.camera, settings.mirror
    raw = 3 * (cam.rows * cam.cols if mirror is None else mirror.size**2)
    need = n * (PNG_SHARE * raw + 200)
    free = shutil.disk_usage(base).free
    if need > free:
        raise InputError(
            "--out",
            str(out),
            f"would need about {need / 1e9:.3g} GB for {n} images, and its disk has {free / 1e9:.3g} GB free",
        )


def database_metadata(
    name: str,
    arena,
    home,
    spacing: float,
    cam: Camera,
    mirror: Catadioptric | None,
    ex: Extractor,
    obstacles: dict,
    **extra,
) -> dict:
    """The database_metadata.yaml block: BoB's camera fields plus `delvjax:` (docs/images.md §4)."""
    res = [cam.cols, cam.rows] if mirror is None else [mirror.size, mirror.size]
    block = {
        "world": name,
        "arena_cm": [float(v) for v in np.asarray(arena)],
        "home_cm": [float(v) for v in np.asarray(home)],
        "spacing_cm": float(spacing),
        "camera_height_cm": float(cam.height),
        "elevation_deg": [float(cam.elev_top_deg), float(cam.elev_bottom_deg)],
        "panorama": [cam.rows, cam.cols],
        **extra,
        "extractor": {
            k: getattr(ex, k)
            for k in (
                "hue_deg",
                "hue_width_deg",
                "sat_min",
                "val_min",
                "band_deg",
                "band_height_deg",
                "fill",
                "max_blobs",
            )
        },
        "obstacles": {k: [[float(x) for x in row] for row in v] for k, v in obstacles.items()},
    }
    if mirror is not None:
        block["catadioptric"] = {
            k: getattr(mirror, k) for k in ("inner", "outer", "elev_inner_deg", "elev_outer_deg", "size")
        }
    return {
        "camera": {"name": "delvjax", "resolution": res, "isPanoramic": 1},
        "needsUnwrapping": int(mirror is not None),
        "isGreyscale": 0,
        "delvjax": block,
    }


@keywords_after(2, ("spacing", "settings", "seed", "chunk", "max_points", "progress"))
def render_database(
    env: str,
    out: str | Path,
    *,
    spacing: float | None = None,
    settings: ImageSettings | None = None,
    seed: int = 0,
    chunk: int = DEFAULT_CHUNK,
    max_points: int = MAX_POINTS,
    progress: Callable[[int, int], None] | None = None,
) -> dict:
    """Render `env` (an image world, preset or environment file) on its grid into a BoB database at
    `out` (docs/images.md §4); nothing is left at `out` if it fails. Returns a summary."""
    settings = settings or ImageSettings()
    iw, spacing = check_render(env, spacing, settings, seed, max_points, chunk)
    pts, grid = world_grid(iw, spacing)
    check_disk(out, len(pts), settings)
    headings = np.zeros(len(pts), np.float32)
    world, key = lit(iw.world, settings.light_azimuth_deg), jax.random.PRNGKey(seed)
    writer = DatabaseWriter(out)
    try:
        for lo, hi, imgs in rendered_chunks(world, settings, pts, headings, key, chunk):
            writer.add(
                np.asarray(imgs[: hi - lo]),
                np.c_[pts[lo:hi], np.full(hi - lo, settings.camera.height)] * 10.0,  # mm; Z: the camera's height
                np.degrees(headings[lo:hi]),
                grid[lo:hi],
                donut=settings.mirror is not None,
            )
            if progress:
                progress(hi - lo, len(pts))
        writer.commit(
            database_metadata(
                iw.name,
                iw.world.arena,
                iw.home,
                spacing,
                settings.camera,
                settings.mirror,
                iw.extractor,
                iw.obstacles(),
                pixel_noise=settings.pixel_noise,
                gain_noise=settings.gain_noise,
                seed=seed,
                light_deg=light_angles(world),
            )
        )
    except BaseException:
        writer.discard()
        raise
    return {"world": iw.name, "images": len(pts), "spacing_cm": spacing, "out": str(out)}
