"""Array shapes of the public functions and results (jaxtyping; docs/model.md §1 units).

P points, B blob slots (the padded landmark count L), L landmarks, M visibility masks,
T trials, n_pix ring pixels. Angles are radians unless a name says `_deg`.
"""

from __future__ import annotations

from jax import Array
from jaxtyping import Bool, Float, Int

Scalar = Float[Array, ""]
Flag = Bool[Array, ""]
Point = Float[Array, "2"]
Points = Float[Array, "P 2"]
PerPoint = Float[Array, "P"]
PerPointFlag = Bool[Array, "P"]
PerPointInt = Int[Array, "P"]
Ring = Float[Array, "n_pix"]
RingMask = Bool[Array, "n_pix"]
Blobs = Float[Array, "B"]
BlobFlags = Bool[Array, "B"]
Masks = Bool[Array, "M L"]
PerTrial = Float[Array, "T"]
PerTrialInt = Int[Array, "T"]
PerTrialFlag = Bool[Array, "T"]
TrialPoints = Float[Array, "T 2"]
Direction = tuple[Scalar, Flag]  # (angle rad, NaN where invalid; valid)
# results over a grid of P cells (a sweep adds leading axes: *batch)
GridPoints = Float[Array, "*batch P 2"]
GridFloat = Float[Array, "*batch P"]
GridFlag = Bool[Array, "*batch P"]
# catchment: M visibility masks x P cells
MaskGridInt = Int[Array, "M P"]
MaskGridFloat = Float[Array, "M P"]
MaskGridFlag = Bool[Array, "M P"]
MaskGridPoints = Float[Array, "M P 2"]
# success rate: D release distances x n trials each
Bins = Float[Array, "D"]
BinTrialPoints = Float[Array, "D n 2"]
BinTrialFloat = Float[Array, "D n"]
BinTrialFlag = Bool[Array, "D n"]
BinTrialInt = Int[Array, "D n"]
# trajectories: T trials x (max_steps + 1) positions
Paths = Float[Array, "T S 2"]
PointBlobs = Float[Array, "P B"]
PointBlobFlags = Bool[Array, "P B"]
BlobVectors = Float[Array, "B 2"]  # landmark vectors, cm
Hypotheses = Float[Array, "A"]  # heading hypotheses, rad
Pairing = Int[Array, "K S"]  # index arrays of every pairing (row) and pair (column)
PairingFlags = Bool[Array, "K S"]
RowFlags = Bool[Array, "K"]
