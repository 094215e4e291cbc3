"""Checks of the thesis's chapter 4 claims (DELV without compass, Figs 4.3-4.14).

Catchment per environment, errors inside/outside the landmark hull, step distance, arbitrary
layouts, DELV against predictive image matching, distance quantization. Each `@check` function
takes `get` and returns (ours, verdict, why); `studies.claims` imports this module to register them.
"""

from __future__ import annotations

from .claims_common import ENVS, _mean, _n, _pairs, _share, _verdict, check


# --- chapter 4 ----------------------------------------------------------------------------------

@check("delv_nocompass_catchment_all_envs")
def _(get):
    c = {e: get(f"catchment:{e}:delv") for e in ENVS}
    large = all(v >= 75.0 for v in c.values())
    env3_lowest = c["env3"] <= min(c["env1"], c["env2"])
    ours = "catchment env1/2/3: " + _n(list(c.values())) + " % (thesis 98.5/95.4/77.7)"
    why = "" if large and env3_lowest else (
        "env3 is not the lowest: with landmarks no obstacles, DELV homes from almost everywhere" if large
        else "a catchment is below 75 %")
    return ours, _verdict([large, env3_lowest]), why


@check("errors_outside_landmark_hull")
def _(get):
    ins = {e: get(f"map:{e}:delv:gt45_inside_hull_pct") for e in ENVS}
    out = {e: get(f"map:{e}:delv:gt45_outside_hull_pct") for e in ENVS}
    near0 = [ins[e] <= 2.0 for e in ENVS]
    outside = [ins[e] <= out[e] for e in ENVS]
    ours = "; ".join(f"{e} e>45 inside {_n(ins[e])} %, outside {_n(out[e])} %" for e in ENVS)
    bad = [e for e in ENVS if not (ins[e] <= 2.0 and ins[e] <= out[e])]
    why = "" if not bad else (f"not in {', '.join(bad)}: the hull there is a thin region at the edge of the layout "
                              "(env3: home lies outside it), where the parallax of a 50 cm move is small")
    return ours, _verdict([all(near0) and all(outside), _share(outside) >= 2 / 3]), why


@check("step_distance_rarely_matters")
def _(get):
    means = {d: _mean(get(f"error_curve:env1:delv:d={d}")) for d in (20, 50, 100, 150)}
    spread = max(means.values()) - min(means.values())
    ours = "mean of the error curve, d = 20/50/100/150 cm: " + _n(list(means.values())) + "°"
    verdict = "holds" if spread <= 10 else "partly" if spread <= 20 else "fails"
    return ours, verdict, "" if verdict == "holds" else f"the curves differ by {spread:.1f}° on average"


@check("few_landmarks_error_below_90")
def _(get):
    curves = {n: get(f"error_curve:random{n}:delv") for n in (3, 4, 5)}
    below = [v < 90 for c in curves.values() for v in c]
    ours = "largest bin mean, 3/4/5 landmarks: " + _n([max(c) for c in curves.values()]) + "°"
    verdict = "holds" if all(below) else "partly" if _share(below) >= 0.9 else "fails"
    return ours, verdict, "" if verdict == "holds" else "some distance bins average 90° or more"


@check("delv_smaller_error_than_warping")
def _(get):
    d, w = get("error_curve:env1:delv"), get("error_curve:env1:warping")
    share = _share(a < b for a, b in _pairs(d, w))
    ours = f"env1 mean error DELV {_n(get('map:env1:delv:mean_error_deg'))}°, image matching " \
           f"{_n(get('map:env1:warping:mean_error_deg'))}°; DELV lower in {share:.0%} of distance bins"
    verdict = "holds" if share >= 0.8 else "partly" if share >= 0.5 else "fails"
    return ours, verdict, "" if verdict == "holds" else "image matching is as good near home"


@check("delv_success_over_90")
def _(get):
    s, p = get("success:env1:delv"), get("success:env1:delv:physical")
    ours = f"default rules {_n(s)} %; physical rules {_n(p)} %"
    verdict = "holds" if min(s) > 90 else "partly" if _mean(s) > 90 else "fails"
    why = "" if verdict == "holds" else "some release distances succeed in 90 % of trials or fewer"
    if verdict == "holds" and min(p) <= 90:
        why = "holds under the default rules; under the physical rules far releases fall below 90 % (landmark hits)"
    return ours, verdict, why


