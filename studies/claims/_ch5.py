"""Checks of the thesis's chapter 5 claims and the §6.2 summary (Figs 5.4-5.12, Tables 5.1-5.4, §3.2.4).

DELV with compass against ACV and ALV, occlusion (hidden landmarks), the visual compass and
compass noise. Each `@check` function takes `get` and returns (ours, verdict, why);
`delvjax.studies.claims` imports this module to register them. As in `delvjax.studies.claims._ch4`: each
docstring says what the check decides, each `why` ends with the rule and its tolerance, and a
comparison of catchments whose sides are all at the ceiling (or where no method loses anything)
is "cannot tell".
"""

from __future__ import annotations

from .. import thesis
from ._common import (
    ENVS,
    FAILS,
    FAILURES,
    _combine,
    _failures,
    _mean,
    _n,
    _opt,
    _pairs,
    _share,
    _verdict,
    _why,
    at_ceiling,
    at_floor,
    check,
)

OCCLUSION_LAYOUTS = ("env1", "env2", "env3", "ring3", "ring5", "ring6")


def _short(m: str) -> str:
    return m.split("-")[0].upper()


# --- chapter 5 ----------------------------------------------------------------------------------

SLIGHTLY = 10.0  # degrees


@check("compass_slightly_smaller_error", f"0 < without - with <= {SLIGHTLY:.0f}° in every environment")
def _(get):
    """With the compass DELV's mean error is below (strictly) and at most 10° below ('slightly') the
    error without it, in env1-3 (partly: smaller in 2 of 3)."""
    w = {e: get(f"map:{e}:delv-compass:mean_error_deg") for e in ENVS}
    wo = {e: get(f"map:{e}:delv:mean_error_deg") for e in ENVS}
    smaller = [w[e] < wo[e] for e in ENVS]
    slight = [wo[e] - w[e] <= SLIGHTLY for e in ENVS]
    ours = "; ".join(f"{e} {_n(w[e])}° with vs {_n(wo[e])}° without" for e in ENVS)
    verdict = "holds" if all(smaller) and all(slight) else "partly" if _share(smaller) >= 2 / 3 else "fails"
    far = [e for e, ok in zip(ENVS, slight) if not ok]
    slips = {e: _opt(get, f"map:{e}:delv:heading_slip_pct") for e in ENVS}
    rest = {e: _opt(get, f"map:{e}:delv:mean_error_without_slips_deg") for e in ENVS}
    not_smaller = [e for e, ok in zip(ENVS, smaller) if not ok]
    why_not = "" if all(smaller) else f"not smaller in {', '.join(not_smaller)}"
    if not_smaller and all(slips[e] is not None for e in not_smaller):
        why_not += (
            " (without compass no wrong heading wins there: "
            + ", ".join(f"{e} {slips[e]:.1f} % of the points" for e in not_smaller)
            + "; the heading that fits the estimated landmark vectors best absorbs part of their error)"
        )
    why_far = "" if not far else f"far smaller in {', '.join(far)}"
    if far and all(slips[e] is not None for e in far):
        why_far += (
            ": without compass a wrong heading hypothesis wins at "
            + ", ".join(f"{e} {slips[e]:.1f} % of the points (mean error {rest[e]:.1f}° at the others)" for e in far)
            + "; with every landmark on one side of home, rotations of the view about home fit nearly alike"
        )
    return ours, verdict, _why(why_not, why_far)


FIG5_5_VS_4_5 = {
    e: (thesis.CATCHMENT["fig5_5"][e]["delv-compass"][0], thesis.CATCHMENT["fig4_5"][e]["delv"][0]) for e in ENVS
}  # with, without compass
COMPASS_TOL = 5.0  # points on the thesis's difference


