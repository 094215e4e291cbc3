"""One rollout step of one lane (docs/model.md §5 "Rollouts", noise in §2.5).

Noise in rollouts (`Noise.rollout_move`):
  * executed heading = commanded heading + N(0, motion_heading);
  * true length = d * (1 + N(0, step)) * (1 + N(0, motion_step)); the odometry reports d_hat = d;
  * the body turns by psi ~ N(0, turn) during the move (the end view has heading
    executed + psi); odometry reports psi_hat = psi + N(0, turn_odometry);
  * bearing and compass noise come from sensing the move just made.
All draws use the key fold_in(fold_in(key_rollout, trial key index), step index), so results
do not depend on how trials are scheduled; with every sigma 0 the draws are multiplied by 0.
A lane's first iteration at its release point computes the vector map's direction there
(a unit move ending at the release point, the vector map's noise stream). Under first_move
"release" (thesis Algorithm 2, the default) a method that needs a unit movement then moves along
the release heading and matches only after that move; under "homing" every method turns to the
direction computed at the release point.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..geometry import unit, wrap
from ..kernel import direction_from, map_poses
from ..methods.base import HomingMethod
from ..scene import Env
from ..sensing import MovePoses, UnitMove
from ..sensor import Sensor
from .rules import RUNNING, TIMEOUT, position_status


def move_poses(pos: Array, heading: Array, key: Array, sensor: Sensor) -> MovePoses:
    """The poses and odometry of one rollout move from `pos` with commanded `heading`."""
    heading_error, length, psi, psi_hat, k_obs = sensor.noise.rollout_move(key, sensor.d)
    executed = heading + heading_error
    return MovePoses(pos, pos + length * unit(executed), executed, executed + psi, psi_hat, k_obs)


class Rollout(eqx.Module):
    """What every step of a block of trials shares: the scene, the home record, the method, the
    sensor, the trials' key indices and visibility, the streams and the limits."""

    env: Env
    home: UnitMove
    method: HomingMethod
    sensor: Sensor
    key_index: ArrayLike
    mask_index: ArrayLike
    masks: ArrayLike
    k_roll: ArrayLike
    k_views: ArrayLike
    radius: ArrayLike
    max_steps: ArrayLike  # traced: every max_steps shares one program (the path buffer's length is run_block's)
    homing_first: ArrayLike
    collide: ArrayLike

    def advance(self, t: Array, pos: Array, heading: Array, step: Array, first: Array):
        """Trial t's first direction (at its release point) or its next move:
        (end, new heading, status, valid, world direction)."""
        at_release = map_poses(pos, heading, self.k_views, self.key_index[t], self.sensor)
        k = jax.random.fold_in(jax.random.fold_in(self.k_roll, self.key_index[t]), step)
        poses = jax.tree.map(lambda a, b: jnp.where(first, a, b), at_release, move_poses(pos, heading, k, self.sensor))
        direction, valid = direction_from(
            self.env, self.masks[self.mask_index[t]], poses, self.home, self.method, self.sensor
        )
        new_heading = jnp.where(valid, direction, wrap(poses.heading_end))
        # first_move "release" (thesis Algorithm 2): a method that needs a unit movement first moves d
        # along the release heading; one that reads only the current view turns to its direction here
        blind = ~self.homing_first & jnp.asarray(self.method.reads_start_view(), bool)
        first_heading = jnp.where(blind, heading, new_heading)
        status = position_status(self.env, poses.end, self.radius, self.collide)
        status = jnp.where((status == RUNNING) & (step + 1 >= self.max_steps), TIMEOUT, status)
        return poses.end, jnp.where(first, first_heading, new_heading), status, valid, direction
