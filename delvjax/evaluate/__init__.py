"""Evaluating a method on an environment: vector maps and rollouts (catchment, success rate,
trajectories; docs/model.md §5). The Python API the command line calls."""

from ._progress import OnStart as OnStart
from ._progress import Progress as Progress
from ._rollouts import catchment as catchment
from ._rollouts import success_rate as success_rate
from ._rollouts import trajectories as trajectories
from ._vector_map import vector_map as vector_map
