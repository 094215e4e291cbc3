"""What the thesis reports for its simulation experiments, as plain data.

Source: Seung-Eun Yu, "Distance-Estimated Landmark Vector Model for Vision-Based Homing
Navigation" (PhD thesis), in the plain-text copy the project works from. Every
``line`` below is a 1-based line number in that file (``sed -n Np`` prints it). Chapters 4
(DELV without compass, predictive image matching) and 5 (DELV with compass, ACV, ALV,
occlusion, visual compass) hold the simulation results; chapter 6 summarises them.
Robotic-experiment numbers (§4.4) are kept apart in ``OTHER["robotic"]``.

Contents
--------
CATCHMENT       catchment area in % of the grid, ``CATCHMENT[source][env][method]`` is a list
                indexed by k = number of hidden (occluded) landmarks, k = 0, 1, 2(, 3). Only
                the k the thesis prints are listed (its "-" cells are left out).
CATCHMENT_SOURCES  where each top-level key of CATCHMENT comes from (section, caption, line).
ERROR_POINTS    error point rate in % of grid points, Tables 5.1 and 5.2:
                ``ERROR_POINTS[table][env][method] = {"gt45": [...k], "gt90": [...k]}``
                (angular error > 45 deg and > 90 deg).
ERROR_POINTS_SOURCES  where each table comes from.
OTHER           every other number the thesis prints about its simulations (thresholds
                quoted in the text, parameters of the runs), each with its source, plus the
                list of figures whose numbers the thesis does not print.
NOTES           inconsistencies and ambiguities found in the thesis text, each with its
                section, line and a one-sentence description.
CLAIMS          the qualitative / quantitative claims about the simulation results, each
                with a verbatim quote (shortened with "..." only), its line, a precise
                statement of what our results must show for the claim to hold, and the
                result quantities needed (``quantity:env:method[:detail]``).

Keys
----
Methods: "delv" (DELV without compass, arrangement matching of the heading),
"delv-compass" (DELV with the true compass), "acv" (average correction vector, compass),
"alv" (average landmark vector, compass), "delv-visual" / "acv-visual" / "alv-visual" (the
compass replaced by the visual compass, §5.3.2), "warping" (predictive image matching of
Franz et al. 1998). Environments: "env1" (four landmarks around home, asymmetric), "env2"
(four at 90 deg), "env3" (four on one side of home), "ring3".."ring6" (L = 3..6 equally
spaced landmarks, Tables 5.2 / 5.4). NB: the thesis's L = 4 rows of Tables 5.2 and 5.4 are
copies of env1 / env2 rows (see NOTES), they are stored here as printed under "ring4".
In chapter 5 every DELV number is with the compass ("delv-compass"); the ACV / ALV numbers
of Tables 5.1-5.4 use the true compass ("acv", "alv").

The thesis gives no landmark coordinates, grid spacing or home radius; docs/model.md §6 says the
claims to check are the trends (who beats whom, how fast each degrades), not the digits.
"""

from __future__ import annotations

THESIS_TITLE = "Distance-Estimated Landmark Vector Model for Vision-Based Homing Navigation"

# ---------------------------------------------------------------------------------------
# 1. Catchment area (%), lists indexed by k = number of hidden landmarks.
# ---------------------------------------------------------------------------------------
CATCHMENT = {
    "fig4_5": {  # DELV without compass, continuous distances
        "env1": {"delv": [98.52]},
        "env2": {"delv": [95.41]},
        "env3": {"delv": [77.66]},
    },
    "fig5_5": {  # DELV with the true compass
        "env1": {"delv-compass": [92.01]},
        "env2": {"delv-compass": [97.04]},
        "env3": {"delv-compass": [84.91]},
    },
    "table5_3": {
        "env1": {
            "delv-compass": [92.01, 49.11, 40.3],
            "acv": [100.0, 52.88, 24.14],
            "alv": [100.0, 7.84, 20.44],
        },
        "env2": {
            "delv-compass": [97.04, 53.96, 51.86],
            "acv": [100.0, 54.99, 25.47],
            "alv": [100.0, 17.09, 23.10],
        },
        "env3": {
            "delv-compass": [84.91, 69.08, 62.34],
            "acv": [98.67, 45.34, 18.46],
            "alv": [100.0, 23.15, 20.59],
        },
    },
    "table5_4": {
        "ring3": {  # k = 3 printed as "-"
            "delv-compass": [94.82, 100.0, 17.46],
            "acv": [99.56, 8.28, 5.62],
            "alv": [100.0, 9.82, 10.36],
        },
        "ring4": {  # AS PRINTED: copies Table 5.3 env1 (DELV, ACV) and env2 (ALV), see NOTES
            "delv-compass": [92.01, 49.11, 40.3],
            "acv": [100.0, 52.88, 24.14],
            "alv": [100.0, 17.09, 23.10],
        },
        "ring5": {
            "delv-compass": [87.43, 87.13, 83.58, 2.96],
            "acv": [91.12, 85.06, 54.14, 1.78],
            "alv": [100.0, 12.46, 18.73, 8.98],
        },
        "ring6": {
            "delv-compass": [85.65, 84.32, 70.71, 2.96],
            "acv": [87.28, 77.96, 66.57, 3.4],
            "alv": [100.0, 13.74, 34.05, 11.74],
        },
    },
    "fig5_10": {  # caption: k = 0, 1, 2 (the text says 1, 2, 3); disagrees with Table 5.3
        "env1": {"delv-compass": [92.01, 82.04, 59.11]},
    },
    "fig5_11": {  # visual compass; environment not stated (assumed env1, see NOTES)
        "env1": {"delv-visual": [74.85], "acv-visual": [47.04], "alv-visual": [40.68]},
    },
    # Text of §5.3.1 (line 902), consistent with Table 5.3 env1; ACV k=0 only "almost 100%".
    "text5_3_1": {
        "env1": {"delv-compass": [92.01, 49.11], "acv": [100.0, 52.88]},
    },
}

