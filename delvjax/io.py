"""Writing results: CSV, JSON and figures, each written atomically (no partial files)."""

from __future__ import annotations

import csv
import json
import math
import os
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator, Sequence

import numpy as np

from .core.errors import InputError


def check_output_path(path: str | Path, field: str, suffixes: Sequence[str]) -> Path:
    """Validate an output path before any work: known suffix, not a directory."""
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise InputError(field, str(path), f"must end in {' or '.join(suffixes)}")
    if p.is_dir():
        raise InputError(field, str(path), "is a directory")
    if p.parent.exists() and not p.parent.is_dir():
        raise InputError(field, str(path), "parent is not a directory")
    return p


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside `path`; rename it onto `path` only if the block succeeds."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; results are ordinary files
        os.replace(tmp, target)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def _cell(v) -> str:
    if v is None:
        return ""
    if isinstance(v, (bool, np.bool_)):
        return "1" if v else "0"
    if isinstance(v, (float, np.floating)):
        return "nan" if math.isnan(v) else f"{float(v):.6g}"
    return str(v)


def write_csv(path: str | Path, columns: dict[str, Sequence]) -> None:
    """Columns of equal length -> CSV with a header row."""
    names = list(columns)
    data = [list(np.asarray(columns[n]).tolist()) if not isinstance(columns[n], list) else columns[n] for n in names]
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for row in zip(*data):
            w.writerow([_cell(v) for v in row])


def write_rows_csv(path: str | Path, rows: list[dict]) -> None:
    """A list of flat dicts -> CSV; columns are the union of the keys in first-seen order, a
    missing value is an empty cell."""
    keys = list(dict.fromkeys(k for r in rows for k in r))
    write_csv(path, {k: [r.get(k) for r in rows] for k in keys})


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.ndarray,)):
        return _jsonable(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return None if math.isnan(obj) else float(obj)
    return obj


def write_json(path: str | Path, obj) -> None:
    """JSON with NaN written as null."""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(json.dumps(_jsonable(obj), indent=2) + "\n")


def write_figure(fig, path: str | Path, dpi: int = 150) -> None:
    """Write a figure atomically, format from the suffix. Figures come from `plots.subplots`, outside
    pyplot's state, so this is safe in a worker thread and leaves nothing open."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight", format=Path(path).suffix.lstrip(".").lower())
