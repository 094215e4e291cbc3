"""The estimator of the `ensemble_settings` study: how near each combination of unstated settings brings our
distribution over the members to the thesis's numbers, its uncertainty from resampling the members, and which
settings the thesis's numbers identify (docs/reproduce.md "Which settings the thesis's numbers imply").
Plain NumPy on the numbers the study's rollouts made; no array program here.

Score of a combination: the mean over the thesis's numbers of the continuous ranked probability score (CRPS)
of our members' values against the thesis's value, in percentage points: E|X - t| - E|X - X'| / 2 over two
different members X, X' (the mean |ours - thesis| of the old fit generalised from one world to a distribution: a
distribution that is near the thesis's number and narrow scores low, a wide one pays for its width).
Uncertainty: the members are resampled with replacement (member i is the i-th world of every family, under
the same seed in every combination, so every combination is scored on the same resample)."""

from __future__ import annotations

import numpy as np

SHARE = 80.0  # %: a setting is identified when one value is best in at least this share of the resamples
BAND = (5.0, 95.0)  # percentiles of the resamples: the band of a score
# percentile of the resamples' gap to the best value that must lie above 0 for a value to be excluded: a
# two-sided 1 % test per setting, about 5 % over the four settings (Bonferroni). At the 5th percentile, means
# over an orthogonal array of 12 members called a setting without effect identified in 10-15 % of synthetic
# draws (the tests' `synthetic`); profiles at 0.5 over 8 members, in none of 100 per setting
GAP = 0.5
MIN_MEMBERS = 5  # fewer members (a preview) identify nothing: most of their resamples repeat one or two members
TIE = 1e-9  # points: scores nearer than this are a tie (a setting the numbers do not depend on)


def resample_weights(members: int, draws: int, seed: int) -> np.ndarray:
    """(1 + draws, members) counts: row 0 the members themselves (all ones), then `draws` resamples with
    replacement, each row the number of times each member was drawn (summing to `members`)."""
    rng = np.random.default_rng(seed)
    picks = rng.integers(0, members, size=(draws, members))
    counts = (picks[:, :, None] == np.arange(members)).sum(axis=1)
    return np.concatenate([np.ones((1, members)), counts]).astype(float)


