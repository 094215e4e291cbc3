"""Every claim check on synthetic numbers: one set that makes it hold, one that contradicts the
claim (it must fail), and where it compares catchments or success rates one at the ceiling
("cannot tell"). Pure Python: no study runs, no JAX program (`tests/reproduce/test_reproduce.py` checks the
verdicts on the numbers of a real run).
"""

from __future__ import annotations

import re

import pytest

from tests.cases.claims import *  # noqa: F401,F403  (the builders of synthetic numbers)
from tests.cases.claims import THESIS_TEXT, _combine, claims, thesis  # noqa: F401

NESTED = {"landmark_number:nested": 1.0}  # layouts whose fewer landmarks are a subset of the more

CASES = {
    "delv_nocompass_catchment_all_envs": {
        "holds": c_catch_envs(98.52, 95.41, 77.66),
        "fails": c_catch_envs(10.0, 10.0, 50.0),
        "partly": c_catch_envs(100.0, 100.0, 98.66),  # env3 lowest by 1.3 points only (the full run)
        CANNOT_TELL: c_catch_envs(100.0, 100.0, 99.5),
    },
    "errors_outside_landmark_hull": {"holds": hull(0.5, 5.0), "fails": hull(10.0, 2.0), CANNOT_TELL: hull(0.0, 0.0)},
    "step_distance_rarely_matters": {
        "holds": steps([flat(10)] * 4, [90.0, 92.0, 91.0, 89.0]),
        "fails": steps([flat(10)] * 3 + [flat(40)], [99.0, 90.0, 80.0, 60.0]),
        CANNOT_TELL: steps([flat(10)] * 4, [100.0] * 4),
    },
    "small_step_slightly_better": {
        "holds": step_errors(10.0, 11.0, 14.0, 15.0),
        "fails": step_errors(15.0, 14.0, 10.0, 11.0),
        "partly": step_errors(14.2, 10.9, 10.82, 12.33),
    },  # the full run: a tie
    "few_landmarks_error_below_90": {
        "holds": random_curves("delv", [RISING] * 3),
        "fails": random_curves("delv", [flat(95)] * 3),
        "partly": random_curves("delv", [FALLING] * 3),
    },  # below 90 but largest near home
    "warping_sensitive_to_landmark_number": {
        "holds": merge(
            random_curves("warping", [flat(60), flat(40), flat(30)]),
            random_curves("delv", [flat(10), flat(11), flat(12)]),
            NESTED,
        ),
        "fails": merge(
            random_curves("warping", [flat(30), flat(30), flat(31)]),
            random_curves("delv", [flat(10), flat(20), flat(30)]),
            NESTED,
        ),
        CANNOT_TELL: merge(  # the seeded layouts change arrangement and number together
            random_curves("warping", [flat(60), flat(40), flat(30)]),
            random_curves("delv", [flat(10), flat(11), flat(12)]),
        ),
        "n/a": random_curves("delv", [flat(10)] * 3),
    },  # no study records the warping curves yet
    "delv_smaller_error_than_warping": {
        "holds": warping_err(flat(5), flat(30), 5.0, 30.0),
        "fails": warping_err(flat(30), flat(5), 30.0, 5.0),
    },
    "delv_success_over_90": {
        "holds": success(FAR_LOW, FAR_LOW),
        "fails": success([10.0] * 9, [10.0] * 9),
        "partly": success([100.0] * 9, OURS_PHYSICAL),  # the far decrease only where success falls to 82 %
        CANNOT_TELL: success([100.0] * 9, [100.0] * 9),
    },
    "delv_beats_warping_success": {
        "holds": beats([100.0] * 9, WARPING_SUCCESS, 100.0, 60.0),
        "fails": beats(WARPING_SUCCESS, [100.0] * 9, 60.0, 100.0),
        CANNOT_TELL: beats([100.0] * 9, [100.0] * 9, 100.0, 100.0),
    },
    "warping_fails_outside_hull": {
        "holds": fail_hull(1.6, 44.6, 0.0),
        "fails": fail_hull(20.0, 10.0, 30.0),
        CANNOT_TELL: fail_hull(0.0, 0.0, 0.0),
    },
    "quantized_error_small_and_level_insensitive": {
        "holds": quant(flat(10), flat(12)),
        "fails": quant(flat(10), flat(60)),
    },
    "fewer_levels_more_failures_three_suffice": {
        "holds": levels_success([60.0, 75.0, 88.0, 90.0, 91.0]),
        "fails": levels_success([90.0, 80.0, 50.0, 85.0, 95.0]),
        "holds#full run": levels_success([73.6, 81.6, 100.0, 100.0, 100.0]),  # at 100 % while level 1 loses
        CANNOT_TELL: levels_success([100.0] * 5),
    },
    "surrounding_landmarks_lower_error": SURROUND,  # judged against edge4, home slightly outside the hull
    "robot_images_delv_errs_more_but_homes": {"holds": robot(13.0, 8.0, 90.0), "fails": robot(8.0, 8.0, 50.0)},
    "robot_images_delv_beats_warping": {
        "holds": robot_vs(8.0, 20.0, 90.0, 70.0),
        "fails": robot_vs(13.3, 8.8, 95.0, 80.0),  # image matching errs less: fails whatever the catchment
        CANNOT_TELL: robot_vs(8.0, 20.0, 100.0, 100.0),
    },
    "robot_images_quantized_similar": {"holds": robot_q(10.0, 12.0), "fails": robot_q(10.0, 40.0)},
    "compass_slightly_smaller_error": {"holds": compass_err(8.0, 10.0), "fails": compass_err(12.0, 10.0)},
    "compass_catchment_env2_similar_env3_better": {
        "holds": compass_catch([(92.01, 98.52), (97.04, 95.41), (84.91, 77.66)]),
        "fails": compass_catch([(99.0, 90.0), (60.0, 90.0), (70.0, 85.0)]),
        CANNOT_TELL: compass_catch([(100.0, 100.0), (100.0, 100.0), (100.0, 98.66)]),
    },  # the full run
    "delv_vs_acv_alv_error_mixed": {
        "holds": curves3(flat(10), flat(15, 13) + [5.0], flat(15, 7) + flat(5, 7)),
        "fails": curves3(flat(20), flat(10), flat(10)),
        "partly": curves3(flat(10), flat(15, 13) + [5.0], flat(15, 12) + flat(5, 2)),
    },  # 12 of 14 one way: no mix
    "delv_compass_success_near_far": {
        "holds": success3([100.0, 100.0, 100.0, 95.0, 95.0, 95.0, 85.0, 85.0, 85.0], *[[95.0] * 6 + [90.0] * 3] * 2),
        "fails": success3(
            [60.0, 60.0, 60.0, 70.0, 70.0, 70.0, 95.0, 95.0, 95.0],
            *[[100.0, 100.0, 100.0, 95.0, 95.0, 95.0, 80.0, 80.0, 80.0]] * 2,
        ),
        CANNOT_TELL: success3([100.0] * 9, [100.0] * 9, [100.0] * 9),
    },
    "matching_tolerates_unequal_landmark_numbers": {
        "holds": tolerate([95.0, 90.0, 80.0], [5.0, 8.0, 12.0]),
        "fails": tolerate([95.0, 40.0, 30.0], [5.0, 40.0, 50.0]),
        "partly": THESIS_OCCLUSION,  # the thesis's own Table 5.3 contradicts §3.2.4
        CANNOT_TELL: tolerate([100.0, 100.0, 100.0], [1.0, 2.0, 3.0], others=(100.0, 99.5, 99.0)),
    },
    "occlusion_increases_errors": {
        "holds": same("gt45", [8.75, 13.99, 20.48], envs=("env1",)),
        "fails": same("gt45", [30.0, 20.0, 10.0], envs=("env1",)),
        "partly": same("gt45", [5.0, 6.5, 8.0], envs=("env1",)),
    },
    "acv_error_grows_faster_than_delv": {
        "holds": T51_GT45,
        "fails": pair("gt45", [10.0, 40.0, 80.0], [5.0, 10.0, 15.0]),
    },
    "error_rate_gt90_acv_lower_without_occlusion": {
        "holds": T5_GT90,
        "fails": pair("gt90", [1.0, 20.0, 30.0], [10.0, 2.0, 3.0], envs=L6),
        CANNOT_TELL: pair("gt90", [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], envs=L6),
    },
    "acv_larger_catchment_small_occlusion": {
        "holds": T53,
        "fails": pair("catchment", [100.0, 80.0, 60.0], [80.0, 50.0, 20.0], envs=("env1",)),
        CANNOT_TELL: pair("catchment", [100.0, 100.0, 90.0], [100.0, 100.0, 50.0], envs=("env1",)),
    },
    "occlusion_catchment_both_severely_decrease": {
        "holds": T53,
        "fails": pair("catchment", [95.0, 94.0, 93.0], [95.0, 94.0, 93.0]),
        "partly": pair("catchment", [100.0, 98.0, 97.0], [100.0, 50.0, 20.0]),
    },
    "acv_catchment_shrinks_faster": {
        "holds": T53,
        "fails": pair("catchment", [100.0, 50.0, 20.0], [100.0, 90.0, 80.0]),
        "partly": pair("catchment", [100.0, 99.0, 98.0], [100.0, 50.0, 20.0]),  # DELV barely shrinks
        CANNOT_TELL: pair("catchment", [100.0] * 3, [100.0] * 3),
    },
    "alv_perfect_then_collapses_under_occlusion": {
        "holds": alv_case([100.0, 10.0, 15.0], [0.0, 10.0, 15.0], [95.0, 60.0, 50.0]),
        "fails": alv_case([80.0, 80.0, 80.0], [20.0, 30.0, 40.0], [50.0, 40.0, 30.0]),
    },
    "k3_collapse": {"holds": THESIS_OCCLUSION, "fails": k3([90.0, 85.0, 80.0, 75.0])},
    "visual_compass_not_exact": {
        "holds": visual_err({"delv-compass": 5.0, "acv": 10.0, "alv": 20.0}),
        "fails": visual_err({m: 0.2 for m in TRUE3}, gt5=0.0),
    },
    "visual_compass_catchment_order": {
        "holds": visual_catch([74.85, 47.04, 40.68]),
        "fails": visual_catch([40.0, 47.0, 75.0]),
        CANNOT_TELL: visual_catch([100.0, 100.0, 100.0]),
        **ORDER_WORLDS,  # Fig 5.11's world unstated: env1-3 judged
    },
    "visual_compass_error_order": {
        "holds": visual_err({"delv-compass": 4.0, "acv": 4.0, "alv": 31.0}),
        "fails": visual_err({"delv-compass": 42.0, "acv": 4.0, "alv": 1.0}),
        CANNOT_TELL: visual_err({m: 0.1 for m in TRUE3}),
        "holds#env3": ERRORS_ON_ENV3,
    },
    "delv_least_compass_dependent": {
        "holds": dependence([95.0, 60.0, 50.0], [2.0, 14.0, 21.0], [95.0, 60.0, 50.0]),
        "fails": dependence([50.0, 90.0, 95.0], [30.0, 2.0, 1.0], [50.0, 90.0, 95.0]),
        CANNOT_TELL: dependence([100.0] * 3, [0.1] * 3, [99.5] * 3),
    },
    "delv_acv_similar_without_occlusion": {
        "holds": similar(8.0, 10.0, 92.0, 100.0),
        "fails": similar(8.0, 40.0, 50.0, 97.0),
        CANNOT_TELL: similar(8.0, 10.0, 100.0, 100.0),
    },
}


