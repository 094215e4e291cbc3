"""Homing methods as equinox modules (docs/model.md §3-4; the protocol: `base.Method`).

A new method is one module file here (a `HomingMethod` subclass) plus one line in the
registry of names, `delvjax/options/_registry.py`, whose classes are the public methods
(`delvjax.<Class>`; `options._registry.public_classes`). The names below are the core's
own shortcuts.
"""

from .acv import ACV
from .alv import ALV
from .base import HomingMethod, Method
from .cartwright_collett import CartwrightCollett
from .delv import DELV
from .delv_gap import DELVGap
from .delv_refined import DELVRefined
from .heading import Compass, HeadingSource, VisualCompass
from .hybrid import Hybrid
from .mfdid import MFDID
from .minwarping import MinWarping
from .program import Program
from .warping import Warping
from .warping2d import Warping2D

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
    "Hybrid",
    "MFDID",
    "Method",
    "MinWarping",
    "Program",
    "VisualCompass",
    "Warping",
    "Warping2D",
]