def crps(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    """CRPS of each number's members (..., M) against the thesis's values t (...), in the units of x: the fair
    form, E|X - t| - E|X - X'| / 2 with X, X' two different members (one member: |x - t|)."""
    m = x.shape[-1]
    near = np.abs(x - t[..., None]).mean(axis=-1)
    spread = np.abs(x[..., :, None] - x[..., None, :]).sum(axis=(-2, -1)) / max(m * (m - 1), 1)
    return near - 0.5 * spread


def scores(x: np.ndarray, t: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """(W, C): the mean CRPS over the N numbers of each of C combinations, x (C, N, M) our numbers per
    combination, thesis number and member, t (N,) the thesis's, under each row of weights (W, M) (member
    counts summing to M: `resample_weights`). Row 0 of ones is `crps(x, t).mean(axis=1)`. In a resample the
    spread is over pairs of different members (a member drawn twice is no pair: its copies would make every
    resample look narrower than the sample, and the narrower combinations more so)."""
    n, m = x.shape[1], x.shape[2]
    near = np.abs(x - t[None, :, None]).sum(axis=1)  # (C, M): |x - t| summed over the numbers
    spread = np.abs(x[:, :, :, None] - x[:, :, None, :]).sum(axis=1)  # (C, M, M), 0 on the diagonal
    pairs = np.maximum(m * m - (weights**2).sum(axis=1), 1.0)  # (W,): ordered pairs of different members
    first = np.einsum("cm,wm->wc", near, weights) / m
    return (first - 0.5 * np.einsum("cij,wi,wj->wc", spread, weights, weights) / pairs[:, None]) / n


def percentile_offsets(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    """(C, N): |the thesis number's percentile among the members - 50| (ties half): 0 at our median, 50
    outside every member's value."""
    below = (x < t[None, :, None]).mean(axis=-1) + 0.5 * (x == t[None, :, None]).mean(axis=-1)
    return np.abs(100.0 * below - 50.0)


def best_shares(values: np.ndarray) -> np.ndarray:
    """(K,): the share (%) of rows of values (R, K) in which each column is smallest, ties shared."""
    tied = values <= values.min(axis=1, keepdims=True) + TIE
    return 100.0 * (tied / tied.sum(axis=1, keepdims=True)).mean(axis=0)


def gap_bounds(values: np.ndarray, best: int) -> np.ndarray:
    """(K,): the GAP percentile over the resamples of each column's gap to column `best` (values (R, K), row =
    resample): above 0 means the column is worse in at least 99.5 % of the resamples."""
    gaps = values - values[:, [best]]
    low = np.percentile(gaps, GAP, axis=0)
    return np.where(np.abs(low) <= TIE, 0.0, low)


def combinations(s: np.ndarray) -> dict:
    """The combinations' scores s (1 + R, C) (row 0 the sample, then the resamples): the best, the share of
    resamples each is best in, its band, and which are not distinguishable from the best (the lower bound of
    their gap to it at most 0)."""
    best = int(np.argmin(s[0]))
    lo, hi = np.percentile(s[1:], BAND, axis=0)
    low = gap_bounds(s[1:], best)
    return {
        "best": best,
        "score": s[0],
        "lo": lo,
        "hi": hi,
        "share_best": best_shares(s[1:]),
        "gap_low": low,
        "indistinct": low <= 0.0,
    }


def profiles(s: np.ndarray, levels: np.ndarray, n_values: int) -> np.ndarray:
    """(W, V): per row of s (W, C) the best (lowest) score of the combinations at each value of one setting
    (levels (C,) the value index of each combination), the others free: the setting's profile. In a full
    factorial every value meets the same combinations of the others. (A mean over them would favour a value
    that makes up for another setting's misfit: the score is V-shaped around the thesis's numbers.)"""
    at = levels[:, None] == np.arange(n_values)  # (C, V)
    return np.where(at[None], s[:, :, None], np.inf).min(axis=1)


def identify(s: np.ndarray, levels: np.ndarray, n_values: int, members: int) -> dict:
    """Whether the thesis's numbers identify one setting: its profile under the sample and every resample, the
    best value, the share of resamples where each value is best, the band of each value's score, the lower
    bound of each value's gap to the best, the values not excluded (gap bound at most 0) and the verdict:
    identified when the best value is best in at least SHARE % of the resamples and every other is excluded,
    with at least MIN_MEMBERS members."""
    prof = profiles(s, levels, n_values)
    best = int(np.argmin(prof[0]))
    share = best_shares(prof[1:])
    low = gap_bounds(prof[1:], best)
    lo, hi = np.percentile(prof[1:], BAND, axis=0)
    kept = [v for v in range(n_values) if v == best or low[v] <= 0.0]
    return {
        "best": best,
        "score": prof[0],
        "lo": lo,
        "hi": hi,
        "share_best": share,
        "gap_low": low,
        "kept": kept,
        "identified": bool(share[best] >= SHARE and kept == [best] and members >= MIN_MEMBERS),
    }


def sentence(found: dict[str, dict], names: dict[str, str], values: dict[str, list[str]], members: int) -> str:
    """The report's sentence(s) on what the thesis's numbers identify: one sentence when they identify none."""
    if members < MIN_MEMBERS:
        return f"With {members} members per world (a preview) the resamples identify no setting."
    yes = [n for n, f in found.items() if f["identified"]]
    if not yes:
        return (
            "The thesis's numbers identify none of the unstated settings: for none of them is one value best in "
            f"at least {SHARE:g} % of the member resamples with every other value worse in {100 - GAP:g} % of them."
        )
    said = [
        f"the {names[n]} ({values[n][found[n]['best']]}, best in {found[n]['share_best'][found[n]['best']]:.4g} % "
        "of the member resamples)"
        for n in yes
    ]
    text = f"The thesis's numbers identify {_join(said)}."
    no = [
        f"the {names[n]} (not excluded: {', '.join(values[n][v] for v in f['kept'])})"
        for n, f in found.items()
        if not f["identified"]
    ]
    return text + (f" They do not identify {_join(no, 'or')}." if no else "")


def _join(parts: list[str], word: str = "and") -> str:
    """'a', 'a and b', 'a, b and c' (or another joining word)."""
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + f" {word} " + parts[-1]
