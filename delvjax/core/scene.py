"""Environments as arrays: cylinders in a rectangular arena around a home (docs/model.md §1, §2.1).

An `Env` is a pytree. Landmarks are an `(L, 3)` array of `[x, y, r]` (cm) with a validity
mask, so environments with different counts can be padded to one shape and batched.
Building one from user input (presets, JSON files, validation) is the edge's job:
`delvjax.envs._presets`.
"""

from __future__ import annotations

import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from .types import Real

DEFAULT_ARENA = (0.0, 0.0, 1000.0, 1000.0)
DEFAULT_HOME = (500.0, 500.0)


class Name:
    """An environment's name as compiled programs see it: every `Name` equals every other and they hash
    alike, so jit, vmap, the compilation caches and tree operations treat scenes that differ only in
    name as one program (no recompilation per environment, no stripping of names before a call).
    The text is `Env.name`; only this class's own comparisons ignore it."""

    __slots__ = ("text",)

    def __init__(self, text: str) -> None:
        self.text = str(text)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Name)

    def __hash__(self) -> int:
        return hash(Name)

    def __repr__(self) -> str:
        return repr(self.text)


class Env(eqx.Module):
    """landmarks: (L, 3) [x, y, r] cm; valid: (L,) bool; home: (2,); arena: (4,) [xmin, ymin, xmax, ymax];
    name: a label for outputs and figures, which compiled programs ignore (`Name`)."""

    landmarks: Array
    valid: Array
    home: Array
    arena: Array
    label: Name = eqx.field(static=True)

    def __init__(self, landmarks: Array, valid: Array, home: Array, arena: Array, name: str = "env") -> None:
        self.landmarks, self.valid, self.home, self.arena = landmarks, valid, home, arena
        self.label = Name(name)

    @property
    def name(self) -> str:
        return self.label.text

    @property
    def n_landmarks(self) -> int:
        return int(np.sum(np.asarray(self.valid)))

    def arrays(self) -> "Env":
        """The same scene named "env". Not needed before a jitted call (names never recompile, `Name`);
        kept for callers of earlier releases and for digests that should not depend on the name."""
        return Env(self.landmarks, self.valid, self.home, self.arena)


def stack_envs(envs: list[Env]) -> Env:
    """One batched `Env` (leading axis = environment) from envs of equal padded size; it takes the
    first one's name."""
    return jax.tree.map(lambda *leaves: jnp.stack(leaves), *envs)


def rotation_mismatch(env: Env, angles_deg=(90.0, 180.0, 270.0)) -> dict[float, float]:
    """How far each rotation of the layout about home is from mapping it onto itself (docs/model.md §6).

    For each angle: rotate the landmark centres about home and return the bottleneck distance
    (cm) to the original centres, i.e. the smallest d such that a one-to-one matching of the
    rotated to the original centres moves none by more than d. 0 for a layout with that
    rotational symmetry (env2, ring4 at 90 deg); env1 is asymmetric: > `ASYMMETRY_CM` for all three.
    """
    from scipy.sparse import csr_matrix  # scipy: loaded only where this is used, so that `import delvjax` stays light
    from scipy.sparse.csgraph import (
        maximum_bipartite_matching,
    )  # scipy: loaded only where this is used, so that `import delvjax` stays light

    pts = np.asarray(env.landmarks, float)[np.asarray(env.valid), :2]
    rel = pts - np.asarray(env.home, float)
    out = {}
    for deg in angles_deg:  # a handful of landmarks: input analysis, not a hot path
        a = math.radians(deg)
        rot = rel @ np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
        dist = np.linalg.norm(rot[:, None, :] - rel[None, :, :], axis=-1)
        best = float(dist.max())
        for t in np.unique(dist):  # smallest threshold with a perfect matching
            match = maximum_bipartite_matching(csr_matrix(dist <= t), perm_type="column")
            if np.all(match >= 0):
                best = float(t)
                break
        out[float(deg)] = best
    return out


# docs/model.md §6 "no rotation by a multiple of 90 degrees nearly maps it onto itself", in numbers:
# every rotation_mismatch of env1 exceeds this (cm); the first env1 layout had 63 cm.
ASYMMETRY_CM = 80.0


def clear_of_landmarks(env: Env, pos: Array, clearance: Real, margin: Real = 0.0) -> Array:
    """At least `margin` inside the arena and farther than r + clearance + margin from every
    landmark centre; pos (..., 2). margin 0 is the grid rule of docs/model.md §5 (grid points
    and release points); margin d keeps a first move, whatever its heading, clear."""
    a = env.arena
    inside = (
        (pos[..., 0] >= a[0] + margin)
        & (pos[..., 0] <= a[2] - margin)
        & (pos[..., 1] >= a[1] + margin)
        & (pos[..., 1] <= a[3] - margin)
    )
    dist = jnp.sqrt(jnp.sum((pos[..., None, :] - env.landmarks[:, :2]) ** 2, axis=-1))
    near = jnp.any(env.valid & (dist <= env.landmarks[:, 2] + clearance + margin), axis=-1)
    return inside & ~near