CATCHMENT_SOURCES = {
    "fig4_5": {"section": "§4.2, Fig 4.5", "line": 546,
               "text": "Figure 4.5: Catchment area with vector map for each environment. "
                       "(a) 98.52%, (b) 95.41%, and (c) 77.66% of the environment."},
    "fig5_5": {"section": "§5.2, Fig 5.5", "line": 808,
               "text": "Figure 5.5: ... (a) 92.01%, (b) 97.04%, and (c) 84.91% of the "
                       "environment. (repeated in the text, line 819)"},
    "table5_3": {"section": "§5.3.1, Table 5.3", "line": 905,
                 "text": "Table 5.3: Catchment area rate(%) for each environments with "
                         "different landmark distribution (rows at lines 905-913)"},
    "table5_4": {"section": "§5.3.1, Table 5.4", "line": 926,
                 "text": "Table 5.4: Catchment area rate(%) for each environments with "
                         "different landmark number (rows at lines 926-937; '-' for L=3,4 k=3)"},
    "fig5_10": {"section": "§5.3.1, Fig 5.10", "line": 857,
                "text": "Figure 5.10: Catchment area with vector map for each environment: "
                        "(a) 92.01%, (b) 82.04%, and (c) 59.11% of the environment. The number "
                        "of landmarks is zero for (a) and one, two for (b) and (c)"},
    "fig5_11": {"section": "§5.3.2, Fig 5.11", "line": 948,
                "text": "Catchment areas for each case are 74.85%, 47.04%, and 40.68%, "
                        "respectively (also in the text, line 954)"},
    "text5_3_1": {"section": "§5.3.1", "line": 902,
                  "text": "with almost 100% than does the DELV method (92.01%). ... the "
                          "catchment area percentages are 49.11% for DELV and 52.88% for ACV"},
}

# ---------------------------------------------------------------------------------------
# 2. Error point rate (%): share of grid points with angular error > 45 / > 90 degrees.
# ---------------------------------------------------------------------------------------
ERROR_POINTS = {
    "table5_1": {
        "env1": {
            "delv-compass": {"gt45": [8.75, 13.99, 20.48], "gt90": [3.02, 3.62, 6.49]},
            "acv": {"gt45": [9.80, 42.50, 80.63], "gt90": [0.15, 10.07, 33.54]},
            "alv": {"gt45": [0.00, 8.64, 12.07], "gt90": [0.00, 1.92, 3.34]},
        },
        "env2": {
            "delv-compass": {"gt45": [7.99, 13.61, 20.15], "gt90": [4.07, 4.00, 6.33]},
            "acv": {"gt45": [7.99, 39.37, 74.33], "gt90": [0.15, 8.71, 36.32]},
            "alv": {"gt45": [0.00, 10.24, 14.91], "gt90": [0.00, 2.60, 4.95]},
        },
        "env3": {
            "delv-compass": {"gt45": [6.79, 8.33, 14.78], "gt90": [3.92, 3.24, 4.68]},
            "acv": {"gt45": [33.33, 53.47, 73.88], "gt90": [2.71, 12.18, 27.63]},
            "alv": {"gt45": [0.00, 4.87, 8.74], "gt90": [0.00, 1.40, 2.19]},
        },
    },
    "table5_2": {
        "ring3": {  # k = 3 printed as "-"
            "delv-compass": {"gt45": [5.23, 6.43, 36.62], "gt90": [2.69, 0.75, 9.12]},
            "acv": {"gt45": [23.77, 42.75, 84.3], "gt90": [2.09, 12.11, 28.25]},
            "alv": {"gt45": [0.00, 13.62, 27.00], "gt90": [0.00, 5.94, 7.29]},
        },
        "ring4": {  # AS PRINTED: copies Table 5.1 env1 (DELV, ACV) and env2 (ALV), see NOTES
            "delv-compass": {"gt45": [8.75, 13.99, 20.48], "gt90": [3.02, 3.62, 6.49]},
            "acv": {"gt45": [9.80, 42.50, 80.63], "gt90": [0.15, 10.07, 33.54]},
            "alv": {"gt45": [0.00, 10.24, 14.91], "gt90": [0.00, 2.60, 4.95]},
        },
        "ring5": {  # k = 2 and k = 3 columns identical for DELV and ACV, see NOTES
            "delv-compass": {"gt45": [13.29, 12.39, 27.19, 27.19],
                             "gt90": [7.10, 4.08, 9.21, 9.21]},
            "acv": {"gt45": [13.14, 37.46, 86.10, 86.10], "gt90": [3.47, 5.29, 39.27, 39.27]},
            "alv": {"gt45": [0.00, 5.80, 12.08, 17.07], "gt90": [0.00, 1.75, 3.71, 6.65]},
        },
        "ring6": {
            "delv-compass": {"gt45": [19.94, 16.31, 18.43, 27.95],
                             "gt90": [9.97, 8.16, 6.04, 7.10]},
            "acv": {"gt45": [21.87, 35.60, 51.43, 27.90], "gt90": [8.60, 12.22, 18.25, 7.09]},
            "alv": {"gt45": [0.00, 3.84, 7.73, 13.61], "gt90": [0.00, 1.14, 2.09, 5.10]},
        },
    },
}