def _margin_part(with_, without, thesis_diff, tol):
    """(ok, None at the ceiling) for with - without within tol of the thesis's difference; None when both
    are >= 99 % or the side that should be lower has less headroom than the margin the claim needs."""
    diff = with_ - without
    need = abs(thesis_diff) - tol
    lower = without if thesis_diff > 0 else with_
    if at_ceiling([with_, without]) or (need > 0 and at_ceiling([lower], 100.0 - need)):
        return None
    return thesis_diff - tol <= diff <= thesis_diff + tol


@check(
    "compass_catchment_env2_similar_env3_better",
    f"with - without within {COMPASS_TOL:.0f} points of the thesis's -6.5 / +1.6 / +7.3",
)
def _(get):
    """Each environment's difference (with - without compass) within 5 points of the thesis's: env1
    -6.5 (lower with compass), env2 +1.6 (similar), env3 +7.3 (better with compass, so at least
    +2.3). A part is cannot tell when both sides are >= 99 % or the lower side cannot rise by the
    margin it needs (env3 without compass above 97.7 %)."""
    c = {e: (get(f"catchment:{e}:delv-compass"), get(f"catchment:{e}:delv")) for e in ENVS}
    parts = {e: _margin_part(a, b, FIG5_5_VS_4_5[e][0] - FIG5_5_VS_4_5[e][1], COMPASS_TOL) for e, (a, b) in c.items()}
    ours = "; ".join(
        f"{e} {_n(a)} with vs {_n(b)} % without (thesis {FIG5_5_VS_4_5[e][0]} vs {FIG5_5_VS_4_5[e][1]})"
        for e, (a, b) in c.items()
    )
    phys = [
        (_opt(get, f"catchment:{e}:delv-compass:physical"), _opt(get, f"catchment:{e}:delv:physical")) for e in ENVS
    ]
    if all(None not in p for p in phys):
        ours += "; physical rules " + ", ".join(f"{e} {_n(a)} vs {_n(b)}" for e, (a, b) in zip(ENVS, phys))
    verdict = _combine([parts["env2"], parts["env3"], parts["env1"]])
    reasons = [
        f"{e} at the ceiling"
        if p is None
        else ""
        if p
        else f"{e} differs from the thesis's difference by more than {COMPASS_TOL:.0f} points"
        for e, p in parts.items()
    ]
    return (
        ours,
        verdict,
        _why(*reasons),
    )


TIE_DEG = 1.0
MIXED = 0.2  # share of bins each way for "smaller in some regions, higher in others"


@check(
    "delv_vs_acv_alv_error_mixed",
    f"vs ACV lower in >= 60 % and higher (by <= {SLIGHTLY:.0f}°) in some bins; vs ALV each way in >= "
    f"{MIXED:.0%} of the bins",
)
def _(get):
    """Bins closer than 1° are ties. Against ACV: DELV lower in >= 60 % of the bins ('most of the
    region') and higher in at least one, by at most 10° ('slightly higher in some'). Against ALV: lower
    in >= 20 % and higher in >= 20 % of the bins (a real mix, not 12 of 14 one way)."""
    d, acv, alv = (get(f"error_curve:env1:{m}") for m in ("delv-compass", "acv", "alv"))
    lo_acv = _share(a < b - TIE_DEG for a, b in _pairs(d, acv))
    hi_acv = [a - b for a, b in _pairs(d, acv) if a > b + TIE_DEG]
    lo_alv = _share(a < b - TIE_DEG for a, b in _pairs(d, alv))
    hi_alv = _share(a > b + TIE_DEG for a, b in _pairs(d, alv))
    acv_ok = lo_acv >= 0.6 and bool(hi_acv) and max(hi_acv) <= SLIGHTLY
    alv_ok = lo_alv >= MIXED and hi_alv >= MIXED
    ours = (
        f"DELV lower than ACV in {lo_acv:.0%}, higher in {len(hi_acv)} bins; lower than ALV in {lo_alv:.0%}, "
        f"higher in {hi_alv:.0%} of distance bins (env1; ties within {TIE_DEG:.0f}°)"
    )
    alv_why = "" if alv_ok else "against ALV one side dominates, not a mix" + _alv_steady(d, alv)
    return (
        ours,
        _verdict([acv_ok, alv_ok]),
        _why("" if acv_ok else "not 'smaller than ACV in most, slightly higher in some'", alv_why),
    )


