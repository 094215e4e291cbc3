"""The differentiable path (docs/differentiable.md): homing quality and its gradient, the
sensitivity of homing to the world and the agent, trap points, landmark layout design."""

from ._layout import optimise_layout as optimise_layout
from ._quality import homing_quality as homing_quality
from ._quality import homing_quality_grad as homing_quality_grad
from ._sensitivity import sensitivity as sensitivity
from ._traps import find_traps as find_traps
