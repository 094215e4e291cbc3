"""A world's image database rendered in memory (docs/images.md §5): the rings `render_database` would
write, without files."""

from __future__ import annotations

import dataclasses

import jax
import numpy as np

from ..core.deprecation import keywords_after
from ..core.images import Extractor
from ..options._limits import MAX_POINTS
from ._load import LoadedDatabase, check_home_move
from ._render import DEFAULT_CHUNK, ImageSettings, check_render, render_rings, world_grid
from ._worlds import ImageWorld


@keywords_after(1, ("spacing", "settings", "seed", "extractor", "chunk", "panoramas"))
def render_in_memory(
    env: str | ImageWorld,
    *,
    spacing: float | None = None,
    settings=None,
    seed: int = 0,
    extractor: Extractor | None = None,
    chunk: int = DEFAULT_CHUNK,
    panoramas: bool = False,
) -> LoadedDatabase:
    """The database `render_database` would write of `env` (a world's name, or an `ImageWorld`), rendered and
    reduced to rings in memory (no files;
    ring for ring what `load_database` reads back from them, docs/images.md §5); panoramas: keep
    every gray panorama too (MinWarping, docs/model.md §4.7)."""

    settings = settings or ImageSettings()
    iw, spacing = check_render(env, spacing, settings, seed, MAX_POINTS, chunk)
    pts, _ = world_grid(iw, spacing)
    ex = extractor or iw.extractor
    if panoramas:
        ex = dataclasses.replace(ex, panorama=True)
    rings = render_rings(iw, settings, pts, np.zeros(len(pts), np.float32), jax.random.PRNGKey(seed), ex, chunk)
    home_index = int(np.argmin(np.linalg.norm(pts - np.asarray(iw.home), axis=-1)))
    check_home_move(pts, home_index, spacing, "env", env if isinstance(env, str) else iw.name)
    return LoadedDatabase(
        iw.name,
        rings,
        [],
        pts[home_index].astype(np.float64),
        home_index,
        np.asarray(iw.world.arena, np.float64),
        spacing,
        settings.camera,
        ex,
        iw.obstacles(),
        settings.mirror,
    )


rendered_database = render_in_memory  # the name until 0.1 (CHANGELOG): `render_database` writes files, this does not
