"""A claim of the thesis as one object: its quote and statement (`delvjax.studies.thesis`), its check and tolerance.

`Claim` holds side by side what the thesis says (id, section, line, quote, statement, needs: one entry of
`delvjax.studies.thesis.CLAIMS`) and how this project judges it (`check`, a function of `get` returning
(ours, verdict, reasons), and `tolerance`, the check's rule and tolerance, which ends every why text).
`@check(claim_id, tolerance)` (`delvjax.studies.claims._common`) registers a check; `claims(quotes, checks)`
joins the two in thesis order and refuses a claim without a check or a check of no claim.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields


@dataclass(frozen=True)
class Claim:
    """One claim: what the thesis says and how it is checked (module docstring). Reads like the thesis's dict
    too (`claim["id"]`, `as_dict()`)."""

    id: str
    section: str
    line: int
    quote: str
    statement: str
    needs: tuple[str, ...]
    check: Callable
    tolerance: str

    def __getitem__(self, key: str):
        if key not in self.__dataclass_fields__:
            raise KeyError(key)
        return getattr(self, key)

    def as_dict(self) -> dict:
        """The thesis's fields (no check): the entry of `delvjax.studies.thesis.CLAIMS`."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in ("check", "tolerance")}


def claims(quotes: list[dict], checks: dict[str, tuple[Callable, str]]) -> list[Claim]:
    """One Claim per quote (thesis order), with its check and tolerance from `checks` (id -> (check,
    tolerance)); ValueError naming the ids when a claim has no check or a check no claim."""
    ids = [q["id"] for q in quotes]
    unchecked = [i for i in ids if i not in checks]
    unknown = sorted(set(checks) - set(ids))
    if unchecked or unknown or len(set(ids)) != len(ids):
        raise ValueError(
            f"claims and checks do not pair: no check for {unchecked}, no claim for {unknown}, "
            f"ids given twice {sorted({i for i in ids if ids.count(i) > 1})}"
        )
    return [
        Claim(
            **{k: q[k] for k in ("id", "section", "line", "quote", "statement")},
            needs=tuple(q["needs"]),
            check=checks[q["id"]][0],
            tolerance=checks[q["id"]][1],
        )
        for q in quotes
    ]
