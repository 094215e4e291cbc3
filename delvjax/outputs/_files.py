"""Writing results: CSV, JSON and figures, each written atomically (no partial files: a temporary beside
the target, fsynced, renamed; `_temporary.py`); the outputs of one command are checked before any work
and written as a unit (`output_set`)."""

from __future__ import annotations

import csv
import json
import math
import os
import tempfile
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..core.errors import InputError
from ._temporary import fsync_path, new_temp_file, ordinary_permissions, remove_stale


def check_folder(folder: str | Path, field: str, value: object) -> Path:
    """`folder` exists or can be created, and the nearest existing folder on its way is writable."""
    base = Path(folder)
    try:
        while not base.exists() and base != base.parent:
            base = base.parent
        if not base.is_dir():
            raise InputError(field, value, f"lies under {base}, which is not a directory")
    except OSError as exc:  # a folder on the way that cannot be searched
        raise InputError(field, value, f"cannot be checked ({exc.strerror or exc})") from None
    if not os.access(base, os.W_OK | os.X_OK):
        raise InputError(field, value, f"is not writable (folder {base})")
    try:  # os.access trusts the permission bits: a read-only or virtual file system (/proc) says yes
        os.rmdir(tempfile.mkdtemp(prefix=".delvjax-probe-", dir=base))
    except OSError as exc:
        raise InputError(field, value, f"is not writable (folder {base}: {exc.strerror or exc})") from None
    return base


def check_out_dir(out: str | Path) -> Path:
    """An output folder, checked before any work: a folder or creatable, writable (else InputError naming --out)."""
    path = Path(out)
    if path.exists() and not path.is_dir():
        raise InputError("--out", str(out), "exists and is not a directory")
    check_folder(path, "--out", str(out))
    remove_stale(path)  # temporaries of an earlier run of this folder that was killed
    return path


def check_output_path(path: str | Path, field: str, suffixes: Sequence[str]) -> Path:
    """Validate an output path before any work: known suffix, not a directory or other non-file, a
    folder that is (or can be created) writable, an existing file writable."""
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise InputError(field, str(path), f"must end in {' or '.join(suffixes)}")
    check_folder(p.parent, field, str(path))
    if p.is_dir():
        raise InputError(field, str(path), "is a directory")
    if p.exists() and not p.is_file():
        raise InputError(field, str(path), "exists and is not a regular file")
    if p.exists() and not os.access(p, os.W_OK):
        raise InputError(field, str(path), "exists and is not writable")
    return p


def _identity(path: str | Path) -> object:
    try:
        st = os.stat(path)  # an existing file under any name (links included)
        return st.st_dev, st.st_ino
    except OSError:
        return os.path.realpath(path)


def check_distinct(named: Mapping[str, str | Path]) -> None:
    """No two of `named` ({option: path}) name the same file (a later one is reported)."""
    seen: dict[object, str] = {}
    for field, path in named.items():
        key = _identity(path)
        if key in seen:
            raise InputError(field, str(path), f"names the same file as {seen[key]}")
        seen[key] = field


def _temp_beside(target: Path) -> Path:
    return new_temp_file(target.parent)


def _publish(tmp: Path, target: Path) -> None:
    """fsync the written temporary, give it ordinary permissions, rename it onto `target`, fsync the folder."""
    fsync_path(tmp)
    ordinary_permissions(tmp)
    os.replace(tmp, target)
    fsync_path(target.parent)


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside `path`; rename it onto `path` only if the block succeeds."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = _temp_beside(target)
    try:
        yield tmp
        _publish(tmp, target)
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


def _csv_to(path: Path, columns: Mapping[str, Sequence | np.ndarray]) -> None:
    names = list(columns)
    data = [list(np.asarray(columns[n]).tolist()) if not isinstance(columns[n], list) else columns[n] for n in names]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for row in zip(*data):
            w.writerow([_cell(v) for v in row])


def write_csv(path: str | Path, columns: dict[str, Sequence]) -> None:
    """Columns of equal length -> CSV with a header row."""
    with atomic_path(path) as tmp:
        _csv_to(tmp, columns)


def _row_columns(rows: list[dict]) -> dict[str, list]:
    keys = list(dict.fromkeys(k for r in rows for k in r))
    return {k: [r.get(k) for r in rows] for k in keys}


def write_rows_csv(path: str | Path, rows: list[dict]) -> None:
    """A list of flat dicts -> CSV; columns are the union of the keys in first-seen order, a
    missing value is an empty cell."""
    write_csv(path, _row_columns(rows))


def jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, (np.ndarray,)):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return None if math.isnan(obj) else float(obj)
    return obj


def _json_to(path: Path, obj) -> None:
    path.write_text(json.dumps(jsonable(obj), indent=2) + "\n")


def write_json(path: str | Path, obj) -> None:
    """JSON with NaN written as null."""
    with atomic_path(path) as tmp:
        _json_to(tmp, obj)


def _figure_to(fig, tmp: Path, target: Path, dpi: int) -> None:
    fig.savefig(tmp, dpi=dpi, bbox_inches="tight", format=target.suffix.lstrip(".").lower())


def write_figure(fig, path: str | Path, dpi: int = 150) -> None:
    """Write a figure atomically, format from the suffix. Figures come from `plots.subplots`, outside
    pyplot's state, so this is safe in a worker thread and leaves nothing open."""
    with atomic_path(path) as tmp:
        _figure_to(fig, tmp, Path(path), dpi)


def _failed(field: str, path: str | Path, exc: BaseException) -> InputError:
    """A write that failed, as one line naming the option and the path."""
    why = exc.strerror if isinstance(exc, OSError) and exc.strerror else f"{type(exc).__name__}: {exc}"
    return InputError(field, str(path), "could not be written (" + " ".join(str(why).split()) + ")")


class OutputSet:
    """The files of one command, staged under temporary names beside their targets (see `output_set`)."""

    def __init__(self) -> None:
        self._staged: list[tuple[Path, Path, str, bool]] = []  # temporary, target, option, target existed
        self._made: list[Path] = []  # folders created here, outermost first

    def _folder(self, folder: Path) -> None:
        missing = []
        while not folder.exists() and folder != folder.parent:
            missing.append(folder)
            folder = folder.parent
        for d in reversed(missing):
            d.mkdir()
            self._made.append(d)

    def _stage(self, path: str | Path, field: str, write: Callable[[Path], None], errors=(OSError,)) -> None:
        target = Path(path)
        try:
            self._folder(target.parent)
            tmp = _temp_beside(target)
        except OSError as exc:
            raise _failed(field, path, exc) from None
        self._staged.append((tmp, target, field, target.exists()))
        try:
            write(tmp)
        except errors as exc:
            raise _failed(field, path, exc) from None

    def file(self, path: str | Path, write: Callable[[Path], None], field: str) -> None:
        """Stage a file written by `write(temporary_path)` (e.g. a netCDF dataset)."""
        self._stage(path, field, write, errors=(Exception,))

    def csv(self, path: str | Path, columns: Mapping[str, Sequence | np.ndarray], field: str) -> None:
        """Stage columns as CSV (`write_csv`)."""
        self._stage(path, field, lambda tmp: _csv_to(tmp, columns))

    def rows_csv(self, path: str | Path, rows: list[dict], field: str) -> None:
        """Stage rows as CSV (`write_rows_csv`)."""
        self.csv(path, _row_columns(rows), field)

    def json(self, path: str | Path, obj, field: str) -> None:
        """Stage JSON (`write_json`)."""
        self._stage(path, field, lambda tmp: _json_to(tmp, obj))

    def figure(self, fig, path: str | Path, field: str, dpi: int = 150) -> None:
        """Stage a figure (`write_figure`); any failure to render it is a failed write."""
        self._stage(path, field, lambda tmp: _figure_to(fig, tmp, Path(path), dpi), errors=(Exception,))

    def _commit(self) -> None:
        done: list[Path] = []
        for tmp, target, field, existed in self._staged:
            try:
                _publish(tmp, target)
            except OSError as exc:
                for t in done:
                    t.unlink(missing_ok=True)
                raise _failed(field, target, exc) from None
            if not existed:
                done.append(target)

    def _discard(self) -> None:
        for tmp, *_ in self._staged:
            tmp.unlink(missing_ok=True)
        for d in reversed(self._made):
            try:
                d.rmdir()
            except OSError:  # not empty: something else is in it now
                pass


@contextmanager
def output_set() -> Iterator[OutputSet]:
    """Write several outputs as a unit: each is staged beside its target and all are renamed at the end
    of the block; if any write fails (InputError naming its option), no target is created and the
    folders made for them are removed again. A target that existed before keeps its content, unless the
    failure is a rename at the very end after that target was already replaced."""
    out = OutputSet()
    try:
        yield out
        out._commit()
    except BaseException:
        out._discard()
        raise
