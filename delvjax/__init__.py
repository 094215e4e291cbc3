"""delvjax: the Distance-Estimated Landmark Vector (DELV) homing method and its comparators
as pure, jit/vmap-able JAX programs (the thesis "Distance-Estimated Landmark Vector Model for
Vision-Based Homing Navigation", chapters 3-5; see docs/model.md).

`delvjax.core` is the model as array programs (methods as equinox modules, sensing, maps,
rollouts); this top level is the edge: names, options, files, figures, CLI and this API.
"""

from .api import load_env, vector_map
from .api_rollouts import catchment, success_rate, trajectories
from .api_soft import homing_quality, homing_quality_grad
from .api_images import ImageSettings, render_database
from .api_image_eval import (database_catchment, database_rollouts, database_vector_map, import_database,
                             load_database, rendered_database)
from .layout import optimise_layout
from .sensitivities import sensitivity
from .traps import find_traps
from .core.errors import InputError
from .core.maps import VectorMap
from .core.methods import (ACV, ALV, DELV, MFDID, CartwrightCollett, Compass, DELVGap, DELVRefined,
                           HomingMethod, Method, Program,
                           VisualCompass, Warping)
from .core.metrics import error_curve, error_point_rates, summarize_map
from .core.scene import Env
from .core.sensing import Snapshot, UnitMove
from .core.sensor import Noise, Sensor
from .presets import make_env
from .registry import METHODS
from .sweeps import load_sweep, run_sweep

__all__ = [
    "ACV", "ALV", "CartwrightCollett", "Compass", "DELV", "DELVGap", "DELVRefined", "Env", "HomingMethod", "InputError", "METHODS", "MFDID",
    "Method", "Noise", "Program", "Sensor", "Snapshot", "UnitMove", "VectorMap", "VisualCompass", "Warping",
    "catchment", "error_curve", "homing_quality", "homing_quality_grad", "find_traps", "optimise_layout", "sensitivity", "error_point_rates", "load_env", "make_env", "success_rate", "summarize_map",
    "load_sweep", "run_sweep", "trajectories", "vector_map",
    "ImageSettings", "render_database", "rendered_database", "load_database", "import_database", "database_vector_map",
    "database_catchment", "database_rollouts",
]
__version__ = "0.1.0"
