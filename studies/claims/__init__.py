"""The thesis's claims, each checked against this run's numbers (the report's claims table).

`evaluate(numbers)` takes {study: {key: value}} (the `numbers` of every study.json) and
returns one row per claim of CLAIMS: section, quote, statement, our
numbers, a verdict ("holds", "partly", "fails", "cannot tell" when the numbers compared are
at the ceiling, or "n/a" when a study it needs was not run or its numbers are unusable) and
why (ending with the claim's rule and tolerance). Verdicts are computed here, never typed in.

CLAIMS is one `Claim` per claim of `delvjax.studies.thesis.CLAIMS`, in thesis order: its quote, section,
statement and needs beside its check and tolerance (`delvjax.studies.claims._claim`); CHECKS maps an id
to its check. The checks live in `delvjax.studies.claims._ch4` and `delvjax.studies.claims._ch5` (one
function per claim, registered by `@check(id, tolerance)`), the registry and shared helpers in
`delvjax.studies.claims._common`; this module imports them all and is the one to import from.
"""

from __future__ import annotations

from .. import thesis
from . import (
    _ch4 as claims_ch4,
)
from . import (
    _ch4_more as claims_ch4_more,
)
from . import (
    _ch5 as claims_ch5,
)
from . import (
    _ch5_occlusion as claims_ch5_occlusion,
)
from . import (
    _ch5_visual as claims_ch5_visual,
)
from ._claim import Claim, claims
from ._common import BACKGROUNDS, CANNOT_TELL, CHECKED, ENVS, Missing, Undefined, _n, check, why_text

__all__ = [
    "BACKGROUNDS",
    "CHECKS",
    "CLAIMS",
    "Claim",
    "ENVS",
    "WORLD_FAILS",
    "WORLD_HOLDS",
    "Missing",
    "Undefined",
    "check",
    "evaluate",
    "world_verdict",
]

_CHECK_MODULES = (
    claims_ch4,
    claims_ch4_more,
    claims_ch5,
    claims_ch5_occlusion,
    claims_ch5_visual,
)  # importing them fills CHECKED, chapter 4 first
CLAIMS: list[Claim] = claims(thesis.CLAIMS, CHECKED)  # a claim without a check, or a check of none: refused here
CHECKS = {c.id: c.check for c in CLAIMS}


GRID_KEYS = (
    "map:",
    "catchment",
    "occlusion:",
    "gap:",
    "visual:",
    "compass_noise:",
    "error_curve:",
    "sensitivity:",
)
TRIAL_KEYS = ("success", "trajectories:")
# what the counts `n:KEY` of a key that is no error curve count (by the key's prefix)
SAMPLE_WORDS = (
    ("fail_", "counted grid points in the region"),
    ("map:", "counted grid points in the region"),
    ("robot_images:", "database points"),
)


def _sample_words(key: str) -> str:
    if ":catchment_pct" in key and key.startswith("robot_images:"):
        return "releases"
    return next((words for prefix, words in SAMPLE_WORDS if key.startswith(prefix)), "points in an error-curve bin")


def smallest_sample(keys: list[str], flat: dict, settings: dict | None) -> tuple[float, str]:
    """The smallest sample behind numbers `keys`: the fewest observations a study recorded under `n:KEY`
    (the points of an error-curve bin, the counted grid points of a hull region, the points and releases
    of a robot-image map), the trials per release distance of a success rate, or the cells of the grid
    (docs/reproduce.md "Claims"); (inf, "") when none is known."""
    found: list[tuple[float, str]] = []
    settings = settings or {}
    for key in keys:
        counts = [c for c in flat.get(f"n:{key}") or [] if c]
        if counts:
            found.append((min(counts), f"{min(counts)} {_sample_words(key)}"))
        elif key.startswith(TRIAL_KEYS) and settings.get("trials"):
            found.append((settings["trials"], f"{settings['trials']} trials per release distance"))
        elif key.startswith(GRID_KEYS) and settings.get("spacing"):
            side = round(1000.0 / settings["spacing"])
            found.append((side * side, f"a {side} × {side} grid"))
    return min(found, default=(float("inf"), ""))


