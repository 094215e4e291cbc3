"""No output overwrites an input (docs/reliability.md): before any work, every output path of a command
is resolved (symlinks followed; for a file that does not exist yet, its folder) and compared with every
input file and folder; an output that is an input file, or lies inside an input folder (an image
database, a sweep's store), is refused naming both options."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..core.errors import InputError

Paths = str | Path | Sequence[str | Path] | None


def _real(path: str | Path) -> str:
    return os.path.realpath(os.path.abspath(os.fspath(path)))


def _each(paths: Paths) -> list[str | Path]:
    if paths is None:
        return []
    if isinstance(paths, (str, Path)):
        return [paths]
    return [p for p in paths if p is not None]


def _inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


def check_no_clash(outputs: Mapping[str, Paths], inputs: Mapping[str, Paths]) -> None:
    """`InputError` naming the output option if one of its paths is an input file, or lies inside (or is)
    an input folder, of `inputs` ({option: path or paths}); inputs that do not exist are ignored (their
    own check reports them)."""
    given = []
    for field, paths in inputs.items():
        for p in _each(paths):
            if os.path.exists(p):
                given.append((field, p, _real(p), os.path.isdir(p)))
    for out_field, paths in outputs.items():
        for out in _each(paths):
            target = _real(out)
            for in_field, p, real, is_dir in given:
                if (is_dir and _inside(target, real)) or target == real:
                    where = "is" if target == real else "lies inside"
                    raise InputError(
                        out_field,
                        str(out),
                        f"{where} the input {in_field} ({p}): an output must not overwrite what the command reads",
                    )
