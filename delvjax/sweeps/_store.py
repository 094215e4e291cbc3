"""Finished sweep cells on disk, so a killed or changed sweep recomputes only what is missing
(docs/sweeps.md "Resuming"). A cell is known by a digest of everything that decides its numbers:
the delvjax sources, jax's version, the scene, method, sensor and key leaves, grid and clearance."""

from __future__ import annotations

import hashlib
from pathlib import Path

import jax
import numpy as np

from ..core.errors import InputError
from ..outputs._cache import package_sources
from ..outputs._files import atomic_path

STORE = ".cells"  # folder inside the sweep's --out


def code_digest() -> str:
    """The delvjax sources and the jax version: a change to either invalidates every cell."""
    h = hashlib.sha256(jax.__version__.encode())
    for path in package_sources():
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def cell_digest(req: dict, code: str) -> str:
    """Digest of one cell's setup (`sweep_kinds.cell_setup`'s result: every leaf and setting) under `code`."""
    h = hashlib.sha256(code.encode())
    leaves, treedef = jax.tree.flatten({k: v.arrays() if hasattr(v, "arrays") else v for k, v in req.items()})
    h.update(str(treedef).encode())
    for leaf in leaves:
        a = np.asarray(leaf)
        h.update(a.dtype.str.encode() + str(a.shape).encode() + a.tobytes())
    return h.hexdigest()[:32]


def load_cells(out: Path) -> dict[str, dict[str, float]]:
    """Every finished cell in `out`: digest -> its sums."""
    done: dict[str, dict[str, float]] = {}
    for path in sorted((Path(out) / STORE).glob("*.npz")):
        try:
            with np.load(path) as z:
                names = [k for k in z.files if k != "digest"]
                for i, d in enumerate(z["digest"]):
                    done[str(d)] = {k: z[k][i] for k in names}
        except (OSError, ValueError, KeyError):  # a damaged chunk is computed again
            continue
    return done


def save_cells(out: Path, digests: list[str], sums: dict[str, np.ndarray]) -> None:
    """One finished chunk, written atomically (a killed run leaves whole chunks or none)."""
    try:
        with atomic_path(Path(out) / STORE / f"{digests[0]}-{len(digests)}.npz") as tmp:
            np.savez(tmp, digest=np.asarray(digests), **sums)
    except OSError as exc:  # e.g. the disk filled up during the sweep: finished chunks stay
        raise InputError("--out", str(out), f"cannot be written ({exc.strerror or exc})") from None
