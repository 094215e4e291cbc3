"""The `delvjax:` block of a database's metadata (docs/images.md §4), checked field by field when it is
read: a malformed value is one line naming the file, the field and the value, before any image is read."""

from __future__ import annotations

from pathlib import Path

from ..core.errors import InputError, is_finite_number


def _numbers(value, n: int | None) -> bool:
    """A list of finite numbers (of length n, if given)."""
    return (
        isinstance(value, (list, tuple)) and (n is None or len(value) == n) and all(is_finite_number(v) for v in value)
    )


def _positive(value) -> bool:
    return _numbers([value], 1) and value > 0


SHAPES = {  # field -> (test, what it must be)
    "arena_cm": (lambda v: _numbers(v, 4) and v[0] < v[2] and v[1] < v[3], "[xmin, ymin, xmax, ymax] in cm"),
    "home_cm": (lambda v: _numbers(v, 2), "[x, y] in cm"),
    "spacing_cm": (_positive, "a number > 0 (cm)"),
    "camera_height_cm": (_positive, "a number > 0 (cm)"),
    "elevation_deg": (
        lambda v: _numbers(v, 2) and -90 <= v[1] < v[0] <= 90,
        "[top, bottom] in degrees, -90 <= bottom < top <= 90",
    ),
    "panorama": (
        lambda v: _numbers(v, 2) and all(isinstance(x, int) and x > 0 for x in v),
        "[rows, columns], integers > 0",
    ),
    "extractor": (lambda v: isinstance(v, dict), "a table of extractor settings"),
    "catadioptric": (
        lambda v: isinstance(v, dict) and _numbers(list(v.values()), None),
        "a table of numbers (inner, outer, elev_inner_deg, elev_outer_deg, size)",
    ),
}
OBSTACLES = {"cylinders": 3, "boxes": 4}  # numbers per row: [x, y, r] and [xmin, ymin, xmax, ymax]


def check_metadata(block, path: Path) -> dict:
    """The `delvjax:` block, every known field checked (`InputError` naming `path`, the field and the value)."""
    if block is None:
        return {}
    if not isinstance(block, dict):
        raise InputError("images", str(path), f"delvjax: must be a table, got {block!r}")
    for name, (test, what) in SHAPES.items():
        if name in block and not test(block[name]):
            raise InputError("images", str(path), f"delvjax.{name} must be {what}, got {block[name]!r}")
    obstacles = block.get("obstacles")
    if obstacles is not None:
        if not isinstance(obstacles, dict) or set(obstacles) - set(OBSTACLES):
            raise InputError("images", str(path), f"delvjax.obstacles must be a table of {' and '.join(OBSTACLES)}")
        for kind, n in OBSTACLES.items():
            rows = obstacles.get(kind) or []
            if not isinstance(rows, list) or not all(_numbers(r, n) for r in rows):
                raise InputError(
                    "images", str(path), f"delvjax.obstacles.{kind} must be rows of {n} numbers, got {rows!r}"
                )
    return block