def _alv_steady(d, alv) -> str:
    """Why DELV and ALV do not mix: ALV's steady error at every distance against DELV's, higher only near home."""
    higher = [i for i, (a, b) in enumerate(_pairs(d, alv)) if a > b + TIE_DEG]
    if not alv or higher != list(range(len(higher))):  # DELV higher somewhere beyond the nearest bins: no such cause
        return ""
    near = (
        ""
        if not higher
        else f", higher only in the nearest {len(higher)} bin{'s' * (len(higher) > 1)} (where "
        "the short home vector turns most with the pixel errors)"
    )
    return (
        f": ALV errs {min(alv):.0f}-{max(alv):.0f}° in every bin, the gradient of a potential (§3.3.2) bending "
        "off the straight line home at every distance, while DELV's noise-free estimates point nearly straight" + near
    )


NEAR_FAR = 3  # release-distance bins
SR_TOL = 3.0  # points: beyond the binomial noise of 100 trials at 80-90 %
LITTLE = 10.0  # points: "little higher"
SIMILAR = 5.0  # points of overall success
NEAR_FAR_RULE = (
    f"overall within {SIMILAR:.0f} points; near {NEAR_FAR} distances DELV higher by {SR_TOL:.0f}..{LITTLE:.0f}; "
    f"far {NEAR_FAR} DELV lower by >= {SR_TOL:.0f}; fails when every decidable near / far part is contradicted"
)


@check("delv_compass_success_near_far", NEAR_FAR_RULE)
def _(get):
    """Against ACV and ALV each: overall success within 5 points ('similar'); the near 3 distances DELV
    higher by 3..10 points ('little higher'); the far 3 distances DELV lower by >= 3 points. Each part
    whose sides are all >= 99 % cannot tell."""
    d, acv, alv = (get(f"success:env1:{m}") for m in ("delv-compass", "acv", "alv"))
    parts, reasons = [], []
    for name, o in (("ACV", acv), ("ALV", alv)):
        sim = None if at_ceiling([d, o]) else abs(_mean(d) - _mean(o)) <= SIMILAR
        dn, on = d[:NEAR_FAR], o[:NEAR_FAR]
        near = None if at_ceiling([dn, on]) else SR_TOL <= _mean(dn) - _mean(on) <= LITTLE
        df, of = d[-NEAR_FAR:], o[-NEAR_FAR:]
        far = None if at_ceiling([df, of]) else _mean(df) <= _mean(of) - SR_TOL
        parts += [sim, near, far]
        reasons += [
            ""
            if far is not False
            else f"far from home DELV succeeds at least as often as {name}" + _far_failures(get, name.lower()),
            "" if near is not False else f"near home DELV is not a little above {name}",
            "" if sim is not False else f"overall not similar to {name}",
        ]
    if None in parts:
        reasons.append("parts at the ceiling (both >= 99 %)")
    pattern = [p for i, p in enumerate(parts) if i % 3 and p is not None]  # the near and far parts
    ours = f"success DELV {_n(d)}, ACV {_n(acv)}, ALV {_n(alv)} %"
    if pattern and not any(pattern):  # the sentence's own content (higher near, lower far) contradicted
        reasons.append("every near / far part that can be decided is contradicted: 'similar' alone is not the claim")
        return ours, FAILS, _why(*reasons)
    return ours, _combine(parts), _why(*reasons)


def _far_failures(get, method: str) -> str:
    """What ends the far releases' failed trials of DELV-compass and `method` (success-rate study)."""
    d, o = (_failures(get, f"success_failures_far:env1:{m}") for m in ("delv-compass", method))
    if not d or not o:
        return ""
    fmt = lambda f: "/".join(str(f[k]) for k in FAILURES)  # noqa: E731
    return (
        f" (failures timeout/landmark/arena of the far {NEAR_FAR} distances: DELV {fmt(d)}, {_short(method)} "
        f"{fmt(o)}; our DELV senses without noise, so a poor first estimate far away sharpens with every step "
        "towards home)"
    )


