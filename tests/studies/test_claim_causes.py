"""The causes a claim's why text names when a part of the claim breaks (issue 22: every remaining gap
explained): each is read from the run's numbers, appears when those numbers show it, and stays away
when they show something else. Pure Python, synthetic numbers (as tests/studies/test_claim_checks.py)."""

from __future__ import annotations

from tests.cases.claims import (
    E3,
    FALLING,
    OURS_PHYSICAL,
    compass_err,
    flat,
    merge,
    random_curves,
    step_errors,
    steps,
    success,
    success3,
    verdict,
)


def _flat(key: str, counts: dict) -> dict:
    """Failure counts as the studies record them (`runs._common.record_failures`)."""
    return {f"{key}:{o}": v for o, v in counts.items()}


def _step_loss(fails: dict, wide: float | None = 100.0) -> dict:
    numbers = merge(
        steps([flat(10)] * 4, [100.0, 100.0, 100.0, 85.7]),
        *[
            _flat(f"catchment_failures:env1:delv:d={d}", {"timeout": 0, "landmark": 0, "arena": 0})
            for d in (20, 50, 100)
        ],
        _flat("catchment_failures:env1:delv:d=150", fails),
        {"step_distance:home_radius_cm": 50.0},
    )
    if wide is not None:
        numbers["catchment:env1:delv:d=150:home_radius=75"] = wide
    return numbers


def test_a_long_step_that_jumps_over_home_is_named_with_its_timeouts():
    why = verdict("step_distance_rarely_matters", _step_loss({"timeout": 20, "landmark": 0, "arena": 0}))["why"]
    assert "d = 150 cm: 20 of its 20 failures time out" in why
    assert "jump over the home disc" in why and "home radius of 75 cm d = 150 cm keeps 100.0 %" in why


def test_landmark_hits_are_not_called_a_jump_over_home():
    why = verdict("step_distance_rarely_matters", _step_loss({"timeout": 5, "landmark": 15, "arena": 0}))["why"]
    assert "5 of its 20 failures time out" in why and "jump over" not in why


def test_short_steps_blamed_on_pixels_only_when_d20_errs_most():
    assert "d = 20 cm errs most" in verdict("small_step_slightly_better", step_errors(12.2, 10.3, 9.2, 12.2))["why"]
    assert "errs most" not in verdict("small_step_slightly_better", step_errors(10.3, 12.2, 9.2, 12.2))["why"]


def test_errors_largest_near_home_get_their_cause():
    why = verdict("few_landmarks_error_below_90", random_curves("delv", [FALLING] * 3))["why"]
    assert "near home the home vector is short" in why


def test_compass_gaps_name_the_wrong_heading_hypotheses():
    numbers = merge(
        {f"map:{e}:delv-compass:mean_error_deg": v for e, v in zip(E3, (7.9, 7.6, 11.1))},
        {f"map:{e}:delv:mean_error_deg": v for e, v in zip(E3, (10.3, 6.7, 31.3))},
        {f"map:{e}:delv:heading_slip_pct": v for e, v in zip(E3, (0.5, 0.0, 14.9))},
        {f"map:{e}:delv:mean_error_without_slips_deg": v for e, v in zip(E3, (9.8, 6.7, 17.0))},
    )
    row = verdict("compass_slightly_smaller_error", numbers)
    assert row["verdict"] == "partly"
    assert "a wrong heading hypothesis wins at env3 14.9 % of the points (mean error 17.0° at the others)" in row["why"]
    assert "not smaller in env2 (without compass no wrong heading wins there: env2 0.0 %" in row["why"]
    plain = verdict("compass_slightly_smaller_error", compass_err(7.0, 10.0))
    assert plain["verdict"] == "holds" and "heading" not in plain["why"]


def test_far_failures_under_the_physical_rules_are_counted():
    numbers = merge(
        success([100.0] * 9, OURS_PHYSICAL),
        _flat("success_failures_far:env1:delv:physical", {"timeout": 2, "landmark": 40, "arena": 0}),
    )
    row = verdict("delv_success_over_90", numbers)
    assert row["verdict"] == "partly" and "40 of the 42 failures of the far 3 distances" in row["why"]
    assert "failures of the far" not in verdict("delv_success_over_90", success([100.0] * 9, OURS_PHYSICAL))["why"]


def test_delv_as_good_far_away_names_what_ends_the_others_trials():
    far_ok = [100.0] * 6 + [95.0] * 3
    numbers = merge(
        success3(far_ok, [100.0] * 6 + [90.0] * 3, [100.0] * 9),
        _flat("success_failures_far:env1:delv-compass", {"timeout": 15, "landmark": 0, "arena": 0}),
        _flat("success_failures_far:env1:acv", {"timeout": 30, "landmark": 0, "arena": 0}),
        _flat("success_failures_far:env1:alv", {"timeout": 0, "landmark": 0, "arena": 0}),
    )
    why = verdict("delv_compass_success_near_far", numbers)["why"]
    assert (
        "far from home DELV succeeds at least as often as ACV (failures timeout/landmark/arena of the far 3 "
        "distances: DELV 15/0/0, ACV 30/0/0" in why
    )


def test_delv_and_alv_that_do_not_mix_name_alvs_steady_error():
    delv = [18.0] + [6.0] * 13
    alv = [10.7, 8.7] + [10.0] * 12
    acv = [10.0 + 2 * i for i in range(14)]
    numbers = {"error_curve:env1:delv-compass": delv, "error_curve:env1:acv": acv, "error_curve:env1:alv": alv}
    why = verdict("delv_vs_acv_alv_error_mixed", numbers)["why"]
    assert "ALV errs 9-11° in every bin" in why and "higher only in the nearest 1 bin (" in why
    numbers["error_curve:env1:delv-compass"] = [6.0] * 7 + [18.0] + [6.0] * 6  # higher far out: another story
    assert "ALV errs" not in verdict("delv_vs_acv_alv_error_mixed", numbers)["why"]


def test_env2s_hull_is_named_a_square_around_home_not_a_thin_region_at_the_edge():
    """Issue 52: claim 2's cause called env2's hull (a square of landmarks around home) 'a thin region at
    the edge'; that is env3's, whose home lies outside its hull."""
    from tests.cases.claims import hull

    numbers = hull(0.5, 5.0)
    numbers.update({"map:env2:delv:gt45_inside_hull_pct": 5.2, "map:env2:delv:gt45_outside_hull_pct": 1.1})
    why = verdict("errors_outside_landmark_hull", numbers)["why"]
    assert "not in env2: its hull surrounds home" in why and "1440 pixels" in why, why
    assert "thin region" not in why and "env3" not in why.split("Rule:")[0].replace("(env2", ""), why
    numbers.update({"map:env3:delv:gt45_inside_hull_pct": 24.5, "map:env3:delv:gt45_outside_hull_pct": 20.2})
    why = verdict("errors_outside_landmark_hull", numbers)["why"]
    assert "not in env3: home lies outside its hull, a thin region" in why, why
