"""Thesis-style figures from result arrays, never recomputing: vector maps, error curves,
catchment maps, success rates, trajectories, sweeps and image experiments."""

from ._images import database_map_figure as database_map_figure
from ._maps import error_curve_figure as error_curve_figure
from ._maps import vector_map_figure as vector_map_figure
from ._rollouts import catchment_figure as catchment_figure
from ._rollouts import success_rate_figure as success_rate_figure
from ._rollouts import trajectories_figure as trajectories_figure
from ._sweep import sweep_figure as sweep_figure
