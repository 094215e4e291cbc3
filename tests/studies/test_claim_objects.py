"""Claims as objects (issue 52): each claim's quote, check and tolerance side by side, and thesis numbers
read from one table (`delvjax.studies.thesis`), never typed again in study code."""

from __future__ import annotations

import io
import tokenize
from pathlib import Path

import pytest

from delvjax import studies
from delvjax.studies import claims, thesis
from delvjax.studies.claims._claim import claims as pair_claims
from delvjax.studies.claims._common import check

STUDY_CODE = [Path(studies.__file__).parent / folder for folder in ("runs", "claims")]


def test_every_claim_is_one_object_with_its_quote_check_and_tolerance():
    assert [c.id for c in claims.CLAIMS] == [c["id"] for c in thesis.CLAIMS]  # thesis order
    for claim, quote in zip(claims.CLAIMS, thesis.CLAIMS):
        assert claim.as_dict() == {**quote, "needs": tuple(quote["needs"])}
        assert claim["quote"] == quote["quote"] and callable(claim.check) and claim.tolerance
        assert claims.CHECKS[claim.id] is claim.check
    row = claims.evaluate({})[0]
    assert row["why"].endswith("(study not run)")
    rows = claims.evaluate(
        {"x": {"catchment:env1:delv": 90.0, "catchment:env2:delv": 90.0, "catchment:env3:delv": 50.0}}
    )
    assert rows[0]["why"].endswith("Rule: " + claims.CLAIMS[0].tolerance)


def test_a_check_of_no_claim_a_second_check_and_a_claim_without_one_are_refused():
    with pytest.raises(ValueError, match="no claim"):
        check("no_such_claim", "a rule")
    with pytest.raises(ValueError, match="checked twice"):
        check(claims.CLAIMS[0].id, "a rule")(lambda get: ("", "holds", ""))
    with pytest.raises(ValueError, match="needs its rule"):
        check(claims.CLAIMS[0].id, "")
    assert claims.CHECKS[claims.CLAIMS[0].id] is claims.CLAIMS[0].check  # the refused ones changed nothing
    checks = {c.id: (c.check, c.tolerance) for c in claims.CLAIMS}
    with pytest.raises(ValueError, match=f"no check for \\['{claims.CLAIMS[1].id}'\\]"):
        pair_claims(thesis.CLAIMS, {k: v for k, v in checks.items() if k != claims.CLAIMS[1].id})
    with pytest.raises(ValueError, match="no claim for \\['extra'\\]"):
        pair_claims(thesis.CLAIMS, {**checks, "extra": checks[claims.CLAIMS[0].id]})


def _two_decimals(table) -> set[float]:
    if isinstance(table, dict):
        return set().union(*map(_two_decimals, table.values()))
    if isinstance(table, list):
        return set().union(*map(_two_decimals, table)) if table else set()
    return {table} if isinstance(table, float) and round(table, 1) != table else set()


# float literals of the study code equal to a thesis number by chance (not typed-again thesis numbers)
NOT_THESIS = {
    ("ensembles.py", 0.15),  # the jitter of a strip plot
    ("_ch4_more.py", 0.75),  # shares of bins or cases ("mostly", "partly")
    ("_ch5_occlusion.py", 0.75),
}


def test_no_study_types_a_thesis_number_again():
    """A thesis number with two decimals (e.g. 92.01) written as a literal in studies/runs/ or studies/claims/
    is one typed again: it must be read from delvjax.studies.thesis (CATCHMENT, ERROR_POINTS)."""
    numbers = _two_decimals(thesis.CATCHMENT) | _two_decimals(thesis.ERROR_POINTS)
    assert {92.01, 74.85, 8.75} <= numbers
    typed = []
    for path in sorted(p for folder in STUDY_CODE for p in folder.glob("*.py")):
        for tok in tokenize.generate_tokens(io.StringIO(path.read_text()).readline):
            if tok.type == tokenize.NUMBER and "." in tok.string and float(tok.string) in numbers:
                if (path.name, float(tok.string)) not in NOT_THESIS:
                    typed.append(f"{path.name}:{tok.start[0]}: {tok.string}")
    assert not typed, typed
