"""Thesis-style figures from result arrays, never recomputing: vector maps, error curves,
catchment maps, success rates, trajectories, sweeps, gradients and image experiments; and the
drawing pieces the studies compose into their own figures (panels, legends, styles)."""

from ._gradients import landmark_figure as landmark_figure
from ._gradients import layout_figure as layout_figure
from ._gradients import parameter_figure as parameter_figure
from ._gradients import profile_figure as profile_figure
from ._gradients import trap_figure as trap_figure
from ._images import database_catchment_figure as database_catchment_figure
from ._images import database_map_figure as database_map_figure
from ._images import paths_figure as paths_figure
from ._images import pipeline_figure as pipeline_figure
from ._maps import HOMING_ARROW as HOMING_ARROW
from ._maps import draw_env as draw_env
from ._maps import draw_vector_map as draw_vector_map
from ._maps import environments_figure as environments_figure
from ._maps import error_curve_figure as error_curve_figure
from ._maps import subplots as subplots
from ._maps import vector_map_figure as vector_map_figure
from ._maps import vector_map_handles as vector_map_handles
from ._rollouts import CATCHMENT_SQUARE as CATCHMENT_SQUARE
from ._rollouts import catchment_figure as catchment_figure
from ._rollouts import catchment_handles as catchment_handles
from ._rollouts import catchment_panel as catchment_panel
from ._rollouts import has_uncounted as has_uncounted
from ._rollouts import success_rate_figure as success_rate_figure
from ._rollouts import trajectories_figure as trajectories_figure
from ._sweep import sweep_figure as sweep_figure
