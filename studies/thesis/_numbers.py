"""The numbers the thesis prints about its simulation experiments (re-exported by `delvjax.studies.thesis`).

Chapter 4 (DELV without compass: Fig 4.5, the run parameters and thresholds of §4.2-4.3) and
chapter 5 (DELV with compass, ACV, ALV, occlusion, visual compass: Figs 5.5, 5.10, 5.11 and
Tables 5.1-5.4), plus the robotic parameters of §4.4 kept apart in ``OTHER["robotic"]``.

CATCHMENT, CATCHMENT_SOURCES        catchment area in % and where each entry comes from.
ERROR_POINTS, ERROR_POINTS_SOURCES  error point rates of Tables 5.1-5.2 and their sources.
OTHER                               other printed numbers, run parameters, what is not printed.

Keys (methods, environments, k = hidden landmarks) and the ``line`` convention are described
in `delvjax.studies.thesis`, which is the module to import from.
"""

from __future__ import annotations

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
    "fig4_5": {
        "section": "§4.2, Fig 4.5",
        "line": 546,
        "text": "Figure 4.5: Catchment area with vector map for each environment. "
        "(a) 98.52%, (b) 95.41%, and (c) 77.66% of the environment.",
    },
    "fig5_5": {
        "section": "§5.2, Fig 5.5",
        "line": 808,
        "text": "Figure 5.5: ... (a) 92.01%, (b) 97.04%, and (c) 84.91% of the "
        "environment. (repeated in the text, line 819)",
    },
    "table5_3": {
        "section": "§5.3.1, Table 5.3",
        "line": 905,
        "text": "Table 5.3: Catchment area rate(%) for each environments with "
        "different landmark distribution (rows at lines 905-913)",
    },
    "table5_4": {
        "section": "§5.3.1, Table 5.4",
        "line": 926,
        "text": "Table 5.4: Catchment area rate(%) for each environments with "
        "different landmark number (rows at lines 926-937; '-' for L=3,4 k=3)",
    },
    "fig5_10": {
        "section": "§5.3.1, Fig 5.10",
        "line": 857,
        "text": "Figure 5.10: Catchment area with vector map for each environment: "
        "(a) 92.01%, (b) 82.04%, and (c) 59.11% of the environment. The number "
        "of landmarks is zero for (a) and one, two for (b) and (c)",
    },
    "fig5_11": {
        "section": "§5.3.2, Fig 5.11",
        "line": 948,
        "text": "Catchment areas for each case are 74.85%, 47.04%, and 40.68%, "
        "respectively (also in the text, line 954)",
    },
    "text5_3_1": {
        "section": "§5.3.1",
        "line": 902,
        "text": "with almost 100% than does the DELV method (92.01%). ... the "
        "catchment area percentages are 49.11% for DELV and 52.88% for ACV",
    },
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
            "delv-compass": {"gt45": [13.29, 12.39, 27.19, 27.19], "gt90": [7.10, 4.08, 9.21, 9.21]},
            "acv": {"gt45": [13.14, 37.46, 86.10, 86.10], "gt90": [3.47, 5.29, 39.27, 39.27]},
            "alv": {"gt45": [0.00, 5.80, 12.08, 17.07], "gt90": [0.00, 1.75, 3.71, 6.65]},
        },
        "ring6": {
            "delv-compass": {"gt45": [19.94, 16.31, 18.43, 27.95], "gt90": [9.97, 8.16, 6.04, 7.10]},
            "acv": {"gt45": [21.87, 35.60, 51.43, 27.90], "gt90": [8.60, 12.22, 18.25, 7.09]},
            "alv": {"gt45": [0.00, 3.84, 7.73, 13.61], "gt90": [0.00, 1.14, 2.09, 5.10]},
        },
    },
}

ERROR_POINTS_SOURCES = {
    "table5_1": {
        "section": "§5.3.1, Table 5.1",
        "line": 865,
        "text": "Table 5.1: Error point rate(%) for each environments with different "
        "landmark distribution (rows at lines 865-873; caption line 875)",
    },
    "table5_2": {
        "section": "§5.3.1, Table 5.2",
        "line": 887,
        "text": "Table 5.2: Error point rate(%) for each environments with different "
        "landmark number (rows at lines 887-898; caption line 900)",
    },
}

