"""Why a thesis number lies outside our band (`studies/runs/_ensemble_gaps.py`): each cause's rule fires on the
row it describes and on no other, and a gap no rule explains is counted as unexplained with its direction."""

from __future__ import annotations

import json

import pytest

from delvjax.studies.runs import _ensemble_gaps, _gap_probe
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


# --- the gap probe's rule (studies/runs/_gap_probe.py, _gap_probes.json) ---------------------------------------


def probe_row(**over) -> dict:
    base = {
        "probe": "bearing5",
        "cause": "5° of bearing noise",
        "hypothesis": "h",
        "source": "Table 5.3",
        "world": "env1",
        "method": "acv",
        "k": 1,
        "quantity": "catchment %",
        "thesis": 30.0,
        "lo": 20.0,
        "median": 35.0,
        "hi": 45.0,
        "members": 16,
        "inside": True,
    }
    return base | over


@pytest.mark.parametrize(
    "over, cause",
    [
        ({}, "inside the band with 5° of bearing noise (gap probe bearing5: 20-45 over 16 members"),
        ({"inside": False, "lo": 32.0}, "unexplained: thesis below"),  # the alternative's band misses it
        ({"inside": False, "lo": 30.5}, "within one grid point of the band with 5° of bearing noise"),
        ({"k": 2}, "unexplained"),  # another thesis number
        ({"world": "env2"}, "unexplained"),
        ({"quantity": "e>45 %"}, "unexplained"),
        ({"thesis": 31.0}, "unexplained"),  # the probe measured another value of the thesis (a stale file)
    ],
)
def test_a_probe_band_holding_the_thesis_number_names_its_cause(over, cause):
    assert gap_cause(row(), 100.0, probes=[probe_row(**over)]).startswith(cause)


def test_earlier_causes_win_over_the_probe_and_the_first_probe_is_named():
    probes = [probe_row(probe="home75", cause="a 75 cm home radius"), probe_row()]
    assert gap_cause(row(thesis=49.5), 100.0, probes=probes).startswith("within one grid point")
    assert gap_cause(row(), 100.0, probes=probes).startswith("inside the band with a 75 cm home radius")
    assert gap_cause(row(), 100.0, probes=[]).startswith("unexplained")


@pytest.mark.parametrize(
    "method, k, doubted", [("delv-compass", 1, True), ("delv-compass", 0, False), ("acv", 1, False)]
)
def test_table5_3_env1_delv_compass_is_doubted_where_fig5_10_prints_another_value(method, k, doubted):
    cause = gap_cause(row(method=method, k=k), 100.0, probes=[])
    assert cause.startswith("a thesis entry its notes doubt (fig5_10_vs_table5_3)") == doubted


def test_a_probe_that_moves_more_thesis_numbers_out_than_in_names_no_cause():
    """The default probe is the reference, never a cause; a probe with a negative net gain is no cause either."""
    assert gap_cause(row(), 100.0, probes=[probe_row(probe="default")]).startswith("unexplained")
    assert gap_cause(row(), 100.0, probes=[probe_row(net=-3, keeps=[5, 8, 20])]).startswith("unexplained")
    cause = gap_cause(row(), 100.0, probes=[probe_row(net=2, keeps=[10, 8, 20])])
    assert "10 of its 20 thesis numbers inside, 8 by default" in cause


def test_the_probes_grid_step_is_the_committed_files():
    """A probe band one grid point short names its cause: the step must be the probe file's grid's."""
    doc = json.loads(_gap_probe.PROBE_FILE.read_text())
    assert doc["spacing_cm"] == _ensemble_gaps.PROBE_SPACING and _ensemble_gaps.grid_step(doc["spacing_cm"]) == 1.0
