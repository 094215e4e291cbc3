"""delvjax: the Distance-Estimated Landmark Vector (DELV) homing method and its comparators
as pure, jit/vmap-able JAX programs (the thesis "Distance-Estimated Landmark Vector Model for
Vision-Based Homing Navigation", chapters 3-5; see docs/model.md).

`delvjax.core` is the model as array programs (methods as equinox modules, sensing, maps,
rollouts); this top level is the edge: names, options, files, figures, CLI and this API.
"""

from .core.errors import InputError as InputError
from .core.maps import VectorMap as VectorMap
from .core.methods import (ACV as ACV, ALV as ALV, DELV as DELV, MFDID as MFDID, CartwrightCollett as CartwrightCollett,
                           Compass as Compass, DELVGap as DELVGap, DELVRefined as DELVRefined,
                           HomingMethod as HomingMethod, Method as Method, Program as Program,
                           VisualCompass as VisualCompass, Warping as Warping)
from .core.metrics import error_curve as error_curve, error_point_rates as error_point_rates
from .core.metrics import summarize_map as summarize_map
from .core.scene import Env as Env
from .core.sensing import Snapshot as Snapshot, UnitMove as UnitMove
from .core.sensor import Noise as Noise, Sensor as Sensor

# The edge's public names, imported on first use (PEP 562), so that `import delvjax` loads neither
# matplotlib, xarray nor PIL: name -> the feature package that defines it.
_LAZY = {
    "load_env": "envs", "make_env": "envs",
    "vector_map": "evaluate", "catchment": "evaluate", "success_rate": "evaluate", "trajectories": "evaluate",
    "homing_quality": "gradients", "homing_quality_grad": "gradients", "optimise_layout": "gradients",
    "sensitivity": "gradients", "find_traps": "gradients",
    "ImageSettings": "images", "render_database": "images", "rendered_database": "images", "load_database": "images",
    "import_database": "images", "database_vector_map": "images", "database_catchment": "images",
    "database_rollouts": "images",
    "METHODS": "options",
    "load_sweep": "sweeps", "run_sweep": "sweeps",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value  # later lookups are plain attribute reads
        return value
    raise AttributeError(f"module 'delvjax' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "ACV", "ALV", "CartwrightCollett", "Compass", "DELV", "DELVGap", "DELVRefined", "Env", "HomingMethod", "InputError",
    "METHODS", "MFDID", "Method", "Noise", "Program", "Sensor", "Snapshot", "UnitMove", "VectorMap", "VisualCompass",
    "Warping", "catchment", "error_curve", "homing_quality", "homing_quality_grad", "find_traps", "optimise_layout",
    "sensitivity", "error_point_rates", "load_env", "make_env", "success_rate", "summarize_map", "load_sweep",
    "run_sweep", "trajectories", "vector_map", "ImageSettings", "render_database", "rendered_database",
    "load_database", "import_database", "database_vector_map", "database_catchment", "database_rollouts",
]
__version__ = "0.1.0"
