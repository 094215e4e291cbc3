"""A sweep file on disk (docs/sweeps.md "Axes", env): its text, and each environment path it names
resolved against the file's own folder, so a sweep file and the `sweep.toml` a sweep writes run alike from
any working folder."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

from ..core.errors import InputError, warn
from ..envs._presets import PRESETS
from ._spec import SweepSpec, parse_sweep


def read_sweep(path: str | Path) -> SweepSpec:
    """A sweep file from disk (`parse_sweep`). A relative environment path is the file's folder's (as in most
    configuration formats); one found only in the working folder is used with a warning. The spec's text,
    which a sweep writes as sweep.toml, names every such file by its absolute path."""
    p = Path(path)
    try:
        text = p.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("sweep", str(path), f"cannot be read ({getattr(exc, 'strerror', None) or exc})") from None
    spec = parse_sweep(text, str(path))
    files = {}
    for label in spec.axes.get("env", []):
        if label in PRESETS or label in spec.random_envs or label in spec.ensemble_envs or Path(label).is_absolute():
            continue
        beside, here = p.parent / label, Path(label)
        if beside.is_file():
            files[label] = str(beside.resolve())
        elif here.is_file():
            warn(f"axes.env: {label!r} is not in the sweep file's folder {p.parent}; using the working folder's")
            files[label] = str(here.resolve())
    if not files:
        return spec
    return dataclasses.replace(spec, env_files=files, text=portable(text, files))


def portable(text: str, files: dict[str, str]) -> str:
    """`text` with each quoted relative environment path replaced by its absolute path (a JSON string is a
    valid TOML basic string)."""
    for label, target in files.items():
        quoted = "|".join(re.escape(q + label + q) for q in ('"', "'"))
        text = re.sub(quoted, lambda _: json.dumps(target), text)
    return text