ERROR_POINTS_SOURCES = {
    "table5_1": {"section": "§5.3.1, Table 5.1", "line": 865,
                 "text": "Table 5.1: Error point rate(%) for each environments with different "
                         "landmark distribution (rows at lines 865-873; caption line 875)"},
    "table5_2": {"section": "§5.3.1, Table 5.2", "line": 887,
                 "text": "Table 5.2: Error point rate(%) for each environments with different "
                         "landmark number (rows at lines 887-898; caption line 900)"},
}

# ---------------------------------------------------------------------------------------
# 3. Other numbers (thresholds stated in the text, run parameters) and what is NOT printed.
# ---------------------------------------------------------------------------------------
OTHER = {
    "fig4_10b_delv_success_rate": {
        "value": 90.0, "relation": ">", "unit": "% of 100 trials per release distance",
        "method": "delv", "section": "§4.2, Fig 4.10b", "line": 600,
        "text": "Our suggested method determines the goal point with a success rate greater "
                "than 90% (see Figure 4.10 (b))."},
    "fig4_13a_quantized_mean_error": {
        "value": 30.0, "relation": "< (mostly)", "unit": "deg, mean angular error per distance",
        "method": "delv (quantized, no compass)", "section": "§4.3, Fig 4.13a", "line": 618,
        "text": "the error mostly remains less than 30 degrees"},
    "fig4_8f_mean_error_far": {
        "value": 90.0, "relation": "<", "unit": "deg, mean angular error far from home",
        "method": "delv", "section": "§4.2, Fig 4.8f", "line": 568,
        "text": "At a distance far from the nest, the angular errors are large but still "
                "smaller than 90°"},
    "alv_error_points_no_occlusion": {
        "value": 0.0, "relation": "==", "unit": "% error points (>45 and >90), k = 0",
        "method": "alv", "section": "§5.3.1, Tables 5.1-5.2", "line": 881,
        "text": "the ALV model shows perfect homing vector results with no involved "
                "perception problem"},
    "alv_catchment_no_occlusion": {
        "value": 100.0, "relation": "==", "unit": "% catchment, k = 0",
        "method": "alv", "section": "§5.3.1, Tables 5.3-5.4", "line": 917,
        "text": "shows perfect homing ability with catchment area rate of 100% when all "
                "landmarks are perceived"},
    "step_distances_tested": {
        "value": [20, 50, 100, 150], "unit": "cm", "section": "§4.2, Fig 4.6-4.7",
        "line": 557, "text": "(a) d = 20, (b) d = 50, (c) d = 100, and (d) d = 150"},
    "step_distance_chosen": {
        "value": 50, "unit": "cm", "section": "§4.2", "line": 552,
        "text": "d = 50cm is chosen for good performance in the environment for a robot size "
                "about 15 cm in diameter"},
    "simulated_robot_diameter": {"value": 15, "unit": "cm", "section": "§4.2", "line": 552},
    "landmark_counts_fig4_8": {
        "value": [3, 4, 5], "section": "§4.2, Fig 4.8", "line": 568,
        "text": "The number of landmarks varies from 3 to 5, and they are arbitrarily positioned."},
    "quantization_levels_fig4_12": {
        "value": [3, 4, 5], "section": "§4.3, Fig 4.12", "line": 604,
        "text": "The landmark distance quantization levels in Figure 4.12 (a) to (c) are 3 to 5"},
    "quantization_levels_fig4_13a": {
        "value": {"text": [1, 2, 5], "caption": [1, 2, 3, 4, 5]},
        "section": "§4.3, Fig 4.13a", "line": 618,
        "text": "The error graphs are shown for DELV with 1, 2, and 5 levels of quantization "
                "compared to the predictive image-matching method. (caption line 614: "
                "'quantized distances of level 1 to 5')"},
    "quantization_level_fig4_14": {
        "value": 3, "section": "§4.3, Fig 4.14", "line": 629,
        "text": "vector maps with the suggested DELV method with quantization level 3 in "
                "environments of various landmark distribution"},
    "landmark_counts_fig4_14": {
        "value": [3, 4, 5], "section": "§4.3, Fig 4.14", "line": 624,
        "text": "the environment with three to five landmarks in different distribution"},
    "image_width": {"value": 360, "unit": "pixels (1 deg)", "section": "§4.2", "line": 570},
    "heading_resolution_delv": {"value": 1, "unit": "deg", "section": "§3.3.1", "line": 394},
    "warping_parameters": {
        "value": {"alpha_steps": 72, "psi_steps": 72, "step_deg": 5,
                  "rho": [0.1, 0.8, 0.05], "rho_steps": 15},
        "section": "§4.2", "line": 587,
        "text": "Both α and ψ had 72 steps, which is a 5° resolution in the range of 0° to 360° "
                "and 15 steps were used for ρ ranging from 0.1 to 0.8 for every 0.05 step."},
    "success_trials": {"value": 100, "unit": "trials per distance", "section": "§4.3",
                       "line": 622},
    "max_moves": {"value": 50, "unit": "moves", "section": "§4.3", "line": 622,
                  "text": "if a robot returned to its home location from a random position "
                          "within 50 movements, it was considered successful"},
    "home": {"value": [500, 500], "section": "§4.2", "line": 518},
    "landmarks_env1_3": {"value": 4, "section": "§4.2", "line": 518,
                         "text": "All three environments contain four cylindrical landmarks "
                                 "but with different sizes and angular positions."},
    # Numbers the thesis does NOT print (only plotted): nothing to compare digit by digit.
    "not_reported": {
        "value": [
            "Fig 4.4 / 5.4 mean angular error per distance (plots only)",
            "Fig 4.7 mean angular error for d = 20/50/100/150 (plot only)",
            "Fig 4.8f, 4.14f error curves (plots only)",
            "Fig 4.10a/b DELV vs warping errors and success rates (only DELV '> 90%')",
            "release distances of Figs 4.10b, 4.13b, 5.7b (x axis not given in the text)",
            "Fig 4.12 catchment areas for quantization levels 3-5 (referred to, not printed)",
            "Fig 4.13a/b error and success rate per quantization level (plots only)",
            "Fig 5.7a/b DELV-compass vs ACV vs ALV errors and success rates (plots only)",
            "Fig 5.12 error curves with the visual compass (plots only)",
            "catchment of the warping method (never given)",
        ],
        "section": "ch. 4-5"},
    # Robotic experiments (§4.4), not simulations: kept for completeness only.
    "robotic": {
        "value": {"step_cm": 20, "arena_m": [1.8, 1.8], "grid_cm": 20,
                  "robot_diameter_cm": 32, "camera_height_cm": 25,
                  "quantization_levels_fig4_20": [1, 4, 5]},
        "section": "§4.4.1", "line": 642},
}

