"""delvjax: the Distance-Estimated Landmark Vector (DELV) homing method and its comparators
as pure, jit/vmap-able JAX programs (the thesis "Distance-Estimated Landmark Vector Model for
Vision-Based Homing Navigation", chapters 3-5; see docs/model.md).

`delvjax.core` is the model as array programs (methods as equinox modules, sensing, maps,
rollouts); this top level is the edge: names, options, files, figures, CLI and this API.
"""

import warnings

# Every public name is imported on first use (PEP 562): `import delvjax` loads neither JAX, matplotlib,
# xarray nor PIL, and `delvjax --help` answers at once. name -> the module that defines it. The method
# classes (DELV, Warping, MinWarping, ...) are not listed here: they are the registry's
# (`options._registry.public_classes`), read on first use, so a new method needs no line in this file.
_LAZY = {
    "InputError": "core.errors",
    "VectorMap": "core.maps",
    "Env": "core.scene",
    "Noise": "core.sensor",
    "Sensor": "core.sensor",
    "Snapshot": "core.sensing",
    "UnitMove": "core.sensing",
    "error_curve": "core.metrics",
    "error_point_rates": "core.metrics",
    "summarize_map": "core.metrics",
    **{name: "core.methods" for name in ("Compass", "HomingMethod", "Method", "MethodSet", "VisualCompass")},
    "load_env": "envs",
    "to_dataframe": "core.tables",
    "to_xarray": "core.tables",
    "make_env": "envs",
    "vector_map": "evaluate",
    "Grid": "core.rollouts",
    "Rules": "core.rollouts",
    "catchment": "evaluate",
    "success_rate": "evaluate",
    "trajectories": "evaluate",
    "homing_loss": "gradients",
    "homing_loss_grad": "gradients",
    "optimise_layout": "gradients",
    "sensitivity": "gradients",
    "find_traps": "gradients",
    "ImageSettings": "images",
    "render_database": "images",
    "render_in_memory": "images",
    "rendered_database": "images",
    "load_database": "images",
    "import_database": "images",
    "database_vector_map": "images",
    "database_catchment": "images",
    "database_rollouts": "images",
    "route_experiments": "familiarity",
    "database_experiments": "familiarity",
    "unfamiliarity_grad": "familiarity",
    "train_model": "familiarity",
    "ridf": "familiarity",
    "METHODS": "options",
    "load_sweep": "sweeps",
    "run_sweep": "sweeps",
}


_RENAMED = {  # old name -> (new name, why): still answered, with a DeprecationWarning (CHANGELOG)
    "homing_quality": ("homing_loss", "lower is better"),  # mean 1 - cos error: a loss, not a quality
    "homing_quality_grad": ("homing_loss_grad", "lower is better"),
    "Program": ("MethodSet", "a program is what XLA compiles"),
}

_PACKAGES = (
    "core",
    "cli",
    "envs",
    "evaluate",
    "familiarity",
    "gradients",
    "images",
    "options",
    "outputs",
    "plots",
    "reproduce",
    "studies",
    "sweeps",
)


def __getattr__(name: str):
    import importlib

    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value  # later lookups are plain attribute reads
        return value
    if name in _RENAMED:
        new, why = _RENAMED[name]
        warnings.warn(f"delvjax.{name} is renamed delvjax.{new} ({why})", DeprecationWarning, stacklevel=2)
        return __getattr__(new)
    if name in _PACKAGES:  # `delvjax.core.maps` after a bare `import delvjax`
        return importlib.import_module(f".{name}", __name__)
    if name == "__all__":  # the names below and the registered methods' classes (read now, not kept)
        return [*_PUBLIC, *(n for n in _method_classes() if n not in _PUBLIC)]
    if not name.startswith("_") and name in (methods := _method_classes()):
        return methods[name]  # not kept in globals(): `options.unregister` takes it away again
    raise AttributeError(f"module 'delvjax' has no attribute {name!r}")


def _method_classes() -> dict:
    """The public method classes by name: the registry's (`options.public_classes`; this loads JAX)."""
    import importlib

    return importlib.import_module(".options", __name__).public_classes()


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | set(_PACKAGES) | set(_method_classes()))


_PUBLIC = [  # with the registered methods' classes, `__all__` (made on first use, `__getattr__`)
    "Grid",
    "Rules",
    "Compass",
    "Env",
    "HomingMethod",
    "InputError",
    "METHODS",
    "Method",
    "Noise",
    "MethodSet",
    "Sensor",
    "Snapshot",
    "UnitMove",
    "VectorMap",
    "VisualCompass",
    "catchment",
    "error_curve",
    "homing_loss",
    "homing_loss_grad",
    "find_traps",
    "optimise_layout",
    "sensitivity",
    "error_point_rates",
    "load_env",
    "make_env",
    "success_rate",
    "summarize_map",
    "load_sweep",
    "run_sweep",
    "to_dataframe",
    "to_xarray",
    "trajectories",
    "vector_map",
    "ImageSettings",
    "render_database",
    "render_in_memory",
    "rendered_database",
    "load_database",
    "import_database",
    "database_vector_map",
    "database_catchment",
    "database_rollouts",
]
__version__ = "0.1.0"
