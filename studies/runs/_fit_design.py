"""What the fit study searches (`runs/fit.py`): the settings grid of the full and the quick design,
the grid spacing, the tolerance of "reached" and the units of each setting."""

from __future__ import annotations


from ._fit_model import TABLES
from ._fit_cells import DEFAULTS


TITLE = "Fit of the thesis's unstated settings: noise, home radius, home move, landmark radii (beyond the thesis)"
COST = 90  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first


FIT_SPACING = 125.0  # cm: the full fit's grid (8 x 8; 100 cm takes 1.5 x as long, 25 cm about 25 x)


QUICK_SPACING = 200.0  # cm: the reduced design's grid (5 x 5)


TOLERANCE = 10.0  # percentage points: a thesis number is "reached" by a setting within this of it


FULL_DESIGN = {
    "grid": {
        "bearing_noise_deg": (0.0, 1.0, 3.0),
        "step_noise": (0.0, 0.1),
        "odometry_turn_noise_deg": (0.0, 3.0),
        "home_radius": (0.5 * DEFAULTS["home_radius"], DEFAULTS["home_radius"], 1.5 * DEFAULTS["home_radius"]),
        "alpha_r_deg": (0.0, 90.0, 180.0),
        "landmark_radius_scale": (0.5, 1.0, 1.5),
    },
    "tables": tuple(TABLES),
    "envs": None,
    "top": 2,
    "check": True,
}


QUICK_DESIGN = {
    "grid": {"bearing_noise_deg": (0.0, 2.0)},
    "tables": ("fig4_5", "fig5_5", "fig5_10", "table5_1", "table5_3"),
    "envs": ("env1", "env2", "env3"),
    "top": 1,
    "check": False,
}


STEPS = 1 + sum(len(v) - 1 for v in FULL_DESIGN["grid"].values()) + 4 + 2  # one tick per settings point evaluated


UNITS = {
    "bearing_noise_deg": "°",
    "step_noise": "× d",
    "odometry_turn_noise_deg": "°",
    "home_radius": "cm",
    "alpha_r_deg": "°",
    "landmark_radius_scale": "×",
}


def design(settings) -> tuple[dict, float]:
    """(design, grid spacing): the full design unless --quick or a grid coarser than FIT_SPACING."""
    if settings.quick or settings.spacing > FIT_SPACING:
        return QUICK_DESIGN, max(settings.spacing, QUICK_SPACING)
    return FULL_DESIGN, max(settings.spacing, FIT_SPACING)
