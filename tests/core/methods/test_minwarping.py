"""MinWarping and 2D-Warping (docs/model.md §4.7) against the plain NumPy twin (tests/twins/minwarping.py),
the analytic cases (a pure rotation gives psi exactly, a pure translation alpha exactly), the promises
of the refinements, and bad input."""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.core.errors import InputError
from delvjax.core.methods import minwarping as mw
from delvjax.core.methods import scale_planes as sp
from delvjax.core.methods import warping2d as w2d
from delvjax.core.methods import warping_search as ws
from delvjax.core.methods.minwarping import MinWarping, MinWarpingCompass
from delvjax.core.methods.warping2d import Warping2D
from delvjax.core.sensing import Snapshot, UnitMove
from tests.cases.compiled import call, compiled
from tests.twins import minwarping as tw

W, H, N = 96, 12, 32  # a small panorama and hypothesis grid: the twin loops over every entry
ELEV = np.radians(30.0 - 60.0 / H * (np.arange(H) + 0.5))
SCALES = tuple(float(s) for s in sp.scale_factors(9, 2.0))


def pair(seed: int, w: int = W, h: int = H) -> tuple[np.ndarray, np.ndarray]:
    """Two smooth random panoramas (sums of a few cosines in azimuth and elevation)."""
    rng = np.random.default_rng(seed)
    az = 2 * np.pi * np.arange(w) / w
    rows = np.arange(h)[:, None]

    def image():
        out = np.zeros((h, w))
        for k in range(1, 7):
            out += rng.normal() * np.cos(k * az[None, :] + rng.uniform(0, 6.3)) * np.cos(rows * rng.uniform(0.2, 1.2))
        return ((out - out.min()) / (np.ptp(out) + 1e-9)).astype(np.float32)

    return image(), image()


@compiled
def stack(ss, cv, measure: str = "nsad", edges: bool = True):
    """`sp.stack` of the two panoramas at ELEV and SCALES."""
    return sp.stack(ss, cv, jnp.asarray(ELEV), np.array(SCALES), measure, edges)


@compiled
def quantised_stack(ss, cv, stack_type: str = "uint8", edges: bool = True):
    """The stack the search reads (`mw.quantised` of the nsad stack)."""
    return mw.quantised(stack(ss, cv, "nsad", edges), "nsad", stack_type)


inverted = compiled(sp.inverted)


@compiled
def match_table(stk):
    entries = ws.min_template(W, SCALES, 2.5, 0.0, math.inf)
    return ws.min_match(sp.arranged(stk, N, N), ws.group_steps(entries, W, N, N), N, N)


@compiled
def match_at(stk, alpha, psi):
    return ws.min_match_at(stk, ws.min_template(W, SCALES, 2.5, 0.0, math.inf), alpha, psi)


@compiled
def mw_search(s, c, cfg):
    return mw.search(s, c, jnp.asarray(ELEV, jnp.float32), cfg)


@compiled
def w2d_search(s, c, cfg):
    return w2d.search(s, c, jnp.asarray(ELEV, jnp.float32), cfg)


def jsearch(ss, cv, **settings):
    cfg = MinWarping(n_alpha=N, n_psi=N, **settings)
    a, p, v = mw_search(ss, cv, cfg)
    return int(a), int(p), int(v)


def test_the_template_is_the_twins():
    twin = sorted((x, y, s) for x, entries in tw.min_template(W, np.array(SCALES), 2.5).items() for y, s in entries)
    assert sorted(map(tuple, ws.min_template(W, SCALES, 2.5, 0.0, math.inf).tolist())) == twin
    assert len(twin) > 10 * W  # many displacements per column, not one


def test_the_stack_and_its_swap_agree_with_the_twin():
    ss, cv = pair(0)
    fwd = np.asarray(stack(ss, cv, "nsad", True))
    np.testing.assert_allclose(fwd, tw.stack(ss, cv, ELEV, np.array(SCALES)), atol=2e-6)
    # the swapped search reads the stack of the swapped images: plane S-1-s transposed
    back = tw.stack(cv, ss, ELEV, np.array(SCALES))
    np.testing.assert_allclose(np.asarray(inverted(jnp.asarray(fwd))), back, atol=2e-6)
    for measure in ("nssd", "sad", "ssd"):
        got = np.asarray(stack(ss, cv, measure, False))
        np.testing.assert_allclose(got, tw.stack(ss, cv, ELEV, np.array(SCALES), measure, False), rtol=2e-5, atol=2e-6)


