"""Inconsistencies and ambiguities found in the thesis text (re-exported by `delvjax.studies.thesis`).

NOTES maps a short key to the section (chapters 3-6: Eqs 3.1-3.3, Figs 4.11-4.13, 5.4, 5.7,
5.10, Tables 5.1-5.4, §5.3.2, §6.3.3), the 1-based ``line`` in the thesis's plain-text copy and a
one-sentence description. The report lists them (`delvjax.reproduce._report.thesis_notes_section`).
"""

from __future__ import annotations

# ---------------------------------------------------------------------------------------
# 4. Inconsistencies and ambiguities in the thesis.
# ---------------------------------------------------------------------------------------
NOTES = {
    "table5_2_L4_copies_other_rows": {
        "section": "Table 5.2",
        "line": 890,
        "description": "The L = 4 rows of Table 5.2 are copies: DELV (8.75/3.02/13.99/3.62/"
        "20.48/6.49) and ACV (9.80/0.15/42.50/10.07/80.63/33.54) equal Table "
        "5.1's environment 1 rows and ALV (0/0/10.24/2.60/14.91/4.95) equals "
        "Table 5.1's environment 2 row, so no equally spaced L = 4 result exists.",
    },
    "table5_4_L4_copies_other_rows": {
        "section": "Table 5.4",
        "line": 929,
        "description": "The L = 4 rows of Table 5.4 copy Table 5.3 the same way: DELV "
        "(92.01/49.11/40.3) and ACV (100/52.88/24.14) are environment 1's and ALV "
        "(100/17.09/23.10) is environment 2's (environment 1's ALV is "
        "100/7.84/20.44).",
    },
    "fig5_10_vs_table5_3": {
        "section": "§5.3.1, Fig 5.10 vs Table 5.3",
        "line": 857,
        "description": "Fig 5.10's caption gives DELV-compass catchment 92.01/82.04/59.11 % "
        "for environment 1 with 0/1/2 hidden landmarks, but Table 5.3 and the "
        "text (line 902) give 92.01/49.11/40.3 % for the same case.",
    },
    "fig5_10_occlusion_count": {
        "section": "§5.3.1, Fig 5.10",
        "line": 859,
        "description": "The caption says zero, one and two landmarks are hidden in Fig 5.10 "
        "(a)-(c), while the text says 'one, two and three' (and (a) is 92.01 %, "
        "the no-occlusion value).",
    },
    "table5_2_L5_duplicate_columns": {
        "section": "Table 5.2",
        "line": 893,
        "description": "For L = 5 the 2-hidden and 3-hidden columns are identical for DELV "
        "(27.19/9.21) and ACV (86.10/39.27) while ALV's differ, which looks like "
        "a copied column.",
    },
    "table5_2_L6_acv_k3": {
        "section": "Table 5.2",
        "line": 897,
        "description": "For L = 6 ACV's 3-hidden entry (27.90/7.09) almost equals DELV's "
        "(27.95/7.10) and is far below ACV's 2-hidden entry (51.43/18.25), which "
        "is implausible and may be a transcription error.",
    },
    "table5_4_L3_delv_100": {
        "section": "Table 5.4",
        "line": 926,
        "description": "DELV's catchment for L = 3 rises from 94.82 % with all landmarks "
        "visible to 100 % with one of three hidden, the only increase to 100 % "
        "under occlusion in the tables.",
    },
    "table5_4_k3_delv_equal": {
        "section": "Table 5.4",
        "line": 932,
        "description": "DELV's 3-hidden catchment is 2.96 % for both L = 5 and L = 6 (two and "
        "three landmarks left), a suspicious coincidence.",
    },
    "alv_catchment_nonmonotone": {
        "section": "Tables 5.3-5.4",
        "line": 907,
        "description": "ALV's catchment is larger with two hidden landmarks than with one in "
        "env1 (7.84 -> 20.44), env2 (17.09 -> 23.10), L=3 (9.82 -> 10.36), L=5 "
        "(12.46 -> 18.73) and L=6 (13.74 -> 34.05), contrary to 'rapidly "
        "decreases' (line 917); only env3 decreases.",
    },
    "error_points_nonmonotone": {
        "section": "Tables 5.1-5.2",
        "line": 893,
        "description": "DELV's >45 error rate falls when a landmark is hidden for L = 5 "
        "(13.29 -> 12.39) and L = 6 (19.94 -> 16.31 -> 18.43), and several >90 "
        "rates fall too (env2 4.07 -> 4.00, env3 3.92 -> 3.24, L=3 2.69 -> 0.75), "
        "whereas line 861 says errors increase with occlusion.",
    },
    "sec5_2_env1_compass_sentence": {
        "section": "§5.2",
        "line": 819,
        "description": "The text says that in environment 1 'the DELV method showed even better "
        "performance than without the reference compass', but the numbers are "
        "92.01 % with and 98.52 % without the compass, so the sentence can only "
        "mean that DELV without the compass did better.",
    },
    "sec5_3_1_surround_vs_table5_1": {
        "section": "§5.3.1",
        "line": 881,
        "description": "The text says DELV performs better when landmarks surround home, but "
        "in Table 5.1 DELV's lowest error rate is in environment 3 (all landmarks "
        "on one side, 6.79 %) and in Table 5.2 its error grows with the number of "
        "equally spaced landmarks (5.23 -> 19.94 % for L = 3 -> 6).",
    },
    "sec5_3_1_delv_vs_acv_error_rate": {
        "section": "§5.3.1",
        "line": 879,
        "description": "'DELV exhibits a smaller error rate' than ACV holds for >45 deg in most "
        "cells but not for env2 k=0 (7.99 = 7.99), L=5 k=0 (13.29 > 13.14), L=6 "
        "k=3 (27.95 > 27.90), and for >90 deg without occlusion ACV is lower "
        "in every layout (env1 0.15 vs 3.02, L=3 2.09 vs 2.69).",
    },
    "sec5_3_1_small_occlusion": {
        "section": "§5.3.1",
        "line": 919,
        "description": "'With small occlusions, the ACV and ALV approach exhibits better homing "
        "ability' contradicts the tables for ALV (one hidden: 7.84 vs DELV 49.11 "
        "% in env1) and for ACV in env3 / L = 3, 5, 6; it holds only without "
        "occlusion, or for ACV with one hidden in env1/env2.",
    },
    "sec5_3_1_alv_vs_delv_k3": {
        "section": "§5.3.1, Table 5.4",
        "line": 917,
        "description": "'the catchment area of the ALV method is much smaller than those of the "
        "DELV method when landmarks were occluded' fails for three hidden "
        "landmarks (L=5: ALV 8.98 vs DELV 2.96; L=6: 11.74 vs 2.96).",
    },
    "sec4_3_quantization_levels": {
        "section": "§4.3, Figs 4.12-4.13",
        "line": 618,
        "description": "Which quantization levels were compared is unclear: Fig 4.12 shows "
        "levels 3-5, Fig 4.13's caption says levels 1 to 5, the text says levels "
        "1, 2 and 5 (plus the warping method), and Fig 4.13b 'for each method'.",
    },
    "sec4_3_catchment_not_printed": {
        "section": "§4.3, Fig 4.12",
        "line": 622,
        "description": "The text refers to 'the catchment area in Figure 4.12' for quantized "
        "DELV, but no catchment percentage is given in the caption or the text.",
    },
    "fig5_4_caption": {
        "section": "§5.2, Fig 5.4",
        "line": 803,
        "description": "Fig 5.4's caption refers only to the vector maps of Fig 4.2 (no "
        "compass) although the text says it shows both Fig 4.2 and Fig 5.2 "
        "(with compass) results.",
    },
    "sec5_3_both_methods": {
        "section": "§5.3, Fig 5.7",
        "line": 825,
        "description": "The text says Fig 5.7a 'shows the angular errors for both methods' and "
        "5.7b 'similar level of performance in both methods' while three methods "
        "(DELV, ACV, ALV) are compared.",
    },
    "environment_unstated": {
        "section": "Figs 4.9-4.11, 4.13, 5.6-5.8, 5.11-5.12",
        "line": 825,
        "description": "The landmark layout of the method comparisons (DELV vs warping, "
        "DELV vs ACV vs ALV, visual compass) is never stated; CATCHMENT['fig5_11'] "
        "is keyed 'env1' by assumption only.",
    },
    "occlusion_choice_unstated": {
        "section": "§5.3.1",
        "line": 847,
        "description": "The thesis does not say which landmarks were hidden or whether results "
        "are averaged over the choices ('artificially removing one of the "
        "landmarks'), although the tables go up to three hidden landmarks.",
    },
    "success_criterion_unstated": {
        "section": "§4.2-4.3",
        "line": 622,
        "description": "Success is 'reached home' within 50 moves, but the home radius, the "
        "grid spacing of the catchment maps and the release distances of the "
        "success-rate plots are not given.",
    },
    "visual_compass_background_unstated": {
        "section": "§5.3.2",
        "line": 943,
        "description": "The visual compass needs a textured background ('appropriate background "
        "settings of the simulation environment are required') but the "
        "background used is not described.",
    },
    "acv_sum_vs_average": {
        "section": "§5.1, Eq 5.2",
        "line": 753,
        "description": "The text says the correction vectors 'are then averaged' while Eq 5.2 "
        "sums them (HV = sum CV_i); only the direction matters for homing.",
    },
    "eq3_1_3_3_typo": {
        "section": "§3.2.1-3.2.3, Eqs 3.1-3.3",
        "line": 297,
        "description": "Eq 3.3 for the reference-map distance R' has sin(theta - psi) in the "
        "denominator, inconsistent with Eq 3.1 (which gives sin(delta + psi)); "
        "docs/model.md §3.1 treats it as a typo and derives R_P from the sine law.",
    },
    "alv_100_needs_no_collisions": {
        "section": "Tables 5.3-5.4",
        "line": 905,
        "description": "ALV's 100 % catchment in every environment implies that rollouts "
        "ignored collisions with landmarks and exits from the arena (docs/model.md §5 "
        "default collisions = 'ignore'); the thesis does not say so.",
    },
    "sec6_3_3_warping_inside_outside_hull": {
        "section": "§6.3.3 vs §4.2, Fig 4.11",
        "line": 1029,
        "description": "§6.3.3 says the image-based matching methods 'such as warping maintain a similar "
        "level of performance' inside and outside the area surrounded by landmarks, while "
        "§4.2 (line 596) says predictive image matching 'often has difficulty in locating "
        "the nest when the robot is in the outer zone of the landmark convex hull', as its "
        "trajectories in Fig 4.11 (line 592) show.",
    },
    "sec3_2_4_vs_table5_3": {
        "section": "§3.2.4 vs §5.3.1, Table 5.3",
        "line": 323,
        "description": "§3.2.4 says a different number of landmarks in the two views 'does not severely "
        "damage the homing rate', but with one landmark hidden DELV's catchment falls from "
        "92.01 to 49.11 % (env1) and from 97.04 to 53.96 % (env2) in Table 5.3, and §5.3.1 "
        "(line 902) calls the decrease severe.",
    },
    "sec4_2_step_distance_direction": {
        "section": "§4.2, Figs 4.6-4.7",
        "line": 552,
        "description": "The text says small step distances d 'might have a slight improvement in the "
        "variance of the error or the angular error itself', then (line 559) that 'it is "
        "advantageous to increase d', which would 'reduce the estimation errors'.",
    },
}