# --- the tests ------------------------------------------------------------------------------


def test_every_claim_has_a_check_and_cases():
    ids = [c["id"] for c in thesis.CLAIMS]
    assert len(ids) == len(set(ids))
    assert set(ids) == set(claims.CHECKS) == set(CASES)
    for cid, cases in CASES.items():
        assert {"holds", "fails"} <= set(cases), cid


@pytest.mark.parametrize("claim_id,case", [(c, v) for c, cases in CASES.items() for v in cases])
def test_check_verdict(claim_id, case):
    """A case is named by its expected verdict ("holds#why" for a second case of the same verdict)."""
    row = verdict(claim_id, CASES[claim_id][case])
    expected = case.split("#")[0]
    assert row["verdict"] == expected, (row["ours"], row["why"])
    assert row["verdict"] in VERDICTS
    if expected != "n/a":
        assert row["ours"] and "Rule:" in row["why"], row  # every check states its rule and tolerance


def test_ceiling_helpers():
    assert at_ceiling([100.0, 99.0]) and not at_ceiling([100.0, 98.9]) and not at_ceiling([])
    assert at_ceiling([[100.0, 99.5], 99.2]) and at_ceiling([98.0], limit=97.75)
    assert at_floor([0.0, 0.5]) and not at_floor([0.0, 2.0]) and no_loss([0.0, 1.9]) and not no_loss([0.0, 2.1])
    assert _combine([True, True]) == "holds" and _combine([True, None]) == CANNOT_TELL
    assert _combine([None, None]) == CANNOT_TELL and _combine([False, None]) == "fails"
    assert _combine([True, False, None]) == "partly"


