"""Array shapes of the public functions and results (jaxtyping; docs/model.md §1 units).

P points, B blob slots (the padded landmark count L), L landmarks, M visibility masks,
T trials, n_pix ring pixels. Angles are radians unless a name says `_deg`.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

import numpy as np
from jax import Array
from jax.typing import ArrayLike
from jaxtyping import Bool, Float, Int

# Inputs may be NumPy arrays (the edge builds them on the host), results are JAX arrays: both pass.
Arrays = Array | np.ndarray

Scalar = Float[Arrays, ""]
# A scalar setting: a Python or NumPy number, or a traced array under jit/vmap/grad (the hints the
# test suite checks at run time, tests/conftest.py, must accept tracers where a setting is traced).
Real = ArrayLike
Flag = Bool[Arrays, ""]
Point = Float[Arrays, "2"]
Points = Float[Arrays, "P 2"]
PerPoint = Float[Arrays, "P"]
PerPointFlag = Bool[Arrays, "P"]
PerPointInt = Int[Arrays, "P"]
Ring = Float[Arrays, "n_pix"]
RingMask = Bool[Arrays, "n_pix"]
# snapshots: one, or a batch of them (an image database)
SnapRing = Float[Arrays, "*batch n_pix"]
SnapMask = Bool[Arrays, "*batch n_pix"]
SnapBlobs = Float[Arrays, "*batch B"]
SnapFlags = Bool[Arrays, "*batch B"]
Blobs = Float[Arrays, "B"]
BlobFlags = Bool[Arrays, "B"]
Masks = Bool[Arrays, "M L"]
PerTrial = Float[Arrays, "T"]
PerTrialInt = Int[Arrays, "T"]
PerTrialFlag = Bool[Arrays, "T"]
TrialPoints = Float[Arrays, "T 2"]
Direction = tuple[Scalar, Flag]  # (angle rad, NaN where invalid; valid)
# results over a grid of P cells (a sweep adds leading axes: *batch)
GridPoints = Float[Arrays, "*batch P 2"]
GridFloat = Float[Arrays, "*batch P"]
GridFlag = Bool[Arrays, "*batch P"]
# catchment: M visibility masks x P cells
MaskGridInt = Int[Arrays, "M P"]
MaskGridFloat = Float[Arrays, "M P"]
MaskGridFlag = Bool[Arrays, "M P"]
MaskGridPoints = Float[Arrays, "M P 2"]
# success rate: D release distances x n trials each
Bins = Float[Arrays, "D"]
BinTrialPoints = Float[Arrays, "D n 2"]
BinTrialFloat = Float[Arrays, "D n"]
BinTrialFlag = Bool[Arrays, "D n"]
BinTrialInt = Int[Arrays, "D n"]
# trajectories: T trials x (max_steps + 1) positions
Paths = Float[Arrays, "T S 2"]
PointBlobs = Float[Arrays, "P B"]
PointBlobFlags = Bool[Arrays, "P B"]
BlobVectors = Float[Arrays, "B 2"]  # landmark vectors, cm
CurrentVectors = Float[Arrays, "C 2"]  # the current list, which may have other slots than the reference
CurrentFlags = Bool[Arrays, "C"]
Hypotheses = Float[Arrays, "A"]  # heading hypotheses, rad
Pairing = Int[Arrays, "K S"]  # index arrays of every pairing (row) and pair (column)
PairingFlags = Bool[Arrays, "K S"]
RowFlags = Bool[Arrays, "K"]


@runtime_checkable
class Move(Protocol):
    """What a heading source reads of a unit movement: the rendered `sensing.UnitMove` and the soft
    path's analytic `soft.sensing.SoftMove` are both one (docs/differentiable.md)."""

    start: Any
    end: Any
    d_hat: Array
    psi_hat: Array
    compass: Array
