"""Importing an image database (docs/images.md §4.1): a BoB database or a plain folder, every image
checked, written as a BoB database with delvjax metadata (`delvjax images import`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._conventions import BOB, resolve
from ._disk import read_index
from ._load import LoadedDatabase, database_arena, database_spacing, load_database
from ._render import database_metadata
from ._writer import DatabaseWriter


def import_database(
    src: str | Path, out: str | Path, conventions: dict | None = None, write_as: dict | None = None, **options
) -> LoadedDatabase:
    """Read a database (BoB or a plain folder; `load_database` options; `conventions` where it does not
    declare its own, docs/images.md §4.1), check every image, and write it as a BoB database at `out`
    with delvjax metadata, in BoB's conventions or `write_as` (heading, heading_column, columns).
    Positions (float64 mm), Z and, where the conventions stay, the headings are copied exactly; nothing
    is left at `out` if any image fails."""
    index = read_index(src, conventions)
    spacing = database_spacing(index, options.get("spacing"))
    arena = database_arena(index, options.get("arena"), spacing)
    target = resolve({}, BOB, write_as or {}, str(out))
    writer = DatabaseWriter(out, target)
    grid = None
    if index.kind == "grid":
        grid = np.round((index.positions - arena[:2] - spacing / 2) / spacing).astype(int)
        grid -= grid.min(0)  # BoB's grid cells are unsigned

    def sink(images: np.ndarray, rows: slice) -> None:
        width = images.shape[2]
        same = index.conventions == target or index.needs_unwrapping
        writer.add(
            images,
            index.xyz_mm[rows],
            np.degrees(index.headings(width)[rows]),
            None if grid is None else grid[rows],
            donut=index.needs_unwrapping,
            stored=index.heading_deg[rows] if same else None,
        )

    try:
        db = load_database(src, sink=sink, conventions=conventions, **options)
        writer.commit(
            database_metadata(
                db.name,
                db.absolute(db.arena.reshape(2, 2)).ravel(),
                db.absolute(db.home),
                db.spacing,
                db.camera,
                db.mirror,
                db.extractor,
                index.meta.get("obstacles") or {"cylinders": [], "boxes": []},  # as stored: absolute
            )
        )
    except BaseException:
        writer.discard()
        raise
    return db