def test_the_full_run_at_the_ceiling_is_not_holds():
    """The review's cases: env3 lowest by 1.3 points and compass catchments at 100 % passed before."""
    assert (
        verdict("delv_nocompass_catchment_all_envs", CASES["delv_nocompass_catchment_all_envs"]["partly"])["verdict"]
        != "holds"
    )
    assert (
        verdict(
            "compass_catchment_env2_similar_env3_better",
            CASES["compass_catchment_env2_similar_env3_better"][CANNOT_TELL],
        )["verdict"]
        == CANNOT_TELL
    )


def test_missing_numbers_are_not_applicable():
    rows = claims.evaluate({})
    assert all(r["verdict"] == "n/a" and "needs" in r["why"] for r in rows)


def test_a_number_without_a_value_is_cannot_tell_not_a_study_not_run():
    """A study records NaN (JSON null) where a number is undefined at its settings: on the tiny run's 5 x 5
    grid no point but home lies inside env2's landmark hull, and home is left out (docs/model.md §5)."""
    numbers = hull(0.0, 10.0)
    assert verdict("errors_outside_landmark_hull", numbers)["verdict"] == "holds"
    numbers["map:env2:delv:gt45_inside_hull_pct"] = None
    row = verdict("errors_outside_landmark_hull", numbers)
    assert row["verdict"] == CANNOT_TELL and "has no value" in row["why"] and "not run" not in row["why"], row
    assert row["ours"].endswith("map:env2:delv:gt45_inside_hull_pct = no value"), row["ours"]
    del numbers["map:env2:delv:gt45_inside_hull_pct"]
    assert verdict("errors_outside_landmark_hull", numbers)["verdict"] == "n/a"


