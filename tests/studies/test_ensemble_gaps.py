"""Why a thesis number lies outside our band (`studies/runs/_ensemble_gaps.py`): each cause's rule fires on the
row it describes and on no other, and a gap no rule explains is counted as unexplained with its direction."""

from __future__ import annotations

import pytest

from delvjax.studies.runs._ensemble_gaps import cause_counts, gap_cause, gaps_text, grid_step


def row(**over) -> dict:
    base = {
        "source": "Table 5.3",
        "world": "env1",
        "method": "acv",
        "k": 1,
        "quantity": "catchment %",
        "thesis": 30.0,
        "ours 5 %": 50.0,
        "ours 95 %": 80.0,
        "inside band": False,
        "built-in over seeds": "60.0-70.0 (5 seeds)",
    }
    return base | over


def test_the_grid_step_is_one_grid_point_in_percent():
    assert grid_step(100.0) == 1.0 and grid_step(200.0) == 4.0 and grid_step(25.0) == pytest.approx(100 / 1600)


@pytest.mark.parametrize(
    "over, cause",
    [
        ({"inside band": True}, ""),
        ({"source": "Table 5.4", "world": "ring4"}, "a thesis entry its notes doubt (table5_4_L4_copies_other_rows)"),
        (
            {"source": "Fig 5.10", "method": "delv-compass", "k": 2},
            "a thesis entry its notes doubt (fig5_10_vs_table5_3)",
        ),
        ({"2° bearing noise: 5 %": 25.0, "2° bearing noise: 95 %": 40.0}, "inside the band with 2° bearing noise"),
        ({"physical rules: 5 %": 10.0, "physical rules: 95 %": 20.0}, "between the default and the physical rules"),
        ({"thesis": 49.5}, "within one grid point (1 points) of the band"),
        ({"thesis": 81.0}, "within one grid point"),
        ({"built-in over seeds": "20.0-35.0 (5 seeds)"}, "inside the built-in world's range over five seeds"),
        ({}, "unexplained: thesis below our band"),
        ({"thesis": 95.0}, "unexplained: thesis above our band"),
        ({"source": "Fig 5.10", "method": "delv-compass", "k": 0}, "unexplained: thesis below"),  # k = 0 agrees
        ({"quantity": "e>45 %", "physical rules: 5 %": 10.0, "physical rules: 95 %": 20.0}, "unexplained"),
    ],
)
def test_each_cause_names_the_gap_it_explains(over, cause):
    assert gap_cause(row(**over), 100.0).startswith(cause)


def test_the_counts_say_how_many_gaps_have_no_cause():
    rows = [row(), row(thesis=95.0), row(thesis=49.5), row(inside_band=True)]
    rows[3]["inside band"] = True
    for r in rows:
        r["gap cause"] = gap_cause(r, 100.0)
    counts = cause_counts(rows)
    assert counts["within one grid point"] == 1 and sum(counts.values()) == 3
    assert gaps_text(rows).endswith("1 have a named cause, 2 none yet.")
