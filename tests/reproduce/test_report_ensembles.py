"""The report's lines on the ensemble studies (`delvjax/reproduce/_report.py` `ensemble_more`): the claims they
judge, the settings sentence with its best combination, and the claims whose verdict changes with the ranges."""

from __future__ import annotations

from types import SimpleNamespace

from delvjax.reproduce._report import ensemble_more

CLAIM = "occlusion_increases_errors"  # claim 22


def test_nothing_is_said_when_no_ensemble_study_ran():
    assert ensemble_more({}, {"catchment:env1:delv": 100.0}) == []


def test_the_settings_sentence_and_the_best_combination_are_quoted():
    flat = {
        "ensemble:claim:a": [1, 0, 2, 44, 0, 0],
        "ensemble:claim:b": [1, 0, 2, 44, 0, 0],
        "ensemble_settings:best": [17, 4.5, 4.08, 5.04],
        "ensemble_settings:score:default": 5.15,
    }
    record = SimpleNamespace(
        tables=[
            {"id": "settings_identified", "note": "The thesis's numbers identify the rules (default)."},
            {
                "id": "settings_design",
                "rows": [{"bearing noise (°)": 1.0, "home radius (cm)": 25.0, "rules": "default"}],
            },
        ]
    )
    text = "\n".join(ensemble_more({"ensemble_settings": record}, flat))
    assert "2 of the thesis's claims are judged over the ensembles' members" in text
    assert (
        "identify the rules (default). Best combination (bearing noise (°) 1.0, home radius (cm) 25.0, rules default): 4.50"
        in text
    )
    assert "[4.08-5.04]; every default 5.15." in text


def test_a_verdict_that_changes_with_the_ranges_gets_its_line_and_one_that_does_not_none():
    changed = {f"ensemble_ranges:{CLAIM}": [82.0, 64.0, 73.0]}  # holds narrowed, depends at 1 and 4/3
    text = ensemble_more({}, changed)[-1]
    assert "Claim 22 (occlusion_increases_errors): depends on the world at the default ranges (64 %" in text
    assert "narrowed by a third holds (82 %" in text
    assert ensemble_more({}, {f"ensemble_ranges:{CLAIM}": [70.0, 64.0, 73.0]})[-1].endswith(
        "no claim's verdict changes."
    )