def test_report_counts_cannot_tell():
    from delvjax.reproduce._report import VERDICT_MARK, claims_section

    rows = [
        {"id": f"c{i}", "section": "§1", "quote": "q", "statement": "s", "ours": "1", "verdict": v, "why": "w"}
        for i, v in enumerate(["holds", "partly", "fails", CANNOT_TELL, CANNOT_TELL, "n/a"])
    ]
    text = claims_section(rows)
    assert text.startswith("**1 hold, 1 partly, 1 fail, 2 cannot tell, 1 not run** of 6 claims.")
    assert VERDICT_MARK[CANNOT_TELL] in text and set(VERDICT_MARK) == set(VERDICTS)


def _norm(s: str) -> str:
    return re.sub(r"\s+", " ", s).strip()


@pytest.mark.skipif(not THESIS_TEXT.is_file(), reason="the thesis's plain-text copy is not on this machine")
@pytest.mark.parametrize("claim", thesis.CLAIMS, ids=lambda c: c["id"])
def test_quote_is_verbatim_at_its_line(claim):
    lines = THESIS_TEXT.read_text().split("\n")
    near = _norm(" ".join(lines[claim["line"] - 1 : claim["line"] + 8]))  # a quote may run past a figure caption
    for fragment in claim["quote"].split("..."):
        if _norm(fragment):
            assert _norm(fragment) in near, (claim["id"], fragment)
    first, line = _norm(claim["quote"].split("...")[0])[:40], _norm(lines[claim["line"] - 1])
    assert first in line or line in first  # the quote starts at its line (a table row may be all of the line)


