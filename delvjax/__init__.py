"""delvjax: the Distance-Estimated Landmark Vector (DELV) homing method and its comparators
as pure, jit/vmap-able JAX programs (the thesis "Distance-Estimated Landmark Vector Model for
Vision-Based Homing Navigation", chapters 3-5; see docs/model.md)."""

from .api import catchment, load_env, success_rate, trajectories, vector_map
from .config import Config, Noise
from .errors import InputError
from .maps import VectorMap
from .methods import METHODS
from .metrics import error_curve, error_point_rates, summarize_map
from .scene import Env, make_env
from .sensing import Snapshot, UnitMove

__all__ = [
    "Config", "Env", "InputError", "METHODS", "Noise", "Snapshot", "UnitMove", "VectorMap",
    "error_curve", "error_point_rates", "load_env", "make_env", "summarize_map", "vector_map",
    "catchment", "success_rate", "trajectories",
]
__version__ = "0.1.0"
