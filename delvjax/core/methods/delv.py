"""DELV: distance-estimated landmark vectors and arrangement matching (thesis §3.2.4, §3.3.1; docs/model.md §3.4)."""

from __future__ import annotations

from collections.abc import Callable

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..errors import InputError
from ..estimation import TIE_RAD, DistanceSettings, current_vectors, reference_vectors
from ..geometry import TWO_PI, angle_of, rotate, safe_norm, wrap
from ..search import first_argmin
from ..sensing import UnitMove
from ..settings import setting
from ..types import (
    BlobFlags,
    Blobs,
    BlobVectors,
    CurrentFlags,
    CurrentVectors,
    Direction,
    Hypotheses,
    Move,
    Pairing,
    PairingFlags,
    Point,
    Real,
    RowFlags,
    Scalar,
)
from .base import HomingMethod
from .heading import HeadingSource
from .pairing import shift_pairs
from .rotations import MIN_SLOTS, best_rotated

ORDERS = ("home", "agent")  # docs/model.md §3.3: the frame in which the current landmark list is sorted


def list_offsets(bearing: Blobs, valid: BlobFlags, alphas: Hypotheses) -> Array:
    """docs/model.md §3.3 order: for each heading hypothesis alpha (A,), the index of the current
    blob that comes first when the list is sorted by its home-frame bearing (beta_j + alpha) mod 2 pi.

    The blobs are sorted by agent-frame bearing beta in [0, 2 pi), so the home-frame list is the
    agent-frame list rotated to start at this index: (A,) int (0 where no blob is valid).
    The table is laid out (B, A) and reduced over the blobs: a reduction over a short minor axis
    does not vectorise on XLA's CPU (with the (A, B) layout this function took 60 us of 128-wide
    vmap per item, now about 5; benchmarks/bench_delv_offsets.py)."""
    # + TIE_RAD: bearings (half-pixel lattice) plus a whole-degree heading often land exactly on 2 pi;
    # float rounding must not decide whether such a blob starts or ends the list
    if alphas.shape[0] == 1:  # a heading estimate (any angle): one remainder per blob
        home_frame = jnp.mod(bearing[:, None] + alphas[None, :] + TIE_RAD, TWO_PI)
    else:
        home_frame = mod_two_pi_of_sum(bearing, alphas, TIE_RAD)
    return first_argmin(jnp.where(valid[:, None], home_frame, jnp.inf), axis=0)


def mod_two_pi_of_sum(bearing: Blobs, alphas: Hypotheses, tie: float) -> Array:
    """`jnp.mod(bearing[:, None] + alphas[None, :] + tie, TWO_PI)`, (B, A), bit for bit where the
    bearings and hypotheses lie in [0, 2 pi) (sorted blobs, `sensing.sort_blobs`; the no-compass
    grid), without a (B, A) float remainder (a libm call per element on XLA's CPU: 27 us of a
    128-wide vmap per item against 2).
    Both inputs are first reduced to [0, 2 pi] (B + A remainders, the identity on that range), so
    the sum x lies in [0, 3 * 2 pi) for a tie below 2 pi, where fmod(x, y) is x - y or x - 2 y, each
    subtraction exact (Sterbenz: y <= x <= 2 y), and x >= 0, so `jnp.mod` adds nothing to the
    remainder. Tested against `jnp.mod`."""
    y = jnp.asarray(TWO_PI, bearing.dtype)
    # the barrier keeps XLA from folding `+ tie` and `- y` into one constant (another rounding)
    x = jax.lax.optimization_barrier(jnp.mod(bearing, y)[:, None] + jnp.mod(alphas, y)[None, :] + tie)
    x = jnp.where(x >= y, x - y, x)
    return jnp.where(x >= y, x - y, x)


