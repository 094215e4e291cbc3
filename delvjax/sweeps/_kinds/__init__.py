"""The kinds of sweep (docs/sweeps.md), one class per kind (`base.SweepKind`: `vector_map.py`, `catchment.py`,
`success_rate.py`, `route_following.py`) and the registry `KINDS` (name -> kind; nothing else compares a kind's name), with what a sweep
does with cells of any kind (`cells.py`). To add a kind: CONTRIBUTING.md "Add a sweep kind"."""

from .base import SweepKind as SweepKind
from .catchment import CATCHMENT as CATCHMENT
from .catchment import catchment_metrics as catchment_metrics
from .cells import cell_setup as cell_setup
from .cells import evaluate as evaluate
from .cells import group_key as group_key
from .cells import idle_padding as idle_padding
from .cells import mask_rows as mask_rows
from .cells import programs_compiled as programs_compiled
from .cells import sum_names as sum_names
from .cells import traced as traced
from .route_following import ROUTE_FOLLOWING as ROUTE_FOLLOWING
from .success_rate import SUCCESS_RATE as SUCCESS_RATE
from .vector_map import VECTOR_MAP as VECTOR_MAP

KINDS: dict[str, SweepKind] = {k: k for k in (VECTOR_MAP, CATCHMENT, SUCCESS_RATE, ROUTE_FOLLOWING)}  # name -> kind