@pytest.mark.parametrize("stack_type", ["uint8", "float32"])
def test_the_match_table_is_the_twins(stack_type):
    ss, cv = pair(1)
    stk = quantised_stack(ss, cv, stack_type)
    table = match_table(stk)
    twin = tw.min_match(np.asarray(stk).astype(np.float64), tw.min_template(W, np.array(SCALES), 2.5), N, N)
    if stack_type == "uint8":
        assert np.array_equal(np.asarray(table), twin)  # sums of bytes: exact
    else:
        np.testing.assert_allclose(np.asarray(table), twin, rtol=1e-5)


@compiled
def window_table(stk, n_alpha: int, n_psi: int):
    reads = ws.run_template(ws.min_template(W, SCALES, 2.5, 0.0, math.inf), W, len(SCALES))
    arr = ws.run_windows(sp.arranged(stk, n_alpha, n_psi))
    return ws.min_match(arr, ws.group_steps(reads, W, n_alpha, n_psi), n_alpha, n_psi)


@compiled
def entry_table(stk, n_alpha: int, n_psi: int):
    entries = ws.min_template(W, SCALES, 2.5, 0.0, math.inf)
    return ws.min_match(sp.arranged(stk, n_alpha, n_psi), ws.group_steps(entries, W, n_alpha, n_psi), n_alpha, n_psi)


