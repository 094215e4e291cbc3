"""How a database's headings and image columns are to be read (docs/images.md §4.1).

Three choices fix them: `heading` (math: degrees counter-clockwise from +x; compass: degrees
clockwise from +y, BoB's and a navigator's bearing), `heading_column` (the file column that looks
along the heading: `first`, column 0, or `centre`, column W // 2, BoB's ant-world camera) and
`columns` (the way the view turns as the file column grows: `clockwise`, as a person turning right
sees it and BoB stores it, or `anticlockwise`, navipy's order). In memory every panorama is
delvjax's ring frame: column j looks along h + 360 j / W (counter-clockwise), h the world heading of
column 0 in radians (docs/model.md §2.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.errors import InputError

CHOICES = {  # field -> (metadata key, allowed values, CLI flag)
    "heading": ("headingConvention", ("math", "compass"), "--heading-convention"),
    "heading_column": ("headingColumn", ("first", "centre"), "--heading-column"),
    "columns": ("columnOrder", ("clockwise", "anticlockwise"), "--columns"),
}


@dataclass(frozen=True)
class Conventions:
    """A database's heading convention, heading column and column order (module docstring)."""

    heading: str = "compass"
    heading_column: str = "centre"
    columns: str = "clockwise"

    def __post_init__(self):
        for name, (_, allowed, flag) in CHOICES.items():
            if getattr(self, name) not in allowed:
                raise InputError(flag, getattr(self, name), f"must be one of {', '.join(allowed)}")

    def metadata(self) -> dict:
        """The metadata keys that declare these conventions (written beside BoB's own)."""
        return {key: getattr(self, name) for name, (key, _, _) in CHOICES.items()}

    def origin_column(self, width: int) -> int:
        """The file column that looks along the stored heading."""
        return 0 if self.heading_column == "first" else width // 2

    def column0_deg(self, heading_deg: np.ndarray, width: int) -> np.ndarray:
        """Stored headings (deg, float64, NaN kept) -> world angle of file column 0 (deg, math, [0, 360))."""
        theta = np.asarray(heading_deg, np.float64)
        theta = theta if self.heading == "math" else 90.0 - theta
        turn = 360.0 * self.origin_column(width) / width
        return np.mod(theta + (turn if self.columns == "clockwise" else -turn), 360.0)

    def stored_deg(self, column0_deg: np.ndarray, width: int) -> np.ndarray:
        """The inverse of `column0_deg`: world angle of file column 0 -> the heading to store (deg, [0, 360))."""
        turn = 360.0 * self.origin_column(width) / width
        theta = np.asarray(column0_deg, np.float64) - (turn if self.columns == "clockwise" else -turn)
        return np.mod(theta if self.heading == "math" else 90.0 - theta, 360.0)

    def to_memory(self, images: np.ndarray, axis: int = -2) -> np.ndarray:
        """File column order -> memory order (column j looks 360 j / W counter-clockwise of column 0)."""
        return file_columns(images, axis) if self.columns == "clockwise" else images

    def to_file(self, images: np.ndarray, axis: int = -2) -> np.ndarray:
        return self.to_memory(images, axis)  # both maps are their own inverse


def file_columns(images: np.ndarray, axis: int = -2) -> np.ndarray:
    """Clockwise file columns <-> memory columns of panoramas (..., H, W, 3), or of any array whose
    columns are `axis` (a mask (H, W), a ring (W,): axis=-1). Self-inverse: column j <-> -j mod W,
    so column 0 looks the same way in both."""
    return np.roll(np.flip(images, axis=axis), 1, axis=axis)


def _circular(deg: np.ndarray) -> tuple[float, float]:
    """Circular mean (deg, (-180, 180]) and resultant length (0..1) of angles in degrees."""
    z = np.exp(1j * np.radians(deg)).mean()
    return float(np.degrees(np.angle(z))), float(abs(z))


def mismatch(signed_deg: np.ndarray, stored_deg: np.ndarray, width: int, used: Conventions) -> str | None:
    """What the homing directions' signed errors (deg, one per point, NaN where invalid) say of the heading
    conventions `used` to read `stored_deg` (each point's stored heading): None when the errors are small
    or without a pattern; else the flags of the conventions under which the errors would vanish (a
    database's own compass headings of the centre column read as a positions.csv folder's math headings
    of column 0 turn every view and give errors of about 90°), or the consistent turn itself."""
    ok = np.isfinite(signed_deg) & np.isfinite(stored_deg)
    e, h = signed_deg[ok], stored_deg[ok]
    if e.size < 8 or np.abs(e).mean() < 45.0:
        return None
    fits = []
    for heading in CHOICES["heading"][1]:
        for column in CHOICES["heading_column"][1]:
            alt = Conventions(heading, column, used.columns)
            turn = used.column0_deg(h, width) - alt.column0_deg(h, width)  # views turned by reading `used`
            rest = np.mod(e - turn + 180.0, 360.0) - 180.0
            mean, length = _circular(rest)
            if alt != used and length > 0.8 and abs(mean) < 20.0:
                fits.append((np.abs(rest).mean(), alt))
    if fits:
        alt = min(fits, key=lambda f: f[0])[1]
        flags = " ".join(f"{CHOICES[n][2]} {getattr(alt, n)}" for n in CHOICES if getattr(alt, n) != getattr(used, n))
        return (
            f"the headings are probably not {used.heading} of the {used.heading_column} column: the homing "
            f"directions err by {np.abs(e).mean():.0f}° on average, and read with {flags} they would not "
            "(docs/images.md §4.1)"
        )
    mean, length = _circular(e)
    if length > 0.8:
        return (
            f"every homing direction is turned by about {mean:.0f}°: the stored headings probably follow another "
            "convention (--heading-convention, --heading-column, --columns; docs/images.md §4.1)"
        )
    return None


BOB = Conventions("compass", "centre", "clockwise")  # BoB's ant world and its route recorder
DELVJAX_BEFORE = Conventions("math", "first", "clockwise")  # delvjax databases written before conventions were declared
PLAIN = DELVJAX_BEFORE  # positions.csv: heading_deg counter-clockwise from +x, of file column 0 (docs/images.md §4)


def declared(meta: dict, path) -> dict:
    """The conventions a database's metadata declares ({} if none); a bad value names the file and key."""
    out = {}
    for name, (key, allowed, _) in CHOICES.items():
        if key in meta:
            if meta[key] not in allowed:
                raise InputError("images", str(path), f"{key} must be one of {', '.join(allowed)}, got {meta[key]!r}")
            out[name] = meta[key]
    return out


def resolve(own: dict, default: Conventions | None, given: dict, where: str) -> Conventions:
    """The database's conventions: what it declares (`own`), else `default`; `given` (CLI or API
    choices) fills what neither says and must agree with what the database declares. `InputError`
    naming the choice when a convention cannot be told, or when `given` contradicts the database."""
    given = {k: v for k, v in given.items() if v is not None}
    for name, value in given.items():
        if name in own and own[name] != value:
            key, _, flag = CHOICES[name]
            raise InputError(
                flag, value, f"contradicts {where}, which declares {key}: {own[name]} (a database has one convention)"
            )
    values = {**given, **own}
    missing = [n for n in CHOICES if n not in values]
    if missing and default is None:
        flags = ", ".join(f"{CHOICES[n][2]} {'|'.join(CHOICES[n][1])}" for n in missing)
        raise InputError(
            "images", where, f"does not say how its headings and columns run: give {flags} (docs/images.md §4.1)"
        )
    base = default or Conventions()
    return Conventions(**{n: values.get(n, getattr(base, n)) for n in CHOICES})
