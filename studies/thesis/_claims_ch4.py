"""The thesis's claims about its chapter 4 simulations (DELV without compass, §4.2-4.5).

Figs 4.3-4.14: catchment per environment, step distance, arbitrary layouts, DELV against
predictive image matching, distance quantization. Each claim has its id, section, ``line``,
a verbatim quote, the statement our results must show and the quantities it needs; see
`delvjax.studies.thesis` (the module to import from), whose CLAIMS puts these first.
"""

from __future__ import annotations

# ---------------------------------------------------------------------------------------
# 5. Claims about the simulation results, chapter 4 (verbatim quotes; "..." marks omissions).
# ---------------------------------------------------------------------------------------
CLAIMS_CH4 = [
    {
        "id": "delv_nocompass_catchment_all_envs",
        "section": "§4.2, Fig 4.5",
        "line": 548,
        "quote": "Based on the results of angular errors and catchment area, the DELV shows "
        "good performance in various environments. Although it seems to be affected by "
        "the distribution of landmarks, they show sufficient level of success rate in "
        "homing.",
        "statement": "DELV without compass has a large catchment in env1, env2 and env3 "
        "(thesis 98.52 / 95.41 / 77.66 %), lowest in env3 where all landmarks lie "
        "on one side of home, by a margin near the thesis's (17.75 points, tolerance 10).",
        "needs": ["catchment:env1:delv", "catchment:env2:delv", "catchment:env3:delv"],
    },
    {
        "id": "errors_outside_landmark_hull",
        "section": "§4.2, Fig 4.3",
        "line": 600,
        "quote": "The amount of error inside the landmark surrounded-area is almost zero, while "
        "the point with errors are main located outside the area, where the agent "
        "might not see every landmark in its view.",
        "statement": "For DELV without compass the share of grid points with error > 45 deg is "
        "near 0 inside the convex hull of the landmarks and the error points lie "
        "mostly outside it (env1-env3).",
        "needs": [
            "error_points_gt45:env1:delv:inside_hull",
            "error_points_gt45:env1:delv:outside_hull",
            "error_points_gt45:env2:delv:inside_hull",
            "error_points_gt45:env2:delv:outside_hull",
        ],
    },
    {
        "id": "step_distance_rarely_matters",
        "section": "§4.2, Fig 4.6-4.7",
        "line": 552,
        "quote": "The angular errors do not differ by a large amount with varying moving "
        "distances d . This shows that the moving distance rarely affects the "
        "performance of the method.",
        "statement": "DELV's mean angular errors (vector map, the numbers of the next claim) for d = 20, "
        "50, 100 and 150 cm lie close together (no d errs clearly more), and so do their catchments "
        "(the thesis: 'very similar patterns in terms of homing performance').",
        "needs": [
            "map:env1:delv:d=20:mean_error_deg",
            "map:env1:delv:d=50:mean_error_deg",
            "map:env1:delv:d=100:mean_error_deg",
            "map:env1:delv:d=150:mean_error_deg",
            "catchment:env1:delv:d=20..150",
        ],
    },
    {
        "id": "small_step_slightly_better",
        "section": "§4.2, Figs 4.6-4.7",
        "line": 552,
        "quote": "Small d s might have a slight improvement in ... the variance of the error or the angular "
        "error itself, but the overall performance in the homing direction has similar patterns.",
        "statement": "DELV without compass with small steps (d = 20, 50 cm) has a slightly (1-10 deg) lower mean "
        "angular error than with large steps (d = 100, 150 cm), env1.",
        "needs": [
            "map:env1:delv:d=20:mean_error_deg",
            "map:env1:delv:d=50:mean_error_deg",
            "map:env1:delv:d=100:mean_error_deg",
            "map:env1:delv:d=150:mean_error_deg",
        ],
    },
    {
        "id": "few_landmarks_error_below_90",
        "section": "§4.2, Fig 4.8f",
        "line": 568,
        "quote": "the method can effectively operate in the environments with asymmetric and "
        "unbalanced distribution of landmarks and various landmark numbers as well. "
        "... At a distance far from the nest, the angular errors are large but still "
        "smaller than 90° .",
        "statement": "In arbitrary layouts of 3, 4 and 5 landmarks DELV without compass has mean "
        "angular error below 90 deg in every distance bin, larger far from home.",
        "needs": ["error_curve:arbitrary3:delv", "error_curve:arbitrary4:delv", "error_curve:arbitrary5:delv"],
    },
    {
        "id": "warping_sensitive_to_landmark_number",
        "section": "§4.1",
        "line": 508,
        "quote": "However, the predictive image matching method is extremely sensitive to the captured image "
        "of the surroundings and the number of landmarks in the environment. With few landmarks in the "
        "snapshot image, there is a high probability that the robot could misjudge its direction to home",
        "statement": "In the arbitrary layouts of 3, 4 and 5 landmarks (Fig 4.8) predictive image matching errs at "
        "least 10 deg more with 3 landmarks than with 5, and its mean error varies with the number "
        "of landmarks at least twice as much as DELV's.",
        "needs": [
            "error_curve:random3:warping",
            "error_curve:random4:warping",
            "error_curve:random5:warping",
            "error_curve:random3:delv",
            "error_curve:random4:delv",
            "error_curve:random5:delv",
        ],
    },
    {
        "id": "delv_smaller_error_than_warping",
        "section": "§4.2, Fig 4.10a",
        "line": 596,
        "quote": "The DELV method suggested provides significantly smaller angular errors than "
        "the predictive image-matching method do.",
        "statement": "DELV without compass has a clearly lower mean angular error than predictive "
        "image matching (warping) in (nearly) every distance bin, same environment.",
        "needs": ["error_curve:env1:delv", "error_curve:env1:warping"],
    },
    {
        "id": "delv_success_over_90",
        "section": "§4.2, Fig 4.10b",
        "line": 600,
        "quote": "Our suggested method determines the goal point with a success rate greater "
        "than 90% (see Figure 4.10 (b)). For the suggested landmark-matching method, "
        "the worsening performance at a far distance from the nest is related to the "
        "occlusion of landmarks.",
        "statement": "DELV without compass succeeds in > 90 % of 100 trials at every release "
        "distance (50..450 cm), the lowest rates at the largest distances.",
        "needs": ["success_rate:env1:delv:by_distance"],
    },
    {
        "id": "delv_beats_warping_success",
        "section": "§4.2, Fig 4.10b; §4.5",
        "line": 735,
        "quote": "Comparison to the predictive image-matching method indicated that the "
        "suggested method has a higher probability of resulting in a successful return "
        "to home.",
        "statement": "DELV without compass has a higher success rate than predictive image "
        "matching at every release distance (and a larger catchment).",
        "needs": [
            "success_rate:env1:delv:by_distance",
            "success_rate:env1:warping:by_distance",
            "catchment:env1:delv",
            "catchment:env1:warping",
        ],
    },
    {
        "id": "warping_fails_outside_hull",
        "section": "§4.2, Fig 4.11",
        "line": 596,
        "quote": "The predictive image-matching approach often has difficulty in locating the "
        "nest when the robot is in the outer zone of the landmark convex hull.",
        "statement": "Predictive image matching fails more often from release points outside "
        "the landmarks' convex hull than from inside, and more often there than "
        "DELV.",
        "needs": [
            "success:env1:warping:outside_hull",
            "success:env1:warping:inside_hull",
            "success:env1:delv:outside_hull",
        ],
    },
    {
        "id": "quantized_error_small_and_level_insensitive",
        "section": "§4.3, Fig 4.13a",
        "line": 618,
        "quote": "as can be seen in Figure 4.13 (a), the error mostly remains less than 30 "
        "degrees. Interestingly, the angular errors do not change much depending on "
        "whether continuous or discretized distances",
        "statement": "DELV without compass with quantized distances (levels 1, 2, 5; caption: "
        "1-5) has mean angular error below 30 deg in most distance bins, and its "
        "error curves lie close to the curve with continuous distances.",
        "needs": ["error_curve:env1:delv:Q=1..5", "error_curve:env1:delv:continuous"],
    },
    {
        "id": "fewer_levels_more_failures_three_suffice",
        "section": "§4.5 (Figs 4.12-4.14)",
        "line": 729,
        "quote": "The larger number of failures in homing resulted from smaller number of "
        "quantization levels leading to error in localization. ... Three-level "
        "quantization of each landmark distance is sufficient to guide the robot home "
        "in many cases shown.",
        "statement": "DELV's homing success rate / catchment decreases as the number of "
        "quantization levels decreases (level 1 worst), while 3 levels already come "
        "close to continuous distances.",
        "needs": [
            "success_rate:env1:delv:Q=1..5",
            "success_rate:env1:delv:continuous",
            "catchment:env1:delv:Q=1..5",
            "catchment:env1:delv:continuous",
        ],
    },
    {
        "id": "surrounding_landmarks_lower_error",
        "section": "§4.3, Fig 4.14",
        "line": 624,
        "quote": "The homing vector results show low angular errors in various environments, "
        "with slightly smaller error if the landmarks surrounded home location "
        "perfectly as in (a).",
        "statement": "With level-3 quantized DELV, layouts of equally spaced landmarks "
        "surrounding home (Fig 4.14a) give a slightly (1-10 deg) lower mean angular error than a "
        "layout with home slightly outside the landmarks' convex hull (Fig 4.14b; ours: edge4, "
        "home 43 cm outside the hull of the centres).",
        "needs": [
            "mean_error:env2:delv:Q=3",
            "mean_error:ring3:delv:Q=3",
            "mean_error:ring6:delv:Q=3",
            "mean_error:edge4:delv:Q=3",
        ],
    },
    {
        "id": "robot_images_delv_errs_more_but_homes",
        "section": "§4.4.1, Figs 4.18-4.19",
        "line": 664,
        "quote": "The angular errors of DELV in real environment were greater than those in the simulation "
        "environments, most likely due to the landmark detection error from the snapshot images. "
        "However, the method still showed good performance in terms of returning to the target location "
        "because the angular errors were relatively small to allow for navigation to the nest.",
        "statement": "On images of the robot arena DELV errs more than on the ideal rings of the same layout, and "
        "still homes from most release points (nearest-snapshot catchment >= 75 %).",
        "needs": [
            "robot_images:delv:mean_error_deg",
            "robot_images:delv:ideal_mean_error_deg",
            "robot_images:delv:catchment_pct",
        ],
    },
    {
        "id": "robot_images_delv_beats_warping",
        "section": "§6.2 (and §4.5, §6.3.1; robot images of §4.4.1, Figs 4.18-4.19)",
        "line": 1003,
        "quote": "While it requires an additional process of the landmark extraction compared to the predictive "
        "image-matching method, the DELV method poses a significantly smaller error in the homing "
        "vector results and in the homing success rate as well.",
        "statement": "On the images of the robot arena DELV errs less than predictive image matching and homes "
        "at least as often (image matching must not beat DELV by more than 2 deg of mean error or "
        "2 points of catchment).",
        "needs": [
            "robot_images:delv:mean_error_deg",
            "robot_images:warping:mean_error_deg",
            "robot_images:delv:catchment_pct",
            "robot_images:warping:catchment_pct",
        ],
    },
    {
        "id": "robot_images_quantized_similar",
        "section": "§4.4.1, Figs 4.20-4.21",
        "line": 689,
        "quote": "The error level compared to those in Figure 4.19 did not show significant increase, however, "
        "and maintained similar level of errors with respect to the quantization level.",
        "statement": "On the robot images, DELV with 1, 2, 4 and 5 distance levels errs about as much as with "
        "continuous distances (mean error within 10 deg of it).",
        "needs": ["robot_images:delv:Q=1,2,4,5:mean_error_deg", "robot_images:delv:mean_error_deg"],
    },
]
