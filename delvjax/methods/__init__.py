"""Homing methods, all with one signature (STYLE.md):

    direction(home: UnitMove, view: UnitMove, config: Config) -> (angle, valid)

`home` is what was recorded at home (a unit move from home along alpha_r), `view` the
unit move that ended at the current point; `angle` is the homing direction in the
agent's frame at the end of that move (radians), `valid` False where it is undefined
(then `angle` is NaN). Maps, rollouts and sweeps are written once against this.
A new method is one new module plus one line in `METHODS`.
"""

from __future__ import annotations

from typing import Callable

from . import acv, alv, delv, mfdid, warping
from .compass import with_heading_source

Method = Callable

METHODS: dict[str, Method] = {
    "delv": delv.direction,
    "delv-compass": with_heading_source(delv.direction_with_heading, "compass"),
    "delv-visual": with_heading_source(delv.direction_with_heading, "visual"),
    "alv": with_heading_source(alv.direction_with_heading, "compass"),
    "alv-visual": with_heading_source(alv.direction_with_heading, "visual"),
    "acv": with_heading_source(acv.direction_with_heading, "compass"),
    "acv-visual": with_heading_source(acv.direction_with_heading, "visual"),
    "warping": warping.direction,
    "mfdid": with_heading_source(mfdid.direction_with_heading, "compass"),
}

DESCRIPTIONS: dict[str, str] = {
    "delv": "DELV, no compass: all cyclic shifts x n_heading heading hypotheses (thesis ch. 3-4)",
    "delv-compass": "DELV with a compass: only the cyclic shift is searched (thesis ch. 5)",
    "delv-visual": "DELV with the visual compass of SPEC 4.4 (thesis 5.3.2)",
    "alv": "average landmark vector with a compass (Lambrinos 2000; thesis 3.3.2)",
    "alv-visual": "ALV with the visual compass (thesis 5.3.2)",
    "acv": "average correction vector with a compass (Hong 1992; thesis Eq 5.2)",
    "acv-visual": "ACV with the visual compass (thesis 5.3.2)",
    "warping": "predictive image matching, 72 alpha x 15 rho x 72 psi, no compass (Franz 1998; thesis 4.2)",
    "mfdid": "matched-filter descent in image distances with a compass (Moller & Vardy 2006)",
}


def uses_start_view(name: str) -> bool:
    """Whether the method reads the snapshot at the start of the agent's unit move (DELV's
    motion parallax, docs/model.md §3.1); the others read only the current view."""
    return name.split("-")[0] == "delv"


def uses_gray(name: str, channel: str) -> bool:
    """Whether the method reads the gray channel (docs/model.md §2.2): the visual compass
    (§4.4), or an image method (warping, MFDID) on `channel="gray"`."""
    return name.endswith("-visual") or (name in ("warping", "mfdid") and channel == "gray")


def get_method(name: str) -> Method:
    from ..errors import InputError

    if name not in METHODS:
        raise InputError("method", name, f"unknown method (choose from {', '.join(METHODS)})")
    return METHODS[name]