# ---------------------------------------------------------------------------------------
# 4. Inconsistencies and ambiguities in the thesis.
# ---------------------------------------------------------------------------------------
NOTES = {
    "table5_2_L4_copies_other_rows": {
        "section": "Table 5.2", "line": 890,
        "description": "The L = 4 rows of Table 5.2 are copies: DELV (8.75/3.02/13.99/3.62/"
                       "20.48/6.49) and ACV (9.80/0.15/42.50/10.07/80.63/33.54) equal Table "
                       "5.1's environment 1 rows and ALV (0/0/10.24/2.60/14.91/4.95) equals "
                       "Table 5.1's environment 2 row, so no equally spaced L = 4 result exists."},
    "table5_4_L4_copies_other_rows": {
        "section": "Table 5.4", "line": 929,
        "description": "The L = 4 rows of Table 5.4 copy Table 5.3 the same way: DELV "
                       "(92.01/49.11/40.3) and ACV (100/52.88/24.14) are environment 1's and ALV "
                       "(100/17.09/23.10) is environment 2's (environment 1's ALV is "
                       "100/7.84/20.44)."},
    "fig5_10_vs_table5_3": {
        "section": "§5.3.1, Fig 5.10 vs Table 5.3", "line": 857,
        "description": "Fig 5.10's caption gives DELV-compass catchment 92.01/82.04/59.11 % "
                       "for environment 1 with 0/1/2 hidden landmarks, but Table 5.3 and the "
                       "text (line 902) give 92.01/49.11/40.3 % for the same case."},
    "fig5_10_occlusion_count": {
        "section": "§5.3.1, Fig 5.10", "line": 859,
        "description": "The caption says zero, one and two landmarks are hidden in Fig 5.10 "
                       "(a)-(c), while the text says 'one, two and three' (and (a) is 92.01 %, "
                       "the no-occlusion value)."},
    "table5_2_L5_duplicate_columns": {
        "section": "Table 5.2", "line": 893,
        "description": "For L = 5 the 2-hidden and 3-hidden columns are identical for DELV "
                       "(27.19/9.21) and ACV (86.10/39.27) while ALV's differ, which looks like "
                       "a copied column."},
    "table5_2_L6_acv_k3": {
        "section": "Table 5.2", "line": 897,
        "description": "For L = 6 ACV's 3-hidden entry (27.90/7.09) almost equals DELV's "
                       "(27.95/7.10) and is far below ACV's 2-hidden entry (51.43/18.25), which "
                       "is implausible and may be a transcription error."},
    "table5_4_L3_delv_100": {
        "section": "Table 5.4", "line": 926,
        "description": "DELV's catchment for L = 3 rises from 94.82 % with all landmarks "
                       "visible to 100 % with one of three hidden, the only increase to 100 % "
                       "under occlusion in the tables."},
    "table5_4_k3_delv_equal": {
        "section": "Table 5.4", "line": 932,
        "description": "DELV's 3-hidden catchment is 2.96 % for both L = 5 and L = 6 (two and "
                       "three landmarks left), a suspicious coincidence."},
    "alv_catchment_nonmonotone": {
        "section": "Tables 5.3-5.4", "line": 907,
        "description": "ALV's catchment is larger with two hidden landmarks than with one in "
                       "env1 (7.84 -> 20.44), env2 (17.09 -> 23.10), L=3 (9.82 -> 10.36), L=5 "
                       "(12.46 -> 18.73) and L=6 (13.74 -> 34.05), contrary to 'rapidly "
                       "decreases' (line 917); only env3 decreases."},
    "error_points_nonmonotone": {
        "section": "Tables 5.1-5.2", "line": 893,
        "description": "DELV's >45 error rate falls when a landmark is hidden for L = 5 "
                       "(13.29 -> 12.39) and L = 6 (19.94 -> 16.31 -> 18.43), and several >90 "
                       "rates fall too (env2 4.07 -> 4.00, env3 3.92 -> 3.24, L=3 2.69 -> 0.75), "
                       "whereas line 861 says errors increase with occlusion."},
    "sec5_2_env1_compass_sentence": {
        "section": "§5.2", "line": 819,
        "description": "The text says that in environment 1 'the DELV method showed even better "
                       "performance than without the reference compass', but the numbers are "
                       "92.01 % with and 98.52 % without the compass, so the sentence can only "
                       "mean that DELV without the compass did better."},
    "sec5_3_1_surround_vs_table5_1": {
        "section": "§5.3.1", "line": 881,
        "description": "The text says DELV performs better when landmarks surround home, but "
                       "in Table 5.1 DELV's lowest error rate is in environment 3 (all landmarks "
                       "on one side, 6.79 %) and in Table 5.2 its error grows with the number of "
                       "equally spaced landmarks (5.23 -> 19.94 % for L = 3 -> 6)."},
    "sec5_3_1_delv_vs_acv_error_rate": {
        "section": "§5.3.1", "line": 879,
        "description": "'DELV exhibits a smaller error rate' than ACV holds for >45 deg in most "
                       "cells but not for env2 k=0 (7.99 = 7.99), L=5 k=0 (13.29 > 13.14), L=6 "
                       "k=3 (27.95 > 27.90), and for >90 deg without occlusion ACV is lower "
                       "everywhere except L=3 (e.g. env1 0.15 vs 3.02)."},
    "sec5_3_1_small_occlusion": {
        "section": "§5.3.1", "line": 919,
        "description": "'With small occlusions, the ACV and ALV approach exhibits better homing "
                       "ability' contradicts the tables for ALV (one hidden: 7.84 vs DELV 49.11 "
                       "% in env1) and for ACV in env3 / L = 3, 5, 6; it holds only without "
                       "occlusion, or for ACV with one hidden in env1/env2."},
    "sec5_3_1_alv_vs_delv_k3": {
        "section": "§5.3.1, Table 5.4", "line": 917,
        "description": "'the catchment area of the ALV method is much smaller than those of the "
                       "DELV method when landmarks were occluded' fails for three hidden "
                       "landmarks (L=5: ALV 8.98 vs DELV 2.96; L=6: 11.74 vs 2.96)."},
    "sec4_3_quantization_levels": {
        "section": "§4.3, Figs 4.12-4.13", "line": 618,
        "description": "Which quantization levels were compared is unclear: Fig 4.12 shows "
                       "levels 3-5, Fig 4.13's caption says levels 1 to 5, the text says levels "
                       "1, 2 and 5 (plus the warping method), and Fig 4.13b 'for each method'."},
    "sec4_3_catchment_not_printed": {
        "section": "§4.3, Fig 4.12", "line": 622,
        "description": "The text refers to 'the catchment area in Figure 4.12' for quantized "
                       "DELV, but no catchment percentage is given in the caption or the text."},
    "fig5_4_caption": {
        "section": "§5.2, Fig 5.4", "line": 803,
        "description": "Fig 5.4's caption refers only to the vector maps of Fig 4.2 (no "
                       "compass) although the text says it shows both Fig 4.2 and Fig 5.2 "
                       "(with compass) results."},
    "sec5_3_both_methods": {
        "section": "§5.3, Fig 5.7", "line": 825,
        "description": "The text says Fig 5.7a 'shows the angular errors for both methods' and "
                       "5.7b 'similar level of performance in both methods' while three methods "
                       "(DELV, ACV, ALV) are compared."},
    "environment_unstated": {
        "section": "Figs 4.9-4.11, 4.13, 5.6-5.8, 5.11-5.12", "line": 825,
        "description": "The landmark layout of the method comparisons (DELV vs warping, "
                       "DELV vs ACV vs ALV, visual compass) is never stated; CATCHMENT['fig5_11'] "
                       "is keyed 'env1' by assumption only."},
    "occlusion_choice_unstated": {
        "section": "§5.3.1", "line": 847,
        "description": "The thesis does not say which landmarks were hidden or whether results "
                       "are averaged over the choices ('artificially removing one of the "
                       "landmarks'), although the tables go up to three hidden landmarks."},
    "success_criterion_unstated": {
        "section": "§4.2-4.3", "line": 622,
        "description": "Success is 'reached home' within 50 moves, but the home radius, the "
                       "grid spacing of the catchment maps and the release distances of the "
                       "success-rate plots are not given."},
    "visual_compass_background_unstated": {
        "section": "§5.3.2", "line": 943,
        "description": "The visual compass needs a textured background ('appropriate background "
                       "settings of the simulation environment are required') but the "
                       "background used is not described."},
    "acv_sum_vs_average": {
        "section": "§5.1, Eq 5.2", "line": 753,
        "description": "The text says the correction vectors 'are then averaged' while Eq 5.2 "
                       "sums them (HV = sum CV_i); only the direction matters for homing."},
    "eq3_1_3_3_typo": {
        "section": "§3.2.1-3.2.3, Eqs 3.1-3.3", "line": 297,
        "description": "Eq 3.3 for the reference-map distance R' has sin(theta - psi) in the "
                       "denominator, inconsistent with Eq 3.1 (which gives sin(delta + psi)); "
                       "docs/model.md §3.1 treats it as a typo and derives R_P from the sine law."},
    "alv_100_needs_no_collisions": {
        "section": "Tables 5.3-5.4", "line": 905,
        "description": "ALV's 100 % catchment in every environment implies that rollouts "
                       "ignored collisions with landmarks and exits from the arena (docs/model.md §5 "
                       "default collisions = 'ignore'); the thesis does not say so."},
}