@pytest.mark.skipif(not THESIS_TEXT.is_file(), reason="the thesis's plain-text copy is not on this machine")
def test_new_notes_point_at_their_lines():
    lines = THESIS_TEXT.read_text().split("\n")
    for key, phrase in (
        ("sec6_3_3_warping_inside_outside_hull", "such as warping maintain a similar level of performance"),
        ("sec3_2_4_vs_table5_3", "it does not severely damage the homing rate"),
        ("sec4_2_step_distance_direction", "Small d s might have a slight improvement in"),
    ):
        assert phrase in lines[thesis.NOTES[key]["line"] - 1], key


def test_a_ceiling_is_evidence_when_the_condition_costs_another_method():
    """DELV keeps 100 % with a hidden landmark while ACV and ALV lose half: 'does not severely damage' holds."""
    numbers = tolerate([100.0, 99.9, 84.4], [1.8, 8.7, 18.7], others=(95.8, 44.8, 25.0))
    assert verdict("matching_tolerates_unequal_landmark_numbers", numbers)["verdict"] == "holds"


def test_numbers_of_the_wrong_shape_are_not_applicable_not_a_crash():
    numbers = dict(CASES["occlusion_increases_errors"]["holds"])
    numbers["occlusion:env1:delv-compass:gt45"] = [1.0]  # one k instead of three
    row = verdict("occlusion_increases_errors", numbers)
    assert row["verdict"] == "n/a" and "unusable" in row["why"]


def test_the_smallest_sample_behind_a_verdict_is_the_fewest_observations_read():
    from delvjax.studies.claims import smallest_sample

    flat = {"error_curve:env1:delv": [10.0, 20.0], "n:error_curve:env1:delv": [7, 0, 30]}
    settings = {"spacing": 100.0, "trials": 100}
    assert smallest_sample(["error_curve:env1:delv"], flat, settings) == (7, "7 points in an error-curve bin")
    both = ["success:env1:delv", "map:env1:delv:gt45_pct"]  # 100 trials per distance, 100 cells: a tie
    assert smallest_sample(both, flat, settings)[0] == 100
    assert smallest_sample(both, flat, {"spacing": 200.0, "trials": 100}) == (25, "a 5 × 5 grid")
    assert smallest_sample(["catchment:env1:delv"], flat, {"spacing": 25.0, "trials": 100}) == (1600, "a 40 × 40 grid")
    assert smallest_sample(["fit:objective"], flat, settings) == (float("inf"), "")


def test_claims_on_hull_regions_and_robot_images_state_their_smallest_sample():
    """Issue 52: claims 10, 14, 15 and 16 read numbers of no grid of the run's spacing (the counted grid
    points of a hull region; the robot world's snapshot database): the studies record their samples under
    `n:KEY` (image_matching, robot_images) and the row names what they count."""
    numbers = merge(
        fail_hull(1.6, 44.6, 0.0),
        {"n:fail_inside_hull:env1:warping": [3], "n:fail_outside_hull:env1:warping": [40]},
        {"n:fail_outside_hull:env1:delv": [40]},
        robot_vs(8.0, 20.0, 90.0, 70.0),
        robot(13.0, 8.0, 90.0),
        robot_q(10.0, 12.0),
        {f"n:robot_images:{m}:mean_error_deg": [78] for m in ("delv", "warping")},
        {"n:robot_images:delv:ideal_mean_error_deg": [78]},
        {f"n:robot_images:{m}:catchment_pct": [76] for m in ("delv", "warping")},
        {f"n:robot_images:delv:Q{q}:mean_error_deg": [78] for q in (1, 2, 4, 5)},
    )
    rows = {r["id"]: r for r in claims.evaluate({"synthetic": numbers}, {"spacing": 100.0, "trials": 100})}
    assert rows["warping_fails_outside_hull"]["sample"] == "3 counted grid points in the region"
    assert rows["robot_images_delv_errs_more_but_homes"]["sample"] == "76 releases"
    assert rows["robot_images_delv_beats_warping"]["sample"] == "76 releases"
    assert rows["robot_images_quantized_similar"]["sample"] == "78 database points"