def rotated_rows(
    cur_idx: Pairing, cur_valid: CurrentFlags, alphas: Hypotheses, offsets: Array | None
) -> tuple[Array, Array]:
    """The current indices of every pairing when the current list starts at another blob.

    `cur_idx` (K, S) indexes the list as sorted (agent frame). Returns (rows (R, K, S), row_of (A,)):
    hypothesis a pairs through rows[row_of[a]]. `offsets` None keeps the list as sorted (R = 1);
    with one hypothesis (a compass) the list is rotated once (R = 1); with A hypotheses each
    rotation r = 0..B-1 is a row block and row_of = offsets (docs/model.md §3.3-3.4): B^3 indices, the
    direct table, used below `rotations.MIN_SLOTS` slots (`rotations.best_rotated` above)."""
    if offsets is None:
        return cur_idx[None], jnp.zeros(alphas.shape, jnp.int32)
    m = jnp.maximum(jnp.sum(cur_valid), 1)
    last = cur_valid.shape[0] - 1
    if alphas.shape[0] == 1:
        return jnp.minimum((cur_idx + offsets[0]) % m, last)[None], jnp.zeros((1,), jnp.int32)
    rot = jnp.arange(cur_valid.shape[0])[:, None, None]
    return jnp.minimum((cur_idx[None] + rot) % m, last), offsets.astype(jnp.int32)


