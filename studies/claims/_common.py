"""The claim-check registry and the helpers the checks share (used by `delvjax.studies.claims`).

`@check(claim_id, tolerance)` registers a claim's check in CHECKED (id -> (check, tolerance)): a function of
`get` (key -> number, raising Missing when the study that makes it was not run, Undefined when it ran but
recorded no value) returning (ours, verdict, reasons), and the text of its rule and tolerance.
`delvjax.studies.claims` joins each with its quote into a `Claim` (`_claim.py`); an id that is no claim of
`delvjax.studies.thesis.CLAIMS`, or one checked twice, is refused at import. The helpers format numbers
and combine parts into a verdict. The checks themselves are in `delvjax.studies.claims._ch4` and
`delvjax.studies.claims._ch5` (and their `_more`, `_occlusion`, `_visual` parts).

Verdicts (VERDICTS): "holds", "partly", "fails", "cannot tell" (also: a number without a value) and
"n/a" (a study not run).
Every why text ends with the claim's rule and tolerance (`why_text`): a check gives only its reasons
(`_why`). A comparison of
catchments or success rates whose sides are all at the ceiling (`at_ceiling`: every value
>= 99 %, or too close to 100 % to show the margin the claim needs) or where no method loses
anything under the condition the claim is about (`no_loss`) cannot tell the methods apart:
such a part is None, and `_combine` turns a claim whose decided parts all hold but some
part is None into "cannot tell", never "holds".
"""

from __future__ import annotations

from collections.abc import Callable

from .. import thesis

CHECKED: dict[str, tuple[Callable, str]] = {}  # claim id -> (check, tolerance), filled by @check
_IDS = frozenset(c["id"] for c in thesis.CLAIMS)

HOLDS, PARTLY, FAILS, CANNOT_TELL, NOT_RUN = "holds", "partly", "fails", "cannot tell", "n/a"
VERDICTS = (HOLDS, PARTLY, FAILS, CANNOT_TELL, NOT_RUN)
CEILING = 99.0  # %: a catchment or success rate at or above it has nothing left to lose or gain


def check(claim_id: str, tolerance: str):
    """Register the decorated function as the check of claim `claim_id`, judged by the rule `tolerance`
    (ValueError for an id that is no claim, or a claim checked twice)."""
    if claim_id not in _IDS:
        raise ValueError(f"@check: {claim_id!r} is no claim of delvjax.studies.thesis.CLAIMS")
    if not tolerance:
        raise ValueError(f"@check: claim {claim_id!r} needs its rule and tolerance")

    def deco(fn):
        if claim_id in CHECKED:
            raise ValueError(f"@check: claim {claim_id!r} is checked twice ({CHECKED[claim_id][0].__module__})")
        CHECKED[claim_id] = (fn, tolerance)
        return fn

    return deco


class Missing(KeyError):
    """A number the claim needs was not produced (its study was not run)."""


class Undefined(Missing):
    """A number the claim needs was recorded without a value (NaN, JSON null): its study ran, but the
    quantity is undefined at these settings, e.g. a share of grid points inside a region no point of a
    coarse grid falls in. The claim's verdict is "cannot tell", not "n/a"."""


# --- helpers ----------------------------------------------------------------------------------

ENVS = ("env1", "env2", "env3")
BACKGROUNDS = ("distant", "walls", "none")


def _flat(values):
    for v in values if isinstance(values, (list, tuple)) else [values]:
        if isinstance(v, (list, tuple)):
            yield from _flat(v)
        else:
            yield v


def at_ceiling(values, limit: float = CEILING) -> bool:
    """True when every value (%, nested lists allowed) is >= limit: compared with each other they
    cannot tell which side is better. Pass limit = 100 - margin when a part needs a margin."""
    vals = list(_flat(values))
    return bool(vals) and all(v >= limit for v in vals)


