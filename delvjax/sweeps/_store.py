"""Finished sweep cells on disk, so a killed or changed sweep recomputes only what is missing
(docs/sweeps.md "Resuming"). A cell is known by a digest of everything that decides its numbers:
the delvjax sources, jax's version, the scene, method, sensor and key leaves, grid and clearance."""

from __future__ import annotations

import hashlib
from pathlib import Path

import jax
import numpy as np

from ..core.errors import InputError, warn
from ..outputs._cache import package_sources
from ..outputs._files import atomic_path
from ..outputs._temporary import remove_stale

STORE = ".cells"  # folder inside the sweep's --out


def code_digest() -> str:
    """The delvjax sources and the jax version: a change to either invalidates every cell."""
    h = hashlib.sha256(jax.__version__.encode())
    for path in package_sources():
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def cell_digest(req: dict, code: str) -> str:
    """Digest of one cell's setup (`_kinds.cell_setup`'s result: every leaf and setting) under `code`."""
    h = hashlib.sha256(code.encode())
    leaves, treedef = jax.tree.flatten({k: v.arrays() if hasattr(v, "arrays") else v for k, v in req.items()})
    h.update(str(treedef).encode())
    for leaf in leaves:
        a = np.asarray(leaf)
        h.update(a.dtype.str.encode() + str(a.shape).encode() + a.tobytes())
    return h.hexdigest()[:32]


def _read_chunk(path: Path) -> dict[str, dict[str, float]]:
    with np.load(path, allow_pickle=False) as z:
        names = [k for k in z.files if k != "digest"]
        digests = z["digest"]
        return {str(d): {k: z[k][i] for k in names} for i, d in enumerate(digests)}


def load_cells(out: Path) -> dict[str, dict[str, float]]:
    """Every finished cell in `out`: digest -> its sums. A chunk that cannot be read (damaged on disk,
    or written by a tool other than delvjax's atomic writer) is removed with a warning line, and its
    cells are computed again."""
    done: dict[str, dict[str, float]] = {}
    remove_stale(Path(out) / STORE)  # chunks a killed run left half written
    for path in sorted((Path(out) / STORE).glob("*.npz")):
        try:
            done.update(_read_chunk(path))
        except Exception as exc:  # noqa: BLE001 - any damage (EOFError, BadZipFile, ...) means "not finished"
            warn(f"finished cells {path} cannot be read ({type(exc).__name__}): they are computed again")
            path.unlink(missing_ok=True)
    return done


def save_cells(out: Path, digests: list[str], sums: dict[str, np.ndarray]) -> None:
    """One finished chunk, written atomically (a killed run leaves whole chunks or none)."""
    try:
        with atomic_path(Path(out) / STORE / f"{digests[0]}-{len(digests)}.npz") as tmp, open(tmp, "wb") as fh:
            np.savez(fh, digest=np.asarray(digests), **sums)
    except OSError as exc:  # e.g. the disk filled up during the sweep: finished chunks stay
        raise InputError("--out", str(out), f"cannot be written ({exc.strerror or exc})") from None
