"""Predictive image matching, "warping" (Franz et al. 1998, Möller 2009; thesis §4.2; docs/model.md §4.3).

The home snapshot S (the sensor's channel of `home.start`) is warped to predict the
current view C (`view.end`) for every hypothesis: movement direction alpha (home frame),
rotation psi (current heading minus alpha_r) and rho = d / r (every landmark at the same
distance r from home):

    C_pred(phi) = S(g - asin(rho * sin(g - alpha))),   g = phi + psi,

sampled at the nearest pixel. The distance sum_phi |C_pred(phi) - C(phi)| is searched over
alpha = 2 pi a / n_alpha, rho = rho_min .. rho_max (n_rho values) and psi = 2 pi m / n_psi;
the first minimum in (alpha, rho, psi) order (alpha outermost, psi innermost) wins. Home
direction in the agent frame: alpha + pi - psi. Defaults 72 x 15 x 72 (thesis §4.2).

Nearest pixel, the rule shared with the NumPy twin: index = round(theta * n / (2 pi)) mod n,
round half to even, theta in float64 (NumPy, at trace time). Over the default hypotheses no
theta * n / (2 pi) lies within 1.9e-5 of a half-integer, so float64 rounding is unambiguous.

How it is fast (all exact):
* psi is a whole-pixel rotation (n_psi must divide n_pix): C_pred(phi) = P_{alpha,rho}(phi + psi)
  with P_{alpha,rho}(g) = S(index[alpha, rho, g]). The table of predicted images P depends on
  the home snapshot only; under the per-point `vmap` of a map the home record is unbatched,
  so P is built once per map, not per point.
* `mask`: sum |P - C| over 0/1 pixels is a Hamming distance. P rows and the n_psi rotations
  of C are packed into 32-bit words (ceil(n_pix / 32)), so one hypothesis costs
  ceil(n_pix / 32) xor + population-count + add, vectorised over (alpha, rho). The first
  minimum is exact integer arithmetic: key = distance << bits | m, the smallest key.
* `gray`: a direct float32 sum of absolute differences over the same (alpha, rho) x psi grid.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np
from jax import Array

from ..errors import InputError
from ..geometry import TWO_PI, wrap
from ..search import first_argmin
from ..sensing import UnitMove
from ..settings import setting
from .base import HomingMethod

WORD_BITS = 32


def check_hypotheses(config: "Warping", n_pix: int) -> None:
    """Raise `InputError` unless the hypothesis grid is usable on `n_pix`-pixel rings: the relations
    between the settings, declared here once (the edge calls it through `Warping.check_input` before
    any work; the search again at trace time)."""
    for name in ("n_alpha", "n_psi", "n_rho"):
        value = getattr(config, name)
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise InputError(name, value, "must be an integer >= 1")
    if not 0.0 < config.rho_min < 1.0:
        raise InputError("rho_min", config.rho_min, "must be in (0, 1)")
    if not config.rho_min <= config.rho_max < 1.0:
        raise InputError("rho_max", config.rho_max, f"must be in [rho_min = {config.rho_min}, 1)")
    if n_pix % config.n_psi:
        raise InputError(
            "n_psi", config.n_psi, f"must divide n_pix = {n_pix} (psi hypotheses are whole-pixel rotations)"
        )
    if (n_pix + 1) << max(1, (config.n_psi - 1).bit_length()) >= 2**31:
        raise InputError("n_psi", config.n_psi, "too large: the search key distance << bits | psi must fit in int32")


def rho_values(config: "Warping") -> np.ndarray:
    """(n_rho,) float64: rho_min + i * (rho_max - rho_min) / (n_rho - 1); rho_min alone if n_rho = 1."""
    if config.n_rho == 1:
        return np.array([config.rho_min])
    i = np.arange(config.n_rho)
    return config.rho_min + i * (config.rho_max - config.rho_min) / (config.n_rho - 1)


def warp_indices(config: "Warping", n: int) -> np.ndarray:
    """(n_alpha * n_rho, n_pix) int32: index[alpha, rho, g], the nearest S pixel of
    g - asin(rho * sin(g - alpha)) at g = 2 pi g / n; rows in (alpha, rho) order. Float64."""
    g = TWO_PI * np.arange(n) / n
    alpha = TWO_PI * np.arange(config.n_alpha) / config.n_alpha
    rho = rho_values(config)
    theta = g[None, None, :] - np.arcsin(rho[None, :, None] * np.sin(g[None, None, :] - alpha[:, None, None]))
    index = np.mod(np.rint(theta * n / TWO_PI).astype(np.int64), n)
    return index.reshape(config.n_alpha * config.n_rho, n).astype(np.int32)


def pack_bits(bits: Array) -> Array:
    """(..., n) bool -> (..., ceil(n / 32)) uint32; pixel j is bit j % 32 of word j // 32, padding 0."""
    n = bits.shape[-1]
    words = -(-n // WORD_BITS)
    padded = jnp.pad(bits, [(0, 0)] * (bits.ndim - 1) + [(0, words * WORD_BITS - n)])
    b = padded.reshape(*bits.shape[:-1], words, WORD_BITS).astype(jnp.uint32)
    return jnp.sum(b << jnp.arange(WORD_BITS, dtype=jnp.uint32), axis=-1, dtype=jnp.uint32)


def rotated_words(mask: Array, shifts: Array) -> Array:
    """Packed rotations of a ring mask: row m holds C_s(g) = C(g - s_m); (len(shifts), words) uint32.

    Each row is a 32-bit-aligned window of the packed doubled image, read as two
    neighbouring words shifted and or-ed; the last word keeps only its n_pix % 32 valid bits.
    """
    n = mask.shape[-1]
    words = -(-n // WORD_BITS)
    total = (-(-(2 * n + WORD_BITS * words) // WORD_BITS) + 1) * WORD_BITS
    doubled = pack_bits(jnp.pad(jnp.concatenate([mask, mask]), (0, total - 2 * n)))
    start = (n - shifts) % n  # C(g - s) = doubled[g + start]
    bit = start[:, None] + WORD_BITS * jnp.arange(words)[None, :]
    k, b = bit // WORD_BITS, (bit % WORD_BITS).astype(jnp.uint32)
    hi = jnp.where(b == 0, jnp.uint32(0), doubled[k + 1] << ((WORD_BITS - b) % WORD_BITS))
    out = (doubled[k] >> b) | hi
    tail = n - WORD_BITS * (words - 1)
    if tail < WORD_BITS:
        out = out.at[:, -1].set(out[:, -1] & jnp.uint32((1 << tail) - 1))
    return out


def hamming_search(predicted_words: Array, current_words: Array) -> tuple[Array, Array, Array]:
    """First minimum of popcount(P_ar xor C_m) over (ar, m), ar-major: (distance, ar, m).

    predicted_words: (words, n_ar) uint32, transposed so that (alpha, rho) is the vector
    lane; current_words: (n_psi, words) uint32. A scan over psi keeps, per (alpha, rho), the
    integer key distance << bits | m of its best rotation (the min of keys is the first
    minimum); the explicit sum over the few words is one vectorised elementwise loop.
    """
    n_psi, words = current_words.shape
    n_ar = predicted_words.shape[1]
    bits = max(1, (n_psi - 1).bit_length())  # key = distance << bits | m

    def rotation(best: Array, xs: tuple[Array, Array]) -> tuple[Array, None]:
        q, m = xs
        dist = sum(jax.lax.population_count(q[w] ^ predicted_words[w]).astype(jnp.int32) for w in range(words))
        return jnp.minimum(best, (dist << bits) | m), None

    init = jnp.full((n_ar,), jnp.iinfo(jnp.int32).max, jnp.int32)
    key, _ = jax.lax.scan(rotation, init, (current_words, jnp.arange(n_psi, dtype=jnp.int32)))
    ar = first_argmin(key >> bits)
    return key[ar] >> bits, ar, key[ar] & ((1 << bits) - 1)


SAD_BLOCK = 24  # pixels summed per step of the gray search (an unrolled, vectorised sum)


def sad_search(predicted: Array, current: Array, shifts: Array) -> tuple[Array, Array, Array]:
    """First minimum of sum_g |P_ar(g) - C(g - s_m)| over (ar, m), ar-major: (distance, ar, m).

    predicted: (n_ar, n) float; current: (n,); shifts: (n_psi,) pixels. Scans over psi (each
    rotation is a slice of the doubled image) and over blocks of SAD_BLOCK pixels (zero
    padding adds nothing), accumulating (n_ar,) float32 sums; per (alpha, rho) the first
    strictly smaller rotation is kept.
    """
    n_ar, n = predicted.shape
    blocks = -(-n // SAD_BLOCK)
    pad = blocks * SAD_BLOCK - n
    p_blocks = jnp.pad(predicted.T.astype(jnp.float32), ((0, pad), (0, 0))).reshape(blocks, SAD_BLOCK, n_ar)
    doubled = jnp.tile(current.astype(jnp.float32), 2)

    def block_sum(acc: Array, xs: tuple[Array, Array]) -> tuple[Array, None]:
        p, c = xs
        return acc + sum(jnp.abs(p[k] - c[k]) for k in range(SAD_BLOCK)), None

    def rotation(carry: tuple[Array, Array], m: Array) -> tuple[tuple[Array, Array], None]:
        best, best_m = carry
        rolled = jax.lax.dynamic_slice(doubled, ((n - shifts[m]) % n,), (n,))  # C(g - s_m)
        rolled = jnp.pad(rolled, (0, pad)).reshape(blocks, SAD_BLOCK)
        dist, _ = jax.lax.scan(block_sum, jnp.zeros((n_ar,), jnp.float32), (p_blocks, rolled))
        better = dist < best
        return (jnp.where(better, dist, best), jnp.where(better, m, best_m)), None

    init = (jnp.full((n_ar,), jnp.inf, jnp.float32), jnp.zeros((n_ar,), jnp.int32))
    (best, best_m), _ = jax.lax.scan(rotation, init, jnp.arange(shifts.shape[0], dtype=jnp.int32))
    ar = first_argmin(best)
    return best[ar], ar, best_m[ar]


def search(home_image: Array, view_image: Array, config: "Warping") -> tuple[Array, Array, Array, Array]:
    """docs/model.md §4.3 search for one view: (minimum distance, alpha index, rho index, psi index).

    home_image, view_image: (n_pix,) `mask` (bool) or `gray` (float) ring images.
    """
    n = home_image.shape[-1]
    check_hypotheses(config, n)
    index = jnp.asarray(warp_indices(config, n))  # constant (n_ar, n_pix)
    shifts = jnp.arange(config.n_psi, dtype=jnp.int32) * (n // config.n_psi)
    if home_image.dtype == jnp.bool_:
        predicted = pack_bits(home_image.astype(bool)[index]).T  # (words, n_ar), per map
        dist, ar, m = hamming_search(predicted, rotated_words(view_image.astype(bool), shifts))
        dist = dist.astype(jnp.float32)
    else:
        dist, ar, m = sad_search(home_image[index], view_image, shifts)
    return dist, ar // config.n_rho, ar % config.n_rho, m


class Warping(HomingMethod):
    """Warping homing direction alpha + pi - psi in the agent frame (docs/model.md §4.3), on the
    sensor's channel; no compass. Hypotheses: n_alpha movement directions, n_psi rotations (must
    divide the ring width), n_rho values of rho = d / r from rho_min to rho_max.

    Invalid (NaN) when the home image is uniform: then every hypothesis predicts the same
    image and the search carries no information.
    """

    n_alpha: int = setting(72, static=True, check="positive_int", limit=3_600, help="movement directions alpha")
    n_psi: int = setting(72, static=True, check="positive_int", help="rotations psi, must divide the ring's pixels")
    n_rho: int = setting(15, static=True, check="positive_int", limit=1_000, help="values of rho = d/r")
    rho_min: float = setting(0.10, static=True, check="unit_interval", help="smallest rho")
    rho_max: float = setting(0.80, static=True, check="unit_interval", help="largest rho, < 1")

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        s, c = home.start.image, view.end.image
        _, a, _, m = search(s, c, self)
        angle = wrap(TWO_PI * a / self.n_alpha + math.pi - TWO_PI * m / self.n_psi)
        valid = jnp.any(s != s[0])
        return jnp.where(valid, angle, jnp.nan), valid

    def reads_image(self) -> bool:
        return True

    def reads_gray(self, channel: str) -> bool:
        return channel == "gray"

    def check_input(self, n_pix: int) -> None:
        """n_psi divides n_pix, rho_min <= rho_max (`check_hypotheses`)."""
        check_hypotheses(self, n_pix)