def test_window_reads_cover_each_columns_entries_exactly():
    """The search reads runs of consecutive displacements as windows of 2^k (`run_template`): per
    column and plane the windows cover exactly the template's displacements, in fewer reads."""
    entries = ws.min_template(W, SCALES, 2.5, 0.0, math.inf)
    reads = ws.run_template(entries, W, len(SCALES))
    assert len(reads) < len(entries) / 2
    covered = {(x, (y + o) % W, k % len(SCALES)) for x, y, k in reads.tolist() for o in range(2 ** (k // len(SCALES)))}
    assert covered == set(map(tuple, entries.tolist()))


@pytest.mark.parametrize("grid", [(32, 32), (32, 16), (48, 32)])
def test_the_match_table_from_window_minima_is_the_entry_by_entry_table(grid):
    """The search's match table (window minima of the arranged stack, `run_windows`) equals the table
    taken entry by entry, bit for bit, on bytes, on ties and on floats (a minimum is exact)."""
    rng = np.random.default_rng(sum(grid))
    for stk in (
        jnp.asarray(rng.integers(0, 201, (9, W, W)), jnp.uint8),
        jnp.asarray(rng.integers(0, 3, (9, W, W)), jnp.uint8),
        jnp.asarray(rng.random((9, W, W)), jnp.float32),
    ):
        assert np.array_equal(np.asarray(window_table(stk, *grid)), np.asarray(entry_table(stk, *grid)))


@compiled
def fine_table(stk, alpha, psi, steps: tuple[int, int], double: bool):
    groups = ws.column_groups(ws.min_template(W, SCALES, 2.5, 0.0, math.inf))
    return mw.fine_windows(stk, groups, alpha, psi, *steps, double)


@pytest.mark.parametrize("steps", [(3, 3), (2, 6)])
def test_the_fine_search_reads_every_candidates_match_from_windows(steps):
    """On the byte stack the fine search scores all (alpha + da, psi + dp) at once from windows of the
    stack; each equals the candidate's match taken one at a time, both ways, ties included."""
    rng = np.random.default_rng(sum(steps))
    for stk in (rng.integers(0, 201, (9, W, W)), rng.integers(0, 3, (9, W, W))):
        stk = jnp.asarray(stk, jnp.uint8)
        back = inverted(stk)
        alpha, psi = (int(v) for v in rng.integers(0, W, 2))
        # hypotheses as traced integers: one compiled program for every candidate and both stacks
        one_way, both = (np.asarray(fine_table(stk, jnp.int32(alpha), jnp.int32(psi), steps, d)) for d in (False, True))
        (sa, sp_), (rows, cols) = steps, one_way.shape
        assert (rows, cols) == (2 * sp_ - 1, 2 * sa - 1)
        for i, dp in enumerate(range(-(sp_ - 1), sp_)):
            for j, da in enumerate(range(-(sa - 1), sa)):
                a, p = (alpha + da) % W, (psi + dp) % W
                there = int(match_at(stk, jnp.int32(a), jnp.int32(p)))
                assert one_way[i, j] == there
                assert both[i, j] == there + int(match_at(back, jnp.int32((a + W // 2 - p) % W), jnp.int32((-p) % W)))


@pytest.mark.parametrize("refine", mw.REFINEMENTS)
def test_every_refinement_finds_the_twins_hypothesis(refine):
    for seed in (2, 3):
        ss, cv = pair(seed)
        stk = quantised_stack(ss, cv)
        stacks = (np.asarray(stk).astype(np.int64), np.asarray(inverted(stk)).astype(np.int64))
        twin = tw.search(ss, cv, ELEV, N, N, double="double" in refine, fine="fine" in refine, stacks=stacks)
        assert jsearch(ss, cv, refine=refine) == tuple(int(t) for t in twin), (seed, refine)


def test_end_to_end_agreement_with_the_twins_own_stack():
    for seed in (4, 5):
        ss, cv = pair(seed)
        twin = tw.search(ss, cv, ELEV, N, N)  # its own float64 stacks, quantised, both directions
        assert jsearch(ss, cv) == tuple(int(t) for t in twin), seed


@pytest.mark.parametrize("k", [0, 6, 7, 50])
def test_a_pure_rotation_gives_psi_exactly(k):
    ss, _ = pair(6)
    cv = np.roll(ss, -k, axis=1)  # current column j shows snapshot column j + k: turned by k pixels
    a, p, v = jsearch(ss, cv)
    assert (p, v) == (k, 0)
    if k % (W // N) == 0:  # on the coarse grid the full search alone finds it
        assert jsearch(ss, cv, refine="none")[1:] == (k, 0)


def translated(ss: np.ndarray, alpha_px: int, rho: float, psi_px: int) -> np.ndarray:
    """The current view after a move along alpha with every point at one distance from home (rho = d / r)
    and a turn by psi: each snapshot column carried to where the equal-distance warp puts it
    (y = atan2(rho sin x, 1 - rho cos x), the nearest column). Columns are constant over rows, so the
    vertical scale does not matter, and come in blocks of 4 equal ones, so that columns the move
    squeezes together carry one value."""
    w = ss.shape[-1]
    cv = np.zeros_like(ss)
    for theta in range(w):
        x = 2 * np.pi * (theta - alpha_px) / w
        iy = int(np.rint(math.atan2(rho * math.sin(x), 1 - rho * math.cos(x)) * w / (2 * np.pi)))
        cv[:, (theta + iy - psi_px) % w] = ss[:, theta]
    return cv


def blocks(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.repeat(np.repeat(rng.random((1, W // 4)).astype(np.float32), 4, 1), H, 0)


CASES = [(0, 0), (24, 0), (57, 33), (90, 3), (12, 60), (45, 45)]


@pytest.mark.parametrize("alpha_px,psi_px", CASES)
def test_a_pure_translation_with_equal_distances_gives_alpha_exactly(alpha_px, psi_px):
    """2D-Warping's one-distance template makes the true (alpha, psi, rho) the only perfect match."""
    ss = blocks(alpha_px)
    cfg = Warping2D(n_alpha=N, n_psi=N, n_rho=11, preprocess="none")  # rho = 0, 0.1, ..., 1
    for k, rho in ((1, 0.1), (3, 0.3), (5, 0.5)):
        cv = translated(ss, alpha_px, rho, psi_px)
        a, p, r, v = w2d_search(jnp.asarray(ss), jnp.asarray(cv), cfg)
        assert (int(a), int(p), int(r)) == (alpha_px, psi_px, k), rho


@pytest.mark.parametrize("alpha_px,psi_px", CASES)
def test_minwarping_scores_a_pure_translation_perfectly(alpha_px, psi_px):
    """MinWarping lets every column take any distance, so the truth matches (nearly) perfectly: every
    column but one or two that the move's squeeze overwrote finds its own; without vertical structure
    nothing tells the truth from hypotheses a few pixels off (ties at 0), so the found alpha is only
    near (docs/model.md §4.7)."""
    ss = blocks(alpha_px)
    for rho in (0.1, 0.3, 0.5):
        cv = translated(ss, alpha_px, rho, psi_px)
        stk = quantised_stack(ss, cv, "uint8", False)
        truth = int(match_at(stk, jnp.int32(alpha_px), jnp.int32(psi_px)))
        assert truth <= 2 * mw.LEVELS  # at most two columns without their own
        a, p, v = jsearch(ss, cv, preprocess="none", refine="none")
        assert v <= truth and abs((a - alpha_px + W // 2) % W - W // 2) <= 6, (rho, a)


def test_the_refinements_never_make_the_minimum_larger():
    for seed in range(7, 10):
        ss, cv = pair(seed)
        assert jsearch(ss, cv, refine="fine")[2] <= jsearch(ss, cv, refine="none")[2]
        assert jsearch(ss, cv, refine="double+fine")[2] <= jsearch(ss, cv, refine="double")[2]


def test_the_double_search_is_symmetric_in_its_two_images():
    """Swapping snapshot and current view gives the way back: alpha' = alpha + pi - psi, psi' = -psi."""
    ss, cv = pair(11)
    a, p, v = jsearch(ss, cv, refine="double")
    a2, p2, v2 = jsearch(cv, ss, refine="double")
    assert v2 == v and p2 == (-p) % W and a2 == (a + W // 2 - p) % W


def move(panorama):
    snap = Snapshot(
        mask=jnp.zeros(W, bool),
        gray=jnp.zeros(W),
        bearing=jnp.zeros(4),
        width=jnp.zeros(4),
        valid=jnp.zeros(4, bool),
        panorama=jnp.asarray(panorama),
        elevations=jnp.asarray(ELEV, jnp.float32),
    )
    return UnitMove(start=snap, end=snap, d_hat=jnp.float32(20.0), psi_hat=jnp.float32(0.0), compass=jnp.float32(0.0))


def test_the_method_turns_the_search_into_a_home_direction_and_a_compass():
    ss, cv = pair(12)
    method = MinWarping(n_alpha=N, n_psi=N)
    a, p, _ = jsearch(ss, cv)
    angle, valid = call(method, move(ss), move(cv))
    assert bool(valid) and abs(float(angle) - tw.home_direction(a, p, W)) < 1e-5
    psi = call(MinWarpingCompass(warping=method), move(ss), move(cv))
    assert abs(float(psi) - (2 * np.pi * p / W + np.pi) % (2 * np.pi) + np.pi) < 1e-5
    blank = np.zeros((H, W), np.float32)
    angle, valid = call(method, move(blank), move(cv))
    assert not bool(valid) and np.isnan(float(angle))


def test_2d_warping_agrees_with_the_twin():
    rhos = (0.1, 0.3, 0.5, 0.7, 0.9)  # rho = 1 puts columns at exact half pixels, which float rounding splits
    cfg = Warping2D(n_alpha=N, n_psi=N, n_rho=5, rho_min=0.1, rho_max=0.9)
    for seed in (13, 14):
        ss, cv = pair(seed)
        got = w2d_search(ss, cv, cfg)
        stk = np.asarray(quantised_stack(ss, cv))
        twin = tw.rho_search(ss, cv, ELEV, N, N, rhos=np.array(rhos), stk=stk.astype(np.int64))
        assert tuple(int(g) for g in got) == tuple(int(t) for t in twin), seed


@pytest.mark.parametrize(
    "settings,field",
    [
        ({"n_alpha": 7}, "n_alpha"),  # 7 does not divide 96 columns
        ({"n_psi": 40}, "n_psi"),
        ({"n_planes": 1}, "n_planes"),  # zero or one scale plane
        ({"n_planes": 8}, "n_planes"),  # even: no plane at 1
        ({"threshold": 1.0}, "threshold"),
        ({"max_scale": 1.0}, "max_scale"),
        ({"n_alpha": 48, "n_psi": 32}, "n_psi"),  # the double search maps psi onto alpha
    ],
)
def test_bad_settings_are_refused_naming_the_setting(settings, field):
    cfg = MinWarping(**{"n_alpha": N, "n_psi": N, **settings})
    with pytest.raises(InputError) as exc:
        cfg.check_input(W)
    assert exc.value.field == field
    ss, cv = pair(0)
    with pytest.raises(InputError):
        mw.search(jnp.asarray(ss), jnp.asarray(cv), jnp.asarray(ELEV), cfg)


@pytest.mark.parametrize("cls", [MinWarping, Warping2D])
@pytest.mark.parametrize("cols", [72, 288, 360])
def test_the_default_hypotheses_divide_every_width_delvjax_renders_or_the_studies_use(cls, cols):
    """360 (the default ring and render width), 288 (the authors'), 72 (the tests' databases): 96 divided only
    288, so `--method minwarping` was refused on the default width (issue 53 point 7)."""
    cfg = cls()
    assert cols % cfg.n_alpha == 0 and cols % cfg.n_psi == 0
    mw.check_grid(cfg, None, cols)  # no InputError