def match_arrangement(
    ref_v: BlobVectors,
    ref_valid: BlobFlags,
    cur_v: CurrentVectors,
    cur_valid: CurrentFlags,
    alphas: Hypotheses,
    offsets: Array | None = None,
) -> tuple[Point, Scalar, Scalar, Array]:
    """Best cyclic shift k and heading hypothesis alpha (Eqs 3.4-3.6): (p (2,), alpha, var, n_pairs).

    For each k and alpha: e_i = V^R_i - Rot(alpha) V_j(i), p = mean e_i, var = sum |e_i - p|^2;
    the first minimum in k-major order wins. With centred pair vectors a'_i, b'_i,
    var(alpha) = sum |a'|^2 + |b'|^2 - 2 Re(e^{i alpha} sum conj(a') b'), so all
    alphas of one shift cost two multiply-adds each.
    ref_v: (B, 2) home frame; cur_v: (B, 2) agent frame; alphas: (A,) radians; offsets: (A,) the
    first current blob of the home-frame list under each alpha (`list_offsets`), None to pair the
    list in its agent-frame order (docs/model.md §3.3).
    """
    p, alpha, var, n, _ = search_pairings(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
    return p, alpha, var, n


def search_pairings(
    ref_v: BlobVectors,
    ref_valid: BlobFlags,
    cur_v: CurrentVectors,
    cur_valid: CurrentFlags,
    alphas: Hypotheses,
    offsets: Array | None = None,
) -> tuple[Point, Scalar, Scalar, Array, tuple[Array, Array, Array]]:
    """`match_arrangement` and the winning pairing: (p, alpha, var, n, (ref_row (S,), cur_row (S,),
    pair_ok_row (S,))). Without a compass in the home-frame order (A > 1 hypotheses, each its own
    rotation of the list) and with at least `rotations.MIN_SLOTS` slots the search is
    `rotations.best_rotated`, O(B^2 + B A); below, the direct table of every rotation
    (`pairing_table`, O(B^3 + B A)); with a compass or the agent-frame order one block of it."""
    ref_idx, cur_idx, pair_ok, shift_ok = shift_pairs(ref_valid, cur_valid)
    n = jnp.sum(pair_ok[0])
    if offsets is not None and alphas.shape[0] > 1 and ref_idx.shape[0] >= MIN_SLOTS:
        pairs = (ref_idx, cur_idx, pair_ok, shift_ok)
        p, alpha, var, rows = best_rotated(
            ref_v, ref_valid, cur_v, cur_valid, alphas, offsets.astype(jnp.int32), pairs, n
        )
        return p, alpha, var, n, rows
    rows, row_of = rotated_rows(cur_idx, cur_valid, alphas, offsets)
    var, a_mean, b_mean = pairing_table(ref_v, cur_v, ref_idx, rows, pair_ok, shift_ok, n, alphas, row_of)
    h, a = best_index(var)
    alpha = alphas[a]
    block = 0 if b_mean.shape[0] == 1 else row_of[a]
    p = a_mean[h] - rotate(b_mean[block, h], alpha)
    return p, alpha, var[h, a], n, (ref_idx[h], rows[block, h], pair_ok[h])


def pairing_table(
    ref_v: BlobVectors,
    cur_v: CurrentVectors,
    ref_idx: Pairing,
    cur_idx: Array,
    pair_ok: PairingFlags,
    row_ok: RowFlags,
    n: Array,
    alphas: Hypotheses,
    row_of: Array | None = None,
) -> tuple[Array, Array, Array]:
    """var of every pairing (row) x heading hypothesis, (H, A) (inf on rows that are not row_ok), and
    the rows' mean reference vectors (H, 2) and mean current vectors (R, H, 2).

    Row h pairs ref_v[ref_idx[h, s]] with cur_v[cur_idx[r, h, s]] where pair_ok[h, s]; hypothesis a
    reads the block r = row_of[a] (`rotated_rows`; a (H, S) `cur_idx` is one block, used by every
    alpha). n is the number of pairs. With centred pair vectors a'_i, b'_i, var(alpha) = sum |a'|^2 +
    |b'|^2 - 2 Re(e^{i alpha} sum conj(a') b'), so all alphas of one row cost two multiply-adds each
    (Eqs 3.4-3.6; docs/model.md §3.4).
    """
    if cur_idx.ndim == 2:
        cur_idx = cur_idx[None]
    w = pair_ok.astype(ref_v.dtype)[..., None]  # (H, S, 1)
    # one division, written out: XLA compiles x / n as x * (1 / n) in some programs only (docs/reproduce.md "Chunking")
    inv_n = 1.0 / jnp.maximum(n, 1).astype(ref_v.dtype)
    a = ref_v[ref_idx] * w  # (H, S, 2)
    b = cur_v[cur_idx] * w  # (R, H, S, 2)
    a_mean = jnp.sum(a, axis=1) * inv_n  # (H, 2)
    b_mean = jnp.sum(b, axis=2) * inv_n  # (R, H, 2)
    a_c = (a - a_mean[:, None]) * w
    b_c = (b - b_mean[:, :, None]) * w
    const = jnp.sum(a_c * a_c + b_c * b_c, axis=(2, 3))  # (R, H)
    z_re = jnp.sum(a_c[..., 0] * b_c[..., 0] + a_c[..., 1] * b_c[..., 1], axis=2)
    z_im = jnp.sum(a_c[..., 0] * b_c[..., 1] - a_c[..., 1] * b_c[..., 0], axis=2)
    if cur_idx.shape[0] == 1:  # one block: every alpha reads it
        const, z_re, z_im = const[0][:, None], z_re[0][:, None], z_im[0][:, None]
    else:  # (H, A): hypothesis a reads block row_of[a]
        const, z_re, z_im = const[row_of].T, z_re[row_of].T, z_im[row_of].T
    var = const - 2.0 * (jnp.cos(alphas)[None, :] * z_re - jnp.sin(alphas)[None, :] * z_im)
    return jnp.where(row_ok[:, None], var, jnp.inf), a_mean, b_mean


def best_index(var: Array) -> tuple[Array, Array]:
    """(row, hypothesis) of the first minimum of a `pairing_table` var, in row-major order."""
    best = first_argmin(var.reshape(-1))
    return best // var.shape[1], best % var.shape[1]


def best_pairing(
    ref_v: BlobVectors,
    cur_v: CurrentVectors,
    ref_idx: Pairing,
    cur_idx: Array,
    pair_ok: PairingFlags,
    row_ok: RowFlags,
    n: Array,
    alphas: Hypotheses,
    row_of: Array | None = None,
) -> tuple[Point, Scalar, Scalar]:
    """The first minimum of var over pairings (rows) x heading hypotheses (`pairing_table`): (p (2,), alpha, var)."""
    var, a_mean, b_mean = pairing_table(ref_v, cur_v, ref_idx, cur_idx, pair_ok, row_ok, n, alphas, row_of)
    h_best, a_best = best_index(var)
    alpha = alphas[a_best]
    block = 0 if b_mean.shape[0] == 1 else row_of[a_best]
    p = a_mean[h_best] - rotate(b_mean[block, h_best], alpha)
    return p, alpha, var[h_best, a_best]


def delv_direction(*args, **kwargs) -> Direction:
    """Homing direction from the best (k, alpha) of `match`; invalid (NaN) when n < `min_pairs` or |p| = 0.

    `min_pairs` is static: 2 without a compass (one pair fits every heading), 1 with a
    heading estimate (one pair fixes p = V^R_i - Rot(alpha) V_j; with n = 1 every shift
    has var = 0 and the first k wins), docs/model.md §3.4. `order` (static): "home" sorts the
    current list by home-frame bearing under each hypothesis (SPEC, docs/model.md §3.3), "agent"
    keeps the agent-frame order (the earlier rule, an option).
    """
    angle, valid, _ = delv_fit(*args, **kwargs)
    return angle, valid


def delv_fit(
    home: UnitMove,
    view: UnitMove,
    settings: DistanceSettings,
    alphas: Hypotheses,
    min_pairs: int,
    match: Callable = match_arrangement,
    order: str = "home",
) -> tuple[Array, Array, dict]:
    """Homing direction from the best (k, alpha) of `match` (`delv_direction`, its arguments) and how
    well the arrangement matched: (angle, valid, fit) with fit the
    residual sum of squares of the best pairing (Eq 3.5, cm^2) `var`, its pairs `n` and the
    landmark counts `n_home`, `n_current` (the hybrid of docs/model.md §4.8 reads them)."""
    ref_v, ref_valid = reference_vectors(home, settings)
    cur_v, cur_valid = current_vectors(view, settings)
    offsets = list_offsets(view.end.bearing, cur_valid, alphas) if order == "home" else None
    p, alpha, var, n = match(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)
    valid = (n >= min_pairs) & (n >= 1) & (safe_norm(p) > 0)
    angle = wrap(angle_of(-p) - alpha)
    fit = {"var": var, "n": n, "n_home": jnp.sum(ref_valid), "n_current": jnp.sum(cur_valid)}
    return jnp.where(valid, angle, jnp.nan), valid, fit


class DELV(HomingMethod):
    """DELV (thesis ch. 3-5; docs/model.md §3): distances from the unit movement, arrangement matching.

    levels: quantization levels Q (0, or None when constructing, = continuous; Eq 3.17), a
            traced leaf, so every Q shares one program; scale: quantization scale a, cm;
    r_max:  cap of estimated distances, cm (§3.1);
    heading: None searches all cyclic shifts x `n_heading` hypotheses alpha = 2 pi a / n_heading
            (no compass, thesis ch. 3-4); a heading source (`Compass()`, `VisualCompass()`)
            fixes alpha, and only the shift is searched (thesis ch. 5); one visible landmark
            then suffices (§3.4);
    order:  the frame in which the current landmark list is sorted before the cyclic pairing
            (docs/model.md §3.3): "home" (default: by home-frame bearing under each heading
            hypothesis, as ACV sorts and as thesis Fig 3.4 draws it) or "agent" (by agent-frame
            bearing, the earlier rule; with occlusion its wrap point moves with the heading).
    """

    levels: Real = setting(
        0,
        converter=lambda q: 0 if q is None else q,
        check="positive_int",
        help="distance quantization levels Q >= 1 (Eq 3.17)",
        shown_default="continuous",
    )
    scale: Real = setting(1000.0, check="positive", unit="cm", help="quantization scale a")
    r_max: Real = setting(2000.0, check="positive", unit="cm", help="cap of estimated distances")
    heading: HeadingSource | None = None
    n_heading: int = setting(
        360, static=True, check="positive_int", limit=36_000, help="heading hypotheses without a compass"
    )
    order: str = eqx.field(static=True, default="home")

    def __check_init__(self):
        if self.order not in ORDERS:
            raise InputError("order", self.order, f"must be one of {', '.join(ORDERS)}")

    def alphas(self, home: Move, view: Move) -> Hypotheses:
        """The heading hypotheses: all n_heading of them, or the heading source's estimate."""
        if self.heading is None:
            return TWO_PI * jnp.arange(self.n_heading, dtype=jnp.float32) / self.n_heading
        return jnp.reshape(self.heading(home, view), (1,))

    def match(
        self,
        ref_v: BlobVectors,
        ref_valid: BlobFlags,
        cur_v: CurrentVectors,
        cur_valid: CurrentFlags,
        alphas: Hypotheses,
        offsets: Array | None = None,
    ) -> tuple[Point, Scalar, Scalar, Array]:
        """The arrangement search (`match_arrangement`): (p, alpha, var, n)."""
        return match_arrangement(ref_v, ref_valid, cur_v, cur_valid, alphas, offsets)

    def __call__(self, home: UnitMove, view: UnitMove) -> Direction:
        angle, valid, _ = self.fit(home, view)
        return angle, valid

    def fit(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array, dict]:
        """(angle, valid, how well it matched): `delv_fit` with this module's settings."""
        min_pairs = 1 if self.heading is not None else 2
        return delv_fit(home, view, self, self.alphas(home, view), min_pairs, self.match, self.order)

    def reads_start_view(self) -> bool:
        return True

    def reads_gray(self, channel: str) -> bool:
        return bool(self.heading is not None and self.heading.reads_gray)