@check("delv_beats_warping_success")
def _(get):
    d, w = get("success:env1:delv"), get("success:env1:warping")
    ge = [a >= b for a, b in _pairs(d, w)]
    cd, cw = get("catchment:env1:delv"), get("catchment:env1:warping")
    ours = f"success DELV {_n(d)} vs image matching {_n(w)} %; catchment {_n(cd)} vs {_n(cw)} %"
    verdict = _verdict([all(ge) and cd > cw, _share(ge) >= 0.5])
    return ours, verdict, "" if verdict == "holds" else "image matching succeeds as often at some distances"


@check("warping_fails_outside_hull")
def _(get):
    wi, wo = get("fail_inside_hull:env1:warping"), get("fail_outside_hull:env1:warping")
    do = get("fail_outside_hull:env1:delv")
    ours = f"failed releases: image matching inside hull {_n(wi)} %, outside {_n(wo)} %; DELV outside {_n(do)} %"
    return ours, _verdict([wo > wi, wo > do]), ""


@check("quantized_error_small_and_level_insensitive")
def _(get):
    cont = _mean(get("error_curve:env1:delv:continuous"))
    levels = {q: get(f"error_curve:env1:delv:Q{q}") for q in (1, 2, 3, 4, 5)}
    small = [_share(v < 30 for v in c) >= 0.5 for c in levels.values()]
    close = [abs(_mean(c) - cont) <= 10 for c in levels.values()]
    ours = "mean error Q = 1..5: " + _n([_mean(c) for c in levels.values()]) + f"°, continuous {_n(cont)}°"
    verdict = _verdict([all(small), all(close)])
    bad = [q for q, ok in zip(levels, close) if not ok]
    return ours, verdict, "" if verdict == "holds" else f"Q = {bad} differ from continuous by more than 10°"


@check("fewer_levels_more_failures_three_suffice")
def _(get):
    tags = ("Q1", "Q2", "Q3", "Q5", "continuous")
    s = [get(f"success_overall:env1:delv:{t}") for t in tags]
    c = [get(f"catchment:env1:delv:{t}") for t in tags]
    monotone = all(b >= a - 2.0 for a, b in zip(s, s[1:]))
    three = s[2] >= s[-1] - 5.0
    ours = "success overall Q = 1/2/3/5/continuous: " + _n(s) + " %; catchment " + _n(c) + " %"
    why = "" if monotone and three else (
        "success does not fall with fewer levels" if not monotone else "three levels fall short of continuous")
    return ours, _verdict([monotone, three]), why


@check("surrounding_landmarks_lower_error")
def _(get):
    sur = {e: get(f"map:{e}:delv:Q3:mean_error_deg") for e in ("env2", "ring6")}
    edge = get("map:env3:delv:Q3:mean_error_deg")
    lower = [v < edge for v in sur.values()]
    ours = f"3 levels, mean error env2 {_n(sur['env2'])}°, ring6 {_n(sur['ring6'])}° vs env3 (one side) {_n(edge)}°"
    return ours, _verdict(lower), ""


@check("robot_images_delv_errs_more_but_homes")
def _(get):
    img, ideal = get("robot_images:delv:mean_error_deg"), get("robot_images:delv:ideal_mean_error_deg")
    catch = get("robot_images:delv:catchment_pct")
    more, homes = img > ideal, catch >= 75.0
    ours = f"mean error {_n(img)}° on images, {_n(ideal)}° on ideal rings; catchment {_n(catch)} %"
    why = "" if more and homes else ("rendered images carry no detection error beyond pixel noise: their rings "
                                     "are the ring model's, so DELV errs as on ideal rings" if homes
                                     else "the catchment on images is below 75 %")
    return ours, _verdict([more and homes, homes]), why


@check("robot_images_quantized_similar")
def _(get):
    base = get("robot_images:delv:mean_error_deg")
    levels = {q: get(f"robot_images:delv:Q{q}:mean_error_deg") for q in (1, 2, 4, 5)}
    close = [abs(v - base) <= 10.0 for v in levels.values()]
    ours = "mean error, 1/2/4/5 levels: " + _n(list(levels.values())) + f"°; continuous {_n(base)}°"
    verdict = "holds" if all(close) else "partly" if _share(close) >= 0.5 else "fails"
    return ours, verdict, "" if verdict == "holds" else "some levels differ by more than 10°"