def test_claims_3_and_4_show_the_same_mean_error_at_each_step_distance():
    """Issue 52: 'mean error at d = 20' was 14.9° in claim 3 (the mean of the error curve's bins) and
    14.1° in claim 4 (the vector map's mean error); both read the vector map's now."""
    numbers = merge(steps([[30.0, 10.0, 10.0]] * 4, [90.0, 92.0, 91.0, 89.0]), step_errors(14.1, 11.0, 14.0, 15.0))
    three = verdict("step_distance_rarely_matters", numbers)["ours"]
    four = verdict("small_step_slightly_better", numbers)["ours"]
    assert "14.1/11.0/14.0/15.0°" in three and "14.1/11.0/14.0/15.0°" in four, (three, four)


def test_claim_1_needs_half_the_thesiss_env3_gap():
    """Issue 52: env3 lowest by 8.0 points passed a rule of 17.75 - 10 points by 0.25; half the
    thesis's gap (8.9 points) is needed to hold."""
    assert verdict("delv_nocompass_catchment_all_envs", c_catch_envs(98.0, 98.5, 90.0))["verdict"] == "partly"
    assert verdict("delv_nocompass_catchment_all_envs", c_catch_envs(98.0, 98.5, 89.0))["verdict"] == "holds"


def test_issue_52_verdicts_judge_what_the_sentences_say():
    """Claim 7: 78.6 % of the bins with 11.2° against 58.5° holds (the mean error decides 'significantly').
    Claim 20: overall similar, near at the ceiling, far contradicted: fails (not partly). Claim 33: ALV
    less affected than DELV under every background: fails even where compass noise costs DELV least."""
    w = [40.0] * 3 + [70.0] * 11
    d = [50.0] * 3 + [5.0] * 11  # DELV lower in 11 of 14 bins
    assert verdict("delv_smaller_error_than_warping", warping_err(d, w, 11.2, 58.5))["verdict"] == "holds"
    near_far = success3([100.0] * 3 + [99.0] * 3 + [98.0] * 3, *[[100.0] * 3 + [99.0] * 3 + [92.0] * 3] * 2)
    assert verdict("delv_compass_success_near_far", near_far)["verdict"] == "fails"
    alv_least = dependence([50.0, 60.0, 90.0], [20.0, 10.0, 1.0], [99.0, 50.0, 50.0])
    assert verdict("delv_least_compass_dependent", alv_least)["verdict"] == "fails"


def test_claims_13_31_32_judge_the_layout_and_worlds_their_figures_show():
    """Issue 52: claim 13 compared with env3 (home 135 cm outside the hull) and dropped 'slightly': it reads
    edge4 (home 43 cm outside, Fig 4.14b) and needs 1-10° (the full run: lower by 10.3-11.5°). Claims 31, 32
    read env1 only, which Fig 5.11 need not show: each of env1-3 is judged, the best world decides."""
    row = verdict("surrounding_landmarks_lower_error", SURROUND["partly#full run"])
    assert "not slightly" in row["why"] and "1-10°" in row["why"] and "env3 (135 cm outside, not judged)" in row["ours"]
    why = verdict("visual_compass_catchment_order", ORDER_WORLDS["holds#env3"])["why"]
    assert "world of Figs 5.11-5.12 is not stated" in why and "env1 fails, env2 cannot tell, env3 holds" in why, why
    assert "env1 fails, env2 fails, env3 holds" in verdict("visual_compass_error_order", ERRORS_ON_ENV3)["why"]
