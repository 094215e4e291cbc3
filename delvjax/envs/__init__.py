"""Environments from user input: the built-in presets, JSON files, seeded random layouts and the
world ensembles of the thesis's families (docs/model.md §6-7, §6.1)."""

from ._ensembles import FAMILIES as FAMILIES
from ._ensembles import ensemble_envs as ensemble_envs
from ._ensembles import family as family
from ._ensembles import member_layouts as member_layouts
from ._ensembles import violations as violations
from ._ensembles import world_properties as world_properties
from ._presets import PRESET_DESCRIPTIONS as PRESET_DESCRIPTIONS
from ._presets import PRESETS as PRESETS
from ._presets import env_from_dict as env_from_dict
from ._presets import env_to_dict as env_to_dict
from ._presets import load_env as load_env
from ._presets import make_env as make_env
from ._presets import random_env as random_env
