"""What the thesis reports for its simulation experiments, as plain data.

Source: Seung-Eun Yu, "Distance-Estimated Landmark Vector Model for Vision-Based Homing
Navigation" (PhD thesis), in the plain-text copy the project works from. Every
``line`` in this data is a 1-based line number in that file (``sed -n Np`` prints it). Chapters 4
(DELV without compass, predictive image matching) and 5 (DELV with compass, ACV, ALV,
occlusion, visual compass) hold the simulation results; chapter 6 summarises them.
Robotic-experiment numbers (§4.4) are kept apart in ``OTHER["robotic"]``.

Contents
--------
CATCHMENT       catchment area in % of the grid, ``CATCHMENT[source][env][method]`` is a list
                indexed by k = number of hidden (occluded) landmarks, k = 0, 1, 2(, 3). Only
                the k the thesis prints are listed (its "-" cells are left out).
CATCHMENT_SOURCES  where each top-level key of CATCHMENT comes from (section, caption, line).
ERROR_POINTS    error point rate in % of grid points, Tables 5.1 and 5.2:
                ``ERROR_POINTS[table][env][method] = {"gt45": [...k], "gt90": [...k]}``
                (angular error > 45 deg and > 90 deg).
ERROR_POINTS_SOURCES  where each table comes from.
OTHER           every other number the thesis prints about its simulations (thresholds
                quoted in the text, parameters of the runs), each with its source, plus the
                list of figures whose numbers the thesis does not print.
NOTES           inconsistencies and ambiguities found in the thesis text, each with its
                section, line and a one-sentence description.
CLAIMS          the qualitative / quantitative claims about the simulation results, each
                with a verbatim quote (shortened with "..." only), its line, a precise
                statement of what our results must show for the claim to hold, and the
                result quantities needed (``quantity:env:method[:detail]``). Joined with its
                check and tolerance it is a ``Claim`` of ``delvjax.studies.claims.CLAIMS``.

Keys
----
Methods: "delv" (DELV without compass, arrangement matching of the heading),
"delv-compass" (DELV with the true compass), "acv" (average correction vector, compass),
"alv" (average landmark vector, compass), "delv-visual" / "acv-visual" / "alv-visual" (the
compass replaced by the visual compass, §5.3.2), "warping" (predictive image matching of
Franz et al. 1998). Environments: "env1" (four landmarks around home, asymmetric), "env2"
(four at 90 deg), "env3" (four on one side of home), "ring3".."ring6" (L = 3..6 equally
spaced landmarks, Tables 5.2 / 5.4). NB: the thesis's L = 4 rows of Tables 5.2 and 5.4 are
copies of env1 / env2 rows (see NOTES), they are stored here as printed under "ring4".
In chapter 5 every DELV number is with the compass ("delv-compass"); the ACV / ALV numbers
of Tables 5.1-5.4 use the true compass ("acv", "alv").

The thesis gives no landmark coordinates, grid spacing or home radius; docs/model.md §6 says the
claims to check are the trends (who beats whom, how fast each degrades), not the digits.

Modules
-------
This module is the entry point (import from here); the data lives in
``delvjax.studies.thesis._numbers`` (CATCHMENT, ERROR_POINTS, their sources, OTHER),
``delvjax.studies.thesis._notes`` (NOTES), ``delvjax.studies.thesis._claims_ch4`` and
``delvjax.studies.thesis._claims_ch5`` (CLAIMS of chapter 4, and of chapter 5 plus the §6.2
summary; CLAIMS is their concatenation, in thesis order).
"""

from __future__ import annotations

from ._claims_ch4 import CLAIMS_CH4 as _CLAIMS_CH4
from ._claims_ch5 import CLAIMS_CH5 as _CLAIMS_CH5
from ._notes import NOTES
from ._numbers import CATCHMENT, CATCHMENT_SOURCES, ERROR_POINTS, ERROR_POINTS_SOURCES, OTHER

__all__ = [
    "THESIS_TITLE",
    "CATCHMENT",
    "CATCHMENT_SOURCES",
    "ERROR_POINTS",
    "ERROR_POINTS_SOURCES",
    "OTHER",
    "NOTES",
    "CLAIMS",
]

THESIS_TITLE = "Distance-Estimated Landmark Vector Model for Vision-Based Homing Navigation"

# ---------------------------------------------------------------------------------------
# 5. Claims about the simulation results, in thesis order: chapter 4, then chapter 5 and §6.2.
# ---------------------------------------------------------------------------------------
CLAIMS = [*_CLAIMS_CH4, *_CLAIMS_CH5]
