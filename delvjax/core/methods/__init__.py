"""Homing methods as equinox modules (docs/model.md §3-4; the protocol: `base.Method`).

A new method is one module file here (a `HomingMethod` subclass) plus one line in the
registry of names, `delvjax/options/_registry.py`.
"""

from .acv import ACV
from .alv import ALV
from .base import HomingMethod, Method
from .cartwright_collett import CartwrightCollett
from .delv import DELV
from .delv_gap import DELVGap
from .delv_refined import DELVRefined
from .heading import Compass, HeadingSource, VisualCompass
from .mfdid import MFDID
from .program import Program
from .warping import Warping

__all__ = [
    "ACV",
    "ALV",
    "CartwrightCollett",
    "Compass",
    "DELV",
    "DELVGap",
    "DELVRefined",
    "HeadingSource",
    "HomingMethod",
    "MFDID",
    "Method",
    "Program",
    "VisualCompass",
    "Warping",
]