# ---------------------------------------------------------------------------------------
# 5. Claims about the simulation results (verbatim quotes; "..." marks omissions).
# ---------------------------------------------------------------------------------------
CLAIMS = [
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
                     "on one side of home.",
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
        "needs": ["error_points_gt45:env1:delv:inside_hull",
                  "error_points_gt45:env1:delv:outside_hull",
                  "error_points_gt45:env2:delv:inside_hull",
                  "error_points_gt45:env2:delv:outside_hull"],
    },
    {
        "id": "step_distance_rarely_matters",
        "section": "§4.2, Fig 4.6-4.7",
        "line": 552,
        "quote": "The angular errors do not differ by a large amount with varying moving "
                 "distances d . This shows that the moving distance rarely affects the "
                 "performance of the method.",
        "statement": "DELV's mean angular error curves for d = 20, 50, 100 and 150 cm lie close "
                     "together (no d gives a clearly worse curve), with at most a slight "
                     "advantage for small d.",
        "needs": ["error_curve:env1:delv:d=20", "error_curve:env1:delv:d=50",
                  "error_curve:env1:delv:d=100", "error_curve:env1:delv:d=150"],
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
        "needs": ["error_curve:arbitrary3:delv", "error_curve:arbitrary4:delv",
                  "error_curve:arbitrary5:delv"],
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
        "needs": ["success_rate:env1:delv:by_distance", "success_rate:env1:warping:by_distance",
                  "catchment:env1:delv", "catchment:env1:warping"],
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
        "needs": ["success:env1:warping:outside_hull", "success:env1:warping:inside_hull",
                  "success:env1:delv:outside_hull"],
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
        "needs": ["success_rate:env1:delv:Q=1..5", "success_rate:env1:delv:continuous",
                  "catchment:env1:delv:Q=1..5", "catchment:env1:delv:continuous"],
    },
    {
        "id": "surrounding_landmarks_lower_error",
        "section": "§4.3, Fig 4.14",
        "line": 624,
        "quote": "The homing vector results show low angular errors in various environments, "
                 "with slightly smaller error if the landmarks surrounded home location "
                 "perfectly as in (a).",
        "statement": "With level-3 quantized DELV, a layout of equally spaced landmarks "
                     "surrounding home gives a slightly lower mean angular error than layouts "
                     "with home at or outside the edge of the landmarks' convex hull.",
        "needs": ["mean_error:ring3:delv:Q=3", "mean_error:ring5:delv:Q=3",
                  "mean_error:env3:delv:Q=3"],
    },
    {
        "id": "compass_slightly_smaller_error",
        "section": "§5.2, Fig 5.4",
        "line": 810,
        "quote": "the method with the reference compass shows slightly smaller errors in "
                 "average, which results from the error in the heading direction estimation. "
                 "However, the difference between methods are not as significant",
        "statement": "In env1-env3 DELV with compass has a mean angular error slightly below "
                     "(never far below) that of DELV without compass.",
        "needs": ["mean_error:env1:delv", "mean_error:env1:delv-compass",
                  "mean_error:env2:delv", "mean_error:env2:delv-compass",
                  "mean_error:env3:delv", "mean_error:env3:delv-compass"],
    },
    {
        "id": "compass_catchment_env2_similar_env3_better",
        "section": "§5.2, Fig 5.5 vs Fig 4.5",
        "line": 819,
        "quote": "The level of the catchment area in environment 2 were similar in both cases, "
                 "but lower in DELV without reference compass for environment 3.",
        "statement": "DELV catchment with and without compass is similar in env2 (thesis 97.04 "
                     "vs 95.41 %) and lower without compass in env3 (84.91 vs 77.66 %); in env1 "
                     "the thesis's numbers favour no compass (98.52 vs 92.01 %).",
        "needs": ["catchment:env1:delv", "catchment:env1:delv-compass",
                  "catchment:env2:delv", "catchment:env2:delv-compass",
                  "catchment:env3:delv", "catchment:env3:delv-compass"],
    },
    {
        "id": "delv_vs_acv_alv_error_mixed",
        "section": "§5.3, Fig 5.7a",
        "line": 837,
        "quote": "the error level of DELV with reference compass is smaller than the ACV method "
                 "in most of the region, but slightly higher in some. Similarly, comparing the "
                 "performance with ALV, DELV show smaller angular error in some regions, but "
                 "higher in others.",
        "statement": "DELV-compass's mean angular error is below ACV's in most distance bins; "
                     "against ALV neither is uniformly lower.",
        "needs": ["error_curve:env1:delv-compass", "error_curve:env1:acv",
                  "error_curve:env1:alv"],
    },
    {
        "id": "delv_compass_success_near_far",
        "section": "§5.3, Fig 5.7b",
        "line": 839,
        "quote": "Success rate in Figure 5.7 (b) indicate the similar level of performance in "
                 "both methods as well. The DELV method with reference compass showed little "
                 "higher success rate in closer starting points while it decreased for the "
                 "further starting point cases.",
        "statement": "DELV-compass's success rate is similar to ACV's/ALV's overall, a little "
                     "higher at short release distances and lower at the largest ones.",
        "needs": ["success_rate:env1:delv-compass:by_distance",
                  "success_rate:env1:acv:by_distance", "success_rate:env1:alv:by_distance"],
    },
    {
        "id": "occlusion_increases_errors",
        "section": "§5.3.1, Fig 5.9",
        "line": 861,
        "quote": "Figure 5.9 shows that as the number of occluded landmarks increase, the "
                 "region of homing vector with errors also increases.",
        "statement": "For DELV-compass in env1 the error point rate (> 45 deg) grows with the "
                     "number k = 0, 1, 2 of hidden landmarks (thesis 8.75 / 13.99 / 20.48 %).",
        "needs": ["error_points_gt45:env1:delv-compass:k=0..2"],
    },
    {
        "id": "acv_error_grows_faster_than_delv",
        "section": "§5.3.1, Table 5.1",
        "line": 879,
        "quote": "Comparing the DELV and ACV methods, the DELV method exhibits a smaller error "
                 "rate and better performance. ... the ACV method exhibits much more rapid "
                 "increase in the error rate compared to that of the DELV model",
        "statement": "In env1-env3 DELV-compass's error point rate (> 45 deg) is at or below "
                     "ACV's for k = 0, 1, 2 hidden landmarks (thesis env2 k=0: a tie at 7.99 %) "
                     "and ACV's rate rises much faster with k "
                     "(thesis env1: ACV 9.80 -> 80.63 %, DELV 8.75 -> 20.48 %).",
        "needs": ["error_points_gt45:env1..3:delv-compass:k=0..2",
                  "error_points_gt45:env1..3:acv:k=0..2"],
    },
    {
        "id": "acv_larger_catchment_small_occlusion",
        "section": "§5.3.1, Table 5.3",
        "line": 902,
        "quote": "with almost 100% than does the DELV method (92.01%). This is also true in the "
                 "environment with one occluded landmark; the catchment area percentages are "
                 "49.11% for DELV and 52.88% for ACV method.",
        "statement": "In env1, ACV's catchment exceeds DELV-compass's with no landmark hidden "
                     "(~100 vs 92 %) and, narrowly, with one hidden (52.88 vs 49.11 %).",
        "needs": ["catchment:env1:acv:k=0,1", "catchment:env1:delv-compass:k=0,1"],
    },
    {
        "id": "acv_catchment_shrinks_faster",
        "section": "§5.3.1, Tables 5.3-5.4",
        "line": 902,
        "quote": "the catchment area generated with the ACV method shrinks more rapidly than "
                 "that of the DELV method. As a result, the catchment area of the DELV method "
                 "exceeds the result of the ACV method when two out of four landmarks are "
                 "occluded in the environment.",
        "statement": "ACV loses more catchment than DELV-compass from k = 0 to k = 2 hidden "
                     "landmarks, and at k = 2 DELV's catchment exceeds ACV's in env1-env3 "
                     "(thesis 40.3 vs 24.14, 51.86 vs 25.47, 62.34 vs 18.46 %).",
        "needs": ["catchment:env1..3:delv-compass:k=0..2", "catchment:env1..3:acv:k=0..2"],
    },
    {
        "id": "alv_perfect_then_collapses_under_occlusion",
        "section": "§5.3.1, Tables 5.1-5.4",
        "line": 917,
        "quote": "The ALV method, as well as in the error point rates results, shows perfect "
                 "homing ability with catchment area rate of 100% when all landmarks are "
                 "perceived. When one or more landmarks are occluded, the rate of the catchment "
                 "area obtained with ALV method rapidly decreases. As in Table 5.3 and Table 5.4, "
                 "the catchment area of the ALV method is much smaller than those of the DELV "
                 "method when landmarks were occluded.",
        "statement": "With the true compass ALV has 0 % error points and 100 % catchment when no "
                     "landmark is hidden (every environment), and its catchment drops to well "
                     "below DELV-compass's as soon as one landmark is hidden (thesis env1 k=1: "
                     "7.84 vs 49.11 %), in env1-3 and ring3-6 for k = 1, 2.",
        "needs": ["error_points_gt45:*:alv:k=0", "catchment:*:alv:k=0..3",
                  "catchment:*:delv-compass:k=0..3"],
    },
    {
        "id": "visual_compass_not_exact",
        "section": "§5.3.2, Fig 5.11",
        "line": 954,
        "quote": "Since the heading estimation according to the visual compass method does not "
                 "guarantee 100% of accuracy, the results show larger error in the direction of "
                 "the homing vector compared to the results obtained when a reference compass is "
                 "given",
        "statement": "The visual compass's heading estimate is wrong at some grid points, and "
                     "DELV, ACV and ALV each have a larger mean angular error with the visual "
                     "compass than with the true compass.",
        "needs": ["visual_compass_heading_error:env1", "mean_error:env1:delv-visual",
                  "mean_error:env1:delv-compass", "mean_error:env1:acv-visual",
                  "mean_error:env1:acv", "mean_error:env1:alv-visual", "mean_error:env1:alv"],
    },
    {
        "id": "visual_compass_catchment_order",
        "section": "§5.3.2, Fig 5.11",
        "line": 954,
        "quote": "The size of the catchment areas in the maps for DELV, ACV, and ALV methods "
                 "are 74.85%, 47.04%, 40.68%, respectively. The reason for the low catchment "
                 "areas with the ACV and ALV methods seems to be related to an increase in the "
                 "trap points",
        "statement": "With the visual compass the catchment orders DELV > ACV > ALV (thesis "
                     "74.85 > 47.04 > 40.68 %), ACV and ALV losing far more than DELV relative "
                     "to the true compass.",
        "needs": ["catchment:env1:delv-visual", "catchment:env1:acv-visual",
                  "catchment:env1:alv-visual", "catchment:env1:delv-compass",
                  "catchment:env1:acv", "catchment:env1:alv"],
    },
    {
        "id": "visual_compass_error_order",
        "section": "§5.3.2, Fig 5.12",
        "line": 963,
        "quote": "upon application of the visual compass method, the error of the DELV method "
                 "is smaller than that of the ALV model, whose error rate is the most increased.",
        "statement": "With the visual compass DELV's mean angular error is below ACV's and "
                     "ALV's, and ALV's error grows the most relative to the true compass.",
        "needs": ["error_curve:env1:delv-visual", "error_curve:env1:acv-visual",
                  "error_curve:env1:alv-visual", "error_curve:env1:alv"],
    },
    {
        "id": "delv_least_compass_dependent",
        "section": "§5.4 (Figs 5.11-5.12)",
        "line": 973,
        "quote": "The results showed that DELV method is less affected by the accuracy of the "
                 "heading direction estimation than other two methods.",
        "statement": "Replacing the true compass by the visual compass costs DELV less "
                     "catchment and less mean-error increase than it costs ACV and ALV.",
        "needs": ["catchment:env1:{delv-compass,delv-visual,acv,acv-visual,alv,alv-visual}",
                  "mean_error:env1:{delv-compass,delv-visual,acv,acv-visual,alv,alv-visual}"],
    },
    {
        "id": "delv_acv_similar_without_occlusion",
        "section": "§6.2 (summarising §5.3)",
        "line": 1003,
        "quote": "There is no big difference in the angular error or catchment area results "
                 "between the DELV and ACV",
        "statement": "With the true compass and all landmarks visible, DELV-compass and ACV have "
                     "similar mean angular errors and catchments (thesis env1 92.01 vs 100 %).",
        "needs": ["mean_error:env1..3:delv-compass", "mean_error:env1..3:acv",
                  "catchment:env1..3:delv-compass:k=0", "catchment:env1..3:acv:k=0"],
    },
]