# ---------------------------------------------------------------------------------------
# 3. Other numbers (thresholds stated in the text, run parameters) and what is NOT printed.
# ---------------------------------------------------------------------------------------
OTHER = {
    "fig4_10b_delv_success_rate": {
        "value": 90.0,
        "relation": ">",
        "unit": "% of 100 trials per release distance",
        "method": "delv",
        "section": "§4.2, Fig 4.10b",
        "line": 600,
        "text": "Our suggested method determines the goal point with a success rate greater "
        "than 90% (see Figure 4.10 (b)).",
    },
    "fig4_13a_quantized_mean_error": {
        "value": 30.0,
        "relation": "< (mostly)",
        "unit": "deg, mean angular error per distance",
        "method": "delv (quantized, no compass)",
        "section": "§4.3, Fig 4.13a",
        "line": 618,
        "text": "the error mostly remains less than 30 degrees",
    },
    "fig4_8f_mean_error_far": {
        "value": 90.0,
        "relation": "<",
        "unit": "deg, mean angular error far from home",
        "method": "delv",
        "section": "§4.2, Fig 4.8f",
        "line": 568,
        "text": "At a distance far from the nest, the angular errors are large but still smaller than 90°",
    },
    "alv_error_points_no_occlusion": {
        "value": 0.0,
        "relation": "==",
        "unit": "% error points (>45 and >90), k = 0",
        "method": "alv",
        "section": "§5.3.1, Tables 5.1-5.2",
        "line": 881,
        "text": "the ALV model shows perfect homing vector results with no involved perception problem",
    },
    "alv_catchment_no_occlusion": {
        "value": 100.0,
        "relation": "==",
        "unit": "% catchment, k = 0",
        "method": "alv",
        "section": "§5.3.1, Tables 5.3-5.4",
        "line": 917,
        "text": "shows perfect homing ability with catchment area rate of 100% when all landmarks are perceived",
    },
    "step_distances_tested": {
        "value": [20, 50, 100, 150],
        "unit": "cm",
        "section": "§4.2, Fig 4.6-4.7",
        "line": 557,
        "text": "(a) d = 20, (b) d = 50, (c) d = 100, and (d) d = 150",
    },
    "step_distance_chosen": {
        "value": 50,
        "unit": "cm",
        "section": "§4.2",
        "line": 552,
        "text": "d = 50cm is chosen for good performance in the environment for a robot size about 15 cm in diameter",
    },
    "simulated_robot_diameter": {"value": 15, "unit": "cm", "section": "§4.2", "line": 552},
    "landmark_counts_fig4_8": {
        "value": [3, 4, 5],
        "section": "§4.2, Fig 4.8",
        "line": 568,
        "text": "The number of landmarks varies from 3 to 5, and they are arbitrarily positioned.",
    },
    "quantization_levels_fig4_12": {
        "value": [3, 4, 5],
        "section": "§4.3, Fig 4.12",
        "line": 604,
        "text": "The landmark distance quantization levels in Figure 4.12 (a) to (c) are 3 to 5",
    },
    "quantization_levels_fig4_13a": {
        "value": {"text": [1, 2, 5], "caption": [1, 2, 3, 4, 5]},
        "section": "§4.3, Fig 4.13a",
        "line": 618,
        "text": "The error graphs are shown for DELV with 1, 2, and 5 levels of quantization "
        "compared to the predictive image-matching method. (caption line 614: "
        "'quantized distances of level 1 to 5')",
    },
    "quantization_level_fig4_14": {
        "value": 3,
        "section": "§4.3, Fig 4.14",
        "line": 629,
        "text": "vector maps with the suggested DELV method with quantization level 3 in "
        "environments of various landmark distribution",
    },
    "landmark_counts_fig4_14": {
        "value": [3, 4, 5],
        "section": "§4.3, Fig 4.14",
        "line": 624,
        "text": "the environment with three to five landmarks in different distribution",
    },
    "image_width": {"value": 360, "unit": "pixels (1 deg)", "section": "§4.2", "line": 570},
    "heading_resolution_delv": {"value": 1, "unit": "deg", "section": "§3.3.1", "line": 394},
    "warping_parameters": {
        "value": {"alpha_steps": 72, "psi_steps": 72, "step_deg": 5, "rho": [0.1, 0.8, 0.05], "rho_steps": 15},
        "section": "§4.2",
        "line": 587,
        "text": "Both α and ψ had 72 steps, which is a 5° resolution in the range of 0° to 360° "
        "and 15 steps were used for ρ ranging from 0.1 to 0.8 for every 0.05 step.",
    },
    "success_trials": {"value": 100, "unit": "trials per distance", "section": "§4.3", "line": 622},
    "max_moves": {
        "value": 50,
        "unit": "moves",
        "section": "§4.3",
        "line": 622,
        "text": "if a robot returned to its home location from a random position "
        "within 50 movements, it was considered successful",
    },
    "home": {"value": [500, 500], "section": "§4.2", "line": 518},
    "landmarks_env1_3": {
        "value": 4,
        "section": "§4.2",
        "line": 518,
        "text": "All three environments contain four cylindrical landmarks "
        "but with different sizes and angular positions.",
    },
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
        "section": "ch. 4-5",
    },
    # Robotic experiments (§4.4), not simulations: kept for completeness only.
    "robotic": {
        "value": {
            "step_cm": 20,
            "arena_m": [1.8, 1.8],
            "grid_cm": 20,
            "robot_diameter_cm": 32,
            "camera_height_cm": 25,
            "quantization_levels_fig4_20": [1, 4, 5],
        },
        "section": "§4.4.1",
        "line": 642,
    },
}
