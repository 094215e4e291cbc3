"""The claim-check registry and the helpers the checks share (used by `studies.claims`).

CHECKS maps a claim id of `studies.thesis.CLAIMS` to its check, a function of `get` (key ->
number, raising Missing when the study that makes it was not run) returning (ours, verdict,
why); `@check(claim_id)` registers one. The helpers format numbers and combine parts into a
verdict. The checks themselves are in `studies.claims_ch4` and `studies.claims_ch5`.
"""

from __future__ import annotations

from typing import Callable

CHECKS: dict[str, Callable] = {}


def check(claim_id: str):
    def deco(fn):
        CHECKS[claim_id] = fn
        return fn
    return deco


class Missing(KeyError):
    """A number the claim needs was not produced (its study was not run)."""


# --- helpers ----------------------------------------------------------------------------------

ENVS = ("env1", "env2", "env3")
BACKGROUNDS = ("distant", "walls", "none")


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