def at_floor(values, limit: float = 1.0) -> bool:
    """True when every value (an error rate in %, a loss in points) is <= limit: nothing to compare."""
    vals = list(_flat(values))
    return bool(vals) and all(v <= limit for v in vals)


def no_loss(losses, limit: float = 2.0) -> bool:
    """True when no method loses more than `limit` points under the claim's condition."""
    return at_floor(losses, limit)


def points_of(get, key: str) -> int | None:
    """The grid points behind share `key` (%): the smallest count a study recorded as `n:<key>`, or None."""
    counts = [c for c in _flat(_opt(get, f"n:{key}") or []) if c]
    return int(min(counts)) if counts else None


def beyond(pct: float, limit: float, n: int | None) -> bool | None:
    """The minimum-evidence rule of every check that compares a share of grid points (%, of `n` points)
    with a bound: True when it exceeds `limit` by more than one grid point's share (100 / n), False when
    it is within `limit`, None (cannot tell) when it exceeds `limit` only by the share of one grid point:
    a verdict must not rest on one grid point (1 of 12 points inside a hull is 8.3 %, and one point the
    other way makes it 0 %). `n` None (not recorded): the share alone decides."""
    if pct <= limit:
        return False
    return None if n and pct - 100.0 / n <= limit else True


def at_least(value: float, bound: float, *counts: int | None) -> bool | None:
    """`value >= bound` under the same rule as `beyond`, for a difference of shares (%, of `counts`
    points each): None (cannot tell) when moving one grid point of each share the other way would turn
    the answer (100 / n per count); counts None: the values alone decide."""
    slack = sum(100.0 / n for n in counts if n)
    if value >= bound:
        return True if value - slack >= bound else None
    return False if value + slack < bound else None


def _combine(parts) -> str:
    """Parts are True (holds), False (fails) or None (cannot tell, e.g. at the ceiling).
    holds: every part holds; cannot tell: the decided parts hold but some cannot be told
    (or none can); fails: every decided part fails; else partly."""
    parts = list(parts)
    known = [p for p in parts if p is not None]
    if not known:
        return CANNOT_TELL
    if all(known):
        return HOLDS if len(known) == len(parts) else CANNOT_TELL
    return FAILS if not any(known) else PARTLY


def _why(*reasons: str) -> str:
    """A check's reasons, empty ones left out (`why_text` adds the claim's rule)."""
    return "; ".join(r for r in reasons if r)


def why_text(reasons: str, tolerance: str) -> str:
    """The why text of a claims row: the check's reasons, then the claim's rule with its tolerance."""
    return (reasons + ". " if reasons else "") + "Rule: " + tolerance


def _opt(get, key):
    """A number shown for context only (None when its study did not record it)."""
    try:
        return get(key)
    except Missing:
        return None


FAILURES = (
    "timeout",
    "landmark",
    "arena",
)  # failure outcomes, as delvjax.studies.runs._common.FAILURES (no JAX import here)


def _failures(get, key: str) -> dict | None:
    """Failure counts by outcome (`<key>:timeout|landmark|arena`, `delvjax.studies.runs._common.record_failures`), or
    None when the run did not record them."""
    counts = {o: _opt(get, f"{key}:{o}") for o in FAILURES}
    return None if any(v is None for v in counts.values()) else {o: int(v) for o, v in counts.items()}


def _n(v) -> str:
    """A number or a list of numbers, 1 decimal."""
    if isinstance(v, (list, tuple)):
        return "/".join(_n(x) for x in v)
    return "–" if v is None else f"{v:.1f}"


def _verdict(parts: list[bool]) -> str:
    """holds if every part holds, fails if none does, else partly."""
    return "holds" if all(parts) else "fails" if not any(parts) else "partly"


def _share(flags) -> float:
    flags = list(flags)
    return sum(flags) / max(len(flags), 1)


def _pairs(a, b):
    return list(zip(a, b))


def _mean(v) -> float:
    return sum(v) / len(v)