def evaluate(numbers_by_study: dict[str, dict], settings: dict | None = None) -> list[dict]:
    """One row per claim (module docstring); `settings` (the run's spacing and trials) gives each row the
    smallest sample behind its verdict (`sample`)."""
    flat = {}
    for numbers in numbers_by_study.values():
        flat.update(numbers)
    read: list[str] = []

    def get(key):
        read.append(key)
        if key not in flat:
            raise Missing(key)
        if flat[key] is None:
            raise Undefined(key)
        return flat[key]

    rows = []
    for claim in CLAIMS:
        row = {k: claim[k] for k in ("id", "section", "quote", "statement")}
        read.clear()
        try:
            ours, verdict, why = claim.check(get)
            why = why_text(why, claim.tolerance)
        except Undefined as exc:  # the study ran; the number has no value at these settings
            ours = "; ".join(f"{k} = {'no value' if flat[k] is None else _n(flat[k])}" for k in read)
            verdict = CANNOT_TELL
            why = f"{exc.args[0]} has no value at these settings (e.g. no grid point in the region it counts)"
        except Missing as exc:
            ours, verdict, why = "", "n/a", f"needs {exc.args[0]} (study not run)"
        except (TypeError, ValueError, IndexError, ZeroDivisionError) as exc:  # a number of the wrong shape
            ours, verdict, why = "", "n/a", f"numbers unusable ({type(exc).__name__}: {exc})"
        row.update(ours=ours, verdict=verdict, why=why)
        row["sample"] = smallest_sample(read, flat, settings)[1] if row["verdict"] != "n/a" else ""
        row["over_worlds"] = over_worlds(flat, claim["id"])
        rows.append(row)
    return rows


WORLD_HOLDS, WORLD_FAILS = 80.0, 20.0  # % of ensemble members: a claim holds at or above, fails at or below


def world_verdict(holds_pct: float, ceiling_pct: float, partly_pct: float = 0.0) -> str:
    """The verdict over worlds from the shares of members in which a claim's check holds and says "partly":
    "cannot tell" when most members cannot tell (a ceiling); holds when it holds in at least WORLD_HOLDS %;
    fails when it holds or partly holds in at most WORLD_FAILS % (it fails in the rest); partly when it holds or
    partly holds in at least WORLD_HOLDS % (a claim that holds in part in most worlds does not fail there);
    else it depends on the world (docs/reproduce.md "Ensembles")."""
    if ceiling_pct > 50.0:
        return "cannot tell (most members at a ceiling)"
    if holds_pct >= WORLD_HOLDS:
        return "holds"
    if holds_pct + partly_pct <= WORLD_FAILS:
        return "fails"
    return "partly" if holds_pct + partly_pct >= WORLD_HOLDS else "depends on the world"


def over_worlds(flat: dict, claim_id: str) -> str:
    """The claim over the world ensembles (`studies/runs/ensembles.py`, `ensemble:claim:<id>` = [holds %,
    interval low, high, members, cannot tell %, partly %]): its verdict over worlds and "holds in X % of N
    members [a-b %], partly in Y %" (a member where the check says "partly" does not count as holding);
    "" when the ensemble study was not run, "not covered" when the claim's numbers are not among
    the ensemble's."""
    if "ensemble:members" not in flat:
        return ""
    row = flat.get(f"ensemble:claim:{claim_id}")
    if not isinstance(row, list) or len(row) not in (5, 6):
        return "not covered (needs numbers the ensembles do not make)"
    p, lo, hi, n, ceiling, partly = (*row, 0.0)[:6]  # partly: recorded since 2026-12-06
    text = f"{world_verdict(p, ceiling, partly)}: holds in {p:.0f} % of {n:.0f} members [{lo:.0f}-{hi:.0f} %]"
    text += f", partly in {partly:.0f} %" if partly else ""
    return text + (f", {ceiling:.0f} % at a ceiling" if ceiling else "")
