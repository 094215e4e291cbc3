"""A rare world of the family (`studies/runs/_gap_tail.py`): the share of many members that reach a thesis number
outside our band, on its side, names the cause only above MIN_SHARE, with the property that separates them."""

from __future__ import annotations

import numpy as np

from delvjax.studies.runs import _gap_tail
from delvjax.studies.runs._ensemble_gaps import gap_cause


def gap(**over) -> dict:
    base = {
        "source": "Table 5.1",
        "world": "env1",
        "method": "acv",
        "k": 0,
        "quantity": "e>45 %",
        "thesis": 9.8,
        "ours 5 %": 16.9,
        "ours 95 %": 44.0,
        "inside band": False,
        "built-in over seeds": "",
    }
    return base | over


def tail(values, gaps=None, quantity="e>45 %") -> dict:
    n = len(values)
    gaps = np.linspace(100, 200, n) if gaps is None else gaps
    return {
        "world": "env1",
        "method": "acv",
        quantity: list(values),
        "properties": {"largest_gap_deg": list(gaps), "centroid_cm": list(np.full(n, 40.0))},
    }


def test_a_number_enough_members_reach_is_a_rare_world_with_its_separating_property():
    values = np.r_[5.0, 9.0, np.linspace(20, 40, 98)]  # two of 100 members at or below 9.8
    gaps = np.r_[90.0, 95.0, np.linspace(120, 200, 98)]  # ... and their largest gap is the smallest
    cause = _gap_tail.tail_cause(gap(), [tail(values, gaps)])
    assert cause.startswith("a world in the family's outer 2.0 % (2 of 100 members reach it")
    assert "largest_gap_deg 90-95" in cause and "AUC 0.00" in cause


def test_too_few_members_or_another_world_method_or_k_explain_nothing():
    values = np.r_[5.0, np.linspace(20, 40, 199)]  # one of 200: 0.5 % < MIN_SHARE
    assert _gap_tail.tail_cause(gap(), [tail(values)]) == ""
    enough = np.r_[5.0, 6.0, np.linspace(20, 40, 98)]
    assert _gap_tail.tail_cause(gap(method="alv"), [tail(enough)]) == ""
    assert _gap_tail.tail_cause(gap(k=1), [tail(enough)]) == ""
    assert _gap_tail.tail_cause(gap(world="env2"), [tail(enough)]) == ""


def test_the_side_of_the_band_decides_which_members_reach_it():
    catch = np.r_[100.0, 100.0, np.linspace(60, 97, 98)]
    above = gap(quantity="catchment %", thesis=100.0, **{"ours 5 %": 69.7, "ours 95 %": 96.8})
    assert "2 of 100" in _gap_tail.tail_cause(above, [tail(catch, quantity="catchment %")])
    below = gap(quantity="catchment %", thesis=50.0, **{"ours 5 %": 69.7, "ours 95 %": 96.8})
    assert _gap_tail.tail_cause(below, [tail(catch, quantity="catchment %")]) == ""


def test_gap_cause_names_the_rare_world_only_where_no_earlier_rule_does():
    values = np.r_[5.0, 9.0, np.linspace(20, 40, 98)]
    assert gap_cause(gap(), 100.0, probes=[], tails=[tail(values)]).startswith("a world in the family's outer")
    assert gap_cause(gap(), 100.0, probes=[], tails=[]).startswith("unexplained: thesis below")
    assert gap_cause(gap(thesis=16.5), 100.0, probes=[], tails=[tail(values)]).startswith("within one grid point")


def test_the_committed_tails_hold_every_member_of_their_family(tmp_path):
    for t in _gap_tail.load_tails():
        n = t["members"]
        assert all(len(t[q]) == n for q in _gap_tail.QUANTITIES)
        assert all(len(v) == n for v in t["properties"].values())
    path = tmp_path / "tails.json"
    _gap_tail.write_tails([{"world": "env1", "method": "acv", "members": 1}], path)
    _gap_tail.write_tails([{"world": "env2", "method": "acv", "members": 2}], path)
    _gap_tail.write_tails([{"world": "env1", "method": "acv", "members": 3}], path)
    assert sorted((r["world"], r["members"]) for r in _gap_tail.load_tails(path)) == [("env1", 3), ("env2", 2)]


def test_measure_gives_every_member_its_numbers_and_properties():
    row = _gap_tail.measure("env2", "acv", members=3, spacing=200.0)
    g45, g90, catch = (np.asarray(row[q]) for q in _gap_tail.QUANTITIES)
    assert len(g45) == len(g90) == len(catch) == 3 and np.all(g45 >= g90)
    assert np.all((0 <= catch) & (catch <= 100)) and set(row["properties"]) >= {"centroid_cm", "largest_gap_deg"}
