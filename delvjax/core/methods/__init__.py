"""Homing methods as equinox modules (docs/model.md §3-4; the protocol: `base.Method`).

A new method is one module file here (a `HomingMethod` subclass) plus one line in the
registry of names, `delvjax/options/_registry.py`, whose classes are the public methods
(`delvjax.<Class>`; `options._registry.public_classes`). The names below are the core's
own shortcuts.
"""

from ..deprecation import deprecated
from .acv import ACV
from .alv import ALV
from .base import HomingMethod, Method
from .cartwright_collett import CartwrightCollett
from .delv import DELV
from .delv_gap import DELVGap
from .delv_refined import DELVRefined
from .heading import Compass, HeadingSource, VisualCompass
from .hybrid import Hybrid
from .method_set import MethodSet
from .mfdid import MFDID
from .minwarping import MinWarping
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
    "MethodSet",
    "VisualCompass",
    "Warping",
    "Warping2D",
]


def __getattr__(name: str):
    if name == "Program":  # the name before this release: a program is what XLA compiles
        deprecated(
            "delvjax: Program is now MethodSet (several methods compiled into one program); Program goes next release"
        )
        return MethodSet
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
