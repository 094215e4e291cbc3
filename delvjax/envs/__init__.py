"""Environments from user input: the built-in presets, JSON files, seeded random layouts
(docs/model.md §6-7)."""

from ._presets import PRESET_DESCRIPTIONS as PRESET_DESCRIPTIONS
from ._presets import PRESETS as PRESETS
from ._presets import env_from_dict as env_from_dict
from ._presets import env_to_dict as env_to_dict
from ._presets import load_env as load_env
from ._presets import make_env as make_env
from ._presets import random_env as random_env