def _occl(get, env, m, field="catchment"):
    return get(f"occlusion:{env}:{m}:{field}")


SEVERE = 20.0  # points of catchment lost: "severely"


@check(
    "matching_tolerates_unequal_landmark_numbers",
    f"catchment loss and e>45 rise from k = 0 to 1 below {SEVERE:.0f} points",
)
def _(get):
    """§3.2.4: different landmark numbers in the two views do 'not severely damage the homing rate or the
    average error'. With one landmark hidden (k = 1) DELV-compass loses < 20 points of catchment (the
    threshold of 'severely' in the claims below) and its e > 45° rate rises by < 20 points, env1-3.
    The thesis's own Table 5.3 contradicts it (env1 92.01 -> 49.11 %). DELV's catchment at the ceiling
    with and without the hidden landmark is evidence only when the condition costs another method
    (ACV or ALV) catchment; when no method loses anything (all >= 99 %) that part cannot tell."""
    parts, cells = [], []
    for e in ENVS:
        c, g = _occl(get, e, "delv-compass"), _occl(get, e, "delv-compass", "gt45")
        nobody_loses = at_ceiling([c[:2]] + [_occl(get, e, m)[:2] for m in ("acv", "alv")])
        parts += [None if nobody_loses else c[0] - c[1] < SEVERE, g[1] - g[0] < SEVERE]
        cells.append(f"{e} catchment {_n(c[:2])} %, e>45 {_n(g[:2])} %")
    ours = "DELV-compass k = 0/1: " + "; ".join(cells) + " (thesis env1 92.01/49.11 %)"
    bad = [e for e, a, b in zip(ENVS, parts[::2], parts[1::2]) if a is False or b is False]
    return (
        ours,
        _combine(parts),
        _why(
            ""
            if not bad
            else f"severe damage in {', '.join(bad)} (as the thesis's own "
            "Table 5.3 shows: linear matching skips a hidden landmark only where the "
            "home-frame list wraps, so most choices of the hidden landmark pair every "
            "landmark after it wrongly; the occlusion study's per-choice table)",
        ),
    )


STEP = 1.0  # points
TABLE5_1_GT45 = thesis.ERROR_POINTS["table5_1"]["env1"]["delv-compass"]["gt45"]  # e>45 %, k = 0, 1, 2
HALF_RISE = (TABLE5_1_GT45[2] - TABLE5_1_GT45[0]) / 2


@check("occlusion_increases_errors", f"each step up by >= {STEP:.0f} point, k = 0 -> 2 up by >= {HALF_RISE:.1f} points")
def _(get):
    """DELV-compass's e > 45° rate in env1 rises by >= 1 point with each hidden landmark, and by at least
    half the thesis's rise (8.75 -> 20.48: 11.7 points) from k = 0 to 2 (partly: one of the two)."""
    g = _occl(get, "env1", "delv-compass", "gt45")
    steps = g[1] >= g[0] + STEP and g[2] >= g[1] + STEP
    total = g[2] - g[0] >= HALF_RISE
    ours = f"env1 DELV e>45, k = 0/1/2: {_n(g[:3])} % (thesis {'/'.join(f'{v:g}' for v in TABLE5_1_GT45)})"
    return (
        ours,
        _verdict([steps, total]),
        _why(
            "" if steps else "not rising with every hidden landmark",
            "" if total else "rises by less than half the thesis's",
        ),
    )


BELOW_TOL = 1.0  # points (the thesis's env2 k = 0 tie at 7.99)


