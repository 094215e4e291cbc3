"""Homing rollouts (thesis §4.3, §5.3.1; docs/model.md §5), split by job:

rules (outcomes, the two rules, a point's status), step (one move of one lane), lanes (the
scheduler), trials (blocks of trials as one program), release (seeded release points),
catchment, success (success rate vs distance), trajectories.
"""

from .catchment import Catchment, catchment_area, catchment_summary, hidden_masks, occlusion_masks, under_release
from .release import START_TRIES, release_points
from .rules import (ARENA, COLLISIONS, DEFAULT_DISTANCES, DEFAULT_FIRST_MOVE, DEFAULT_LANES, DEFAULT_RULES, EXCLUDED,
                    FIRST_MOVES, HOMING_RULES, HOME_RADIUS, HOME_TOLERANCE, LANDMARK, MAX_STEPS, NEAR_WALL, N_STARTS, OUTCOMES, PHYSICAL_RULES, RUNNING,
                    SUCCESS, TIMEOUT, TRIALS_PER_DISTANCE, catchment_counted, check_rules, position_status, rollout_keys,
                    wall_margin)
from .step import move_poses
from .success import SuccessRate, success_rate_trials, wilson_interval_pct
from .trajectories import Trajectories, trajectory_trials
from .trials import MASK_ROWS, TRIAL_BLOCK, Trials, home_record, run_trials, trial_block

__all__ = ["ARENA", "COLLISIONS", "Catchment", "DEFAULT_DISTANCES", "DEFAULT_FIRST_MOVE", "DEFAULT_LANES", "HOMING_RULES",
           "catchment_counted", "wall_margin", "NEAR_WALL", "DEFAULT_RULES", "EXCLUDED",
           "FIRST_MOVES", "HOME_RADIUS", "HOME_TOLERANCE", "LANDMARK", "MASK_ROWS", "MAX_STEPS", "N_STARTS", "OUTCOMES",
           "PHYSICAL_RULES", "RUNNING", "START_TRIES", "SUCCESS", "SuccessRate", "TIMEOUT", "TRIALS_PER_DISTANCE", "TRIAL_BLOCK",
           "Trajectories", "Trials", "catchment_area", "catchment_summary", "check_rules", "hidden_masks", "under_release",
           "home_record", "move_poses", "occlusion_masks", "position_status", "release_points", "rollout_keys",
           "run_trials", "success_rate_trials", "trajectory_trials", "trial_block", "wilson_interval_pct"]
