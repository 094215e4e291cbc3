"""A database whose headings are read with the wrong convention says so, naming the flags that fix it
(issue 53 point 7: a delvjax database's own compass headings, 270, copied into a positions.csv folder
gave 96° errors without a word)."""

from __future__ import annotations

import numpy as np

from delvjax.images._conventions import BOB, PLAIN, mismatch


def _turned(stored: np.ndarray, true, read, rng) -> np.ndarray:
    """Signed homing errors of views turned by reading `stored` with `read` instead of `true`."""
    turn = read.column0_deg(stored, 360) - true.column0_deg(stored, 360)
    return np.mod(turn + rng.normal(0, 8, stored.size) + 180.0, 360.0) - 180.0


def test_compass_headings_read_as_a_positions_csv_folders_name_the_flags_that_fix_them():
    rng = np.random.default_rng(0)
    for stored in (np.full(99, 270.0), rng.uniform(0, 360, 99)):  # a rendered grid's, a route's
        hint = mismatch(_turned(stored, BOB, PLAIN, rng), stored, 360, PLAIN)
        assert hint and "--heading-convention compass --heading-column centre" in hint, hint
        assert "--columns" not in hint  # the column order was right: not named


def test_small_or_patternless_errors_say_nothing():
    rng = np.random.default_rng(1)
    stored = np.full(99, 270.0)
    assert mismatch(rng.normal(0, 10, 99), stored, 360, PLAIN) is None  # right conventions: small errors
    assert mismatch(rng.uniform(-180, 180, 99), stored, 360, PLAIN) is None  # a bad method, not a turn
    assert mismatch(np.full(5, 90.0), stored[:5], 360, PLAIN) is None  # too few points to tell