@check(
    "acv_error_grows_faster_than_delv", "DELV <= ACV + 1 at every k; ACV's rise >= 2 x DELV's and >= DELV's + 10 points"
)
def _(get):
    """DELV-compass's e > 45° rate at or below ACV's (within 1 point) for k = 0..2, and ACV's rise from
    k = 0 to 2 'much more rapid': at least twice DELV's and at least 10 points more (thesis env1 +70.8
    vs +11.7), env1-3."""
    below, faster, parts = [], [], []
    for e in ENVS:
        d, a = _occl(get, e, "delv-compass", "gt45")[:3], _occl(get, e, "acv", "gt45")[:3]
        below.append(all(x <= y + BELOW_TOL for x, y in zip(d, a)))
        rd, ra = d[2] - d[0], a[2] - a[0]
        faster.append(ra >= 2 * rd and ra >= rd + 10.0)
        parts.append(f"{e} DELV {_n(d)} vs ACV {_n(a)}")
    ours = "e>45 % for k = 0/1/2: " + "; ".join(parts)
    verdict = "holds" if all(below) and all(faster) else "partly" if all(faster) or all(below) else "fails"
    return (
        ours,
        verdict,
        _why(
            "" if all(below) else "DELV above ACV somewhere",
            "" if all(faster) else "ACV's rate does not rise much faster somewhere",
        ),
    )


GT90_K0_TOL, GT90_TOL, GT90_FLOOR = 0.5, 1.0, 0.5  # points


@check(
    "error_rate_gt90_acv_lower_without_occlusion",
    f"k = 0: ACV <= DELV + {GT90_K0_TOL}; k >= 1: DELV <= ACV + {GT90_TOL:.0f}, every layout",
)
def _(get):
    """The e > 90° columns of Tables 5.1-5.2 as printed: with no landmark hidden ACV's rate is at or
    below DELV-compass's (within 0.5 point) in every layout, and with k >= 1 hidden DELV's is at or
    below ACV's (within 1 point; the thesis's L = 6 k = 3 is 7.10 vs 7.09). Cells where both are
    <= 0.5 % cannot tell."""
    k0, kn, cells = [], [], []
    for e in OCCLUSION_LAYOUTS:
        d, a = _occl(get, e, "delv-compass", "gt90"), _occl(get, e, "acv", "gt90")
        k0.append(None if at_floor([d[0], a[0]], GT90_FLOOR) else a[0] <= d[0] + GT90_K0_TOL)
        kn += [None if at_floor([x, y], GT90_FLOOR) else x <= y + GT90_TOL for x, y in zip(d[1:], a[1:])]
        cells.append(f"{e} DELV {_n(d)} vs ACV {_n(a)}")
    ours = "e>90 % for k = 0, 1, ...: " + "; ".join(cells) + " (thesis env1 3.02/3.62/6.49 vs 0.15/10.07/33.54)"

    def part(flags):
        known = [f for f in flags if f is not None]
        return None if not known else all(known)

    parts = [part(k0), part(kn)]
    verdict = _combine(parts)
    if verdict == "fails" and (_share(f for f in k0 + kn if f is not None) >= 0.5):
        verdict = "partly"
    return (
        ours,
        verdict,
        _why(
            "" if parts[0] is not False else "ACV above DELV without occlusion somewhere" + K0_CAUSE,
            "" if parts[1] is not False else "DELV above ACV with hidden landmarks somewhere",
        ),
    )


TABLE5_3_ENV1 = thesis.CATCHMENT["table5_3"]["env1"]
SMALL_OCCL = {k: TABLE5_3_ENV1["acv"][k] - TABLE5_3_ENV1["delv-compass"][k] for k in (0, 1)}  # ACV - DELV, env1
ACV_LAYOUT = (
    "ACV's errors depend strongly on the layout, which the thesis does not give (env3 moved by up to 150 cm: "
    "ACV's e>45 21-82 %, docs/reproduce.md 'Causes measured outside the run')"
)
K0_CAUSE = (
    ": with every landmark in view our DELV has almost no error points (noise-free sensing), and ACV's "
    "corrections, tangential to the bearings only (Eq 5.2), leave some; " + ACV_LAYOUT
)
GAP_TOL_OCCL = 10.0
BEYOND_TIE = 0.5
