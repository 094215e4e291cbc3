"""The one-line help of each command of `delvjax` (`delvjax --help` and the commands' parsers), and the
version (`delvjax --version`)."""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as installed

DESCRIPTION = "Visual homing methods (DELV, ALV, ACV, ...) as JAX batch evaluators."
# command -> its one line in `delvjax --help` (the commands' parsers read it from here)
COMMAND_HELP = {
    "envs": "list the built-in environments and methods",
    "vector-map": "homing direction at every grid point (docs/model.md §5; Figs 4.2/4.3)",
    "reproduce": "every simulation study of the thesis, a report beside the thesis's numbers",
    "catchment": "catchment area: a rollout from every grid point (docs/model.md §5; Figs 4.5, 5.5)",
    "success-rate": "success rate vs release distance (docs/model.md §5; Figs 4.10b, 5.7b)",
    "trajectories": "homing paths from chosen release points (docs/model.md §5; Figs 4.11, 5.8)",
    "sweep": "every combination of the axes of a sweep file (TOML), one program per shape",
    "plot-sweep": "heat maps or line plots (95 %% intervals over seeds) of a finished sweep",
    "sensitivity": "which landmark matters most, and the sensitivity of homing loss to d and the noise (gradients; docs/differentiable.md)",
    "traps": "trap points (sinks, saddles, sources) of a homing field near its failed rollouts (optimistix; docs/differentiable.md)",
    "optimise-layout": "move the landmarks to minimise the homing loss (optimistix BFGS), compare by catchment (docs/differentiable.md)",
    "images": "image databases: render one from a world, import one (docs/images.md)",
    "familiarity": "route following by visual familiarity: perfect memory, InfoMax, mushroom body (docs/familiarity.md)",
}


def version() -> str:
    """The installed delvjax version (package metadata; no JAX loaded)."""
    try:
        return installed("delvjax")
    except PackageNotFoundError:  # run from a source tree that is not installed
        return "unknown (not installed)"
