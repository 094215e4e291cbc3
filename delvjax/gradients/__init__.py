"""The differentiable path (docs/differentiable.md): homing loss and its gradient, the
sensitivity of homing to the world and the agent, trap points, landmark layout design."""

from ._layout import optimise_layout as optimise_layout
from ._loss import homing_loss as homing_loss
from ._sensitivity import sensitivity as sensitivity
from ._sensitivity import sensitivity_profiles as sensitivity_profiles
from ._smoothing import SAMPLES as SAMPLES
from ._smoothing import SMOOTHING_CM as SMOOTHING_CM
from ._smoothing import SMOOTHING_DEG as SMOOTHING_DEG
from ._smoothing import homing_loss_grad as homing_loss_grad
from ._traps import find_traps as find_traps
