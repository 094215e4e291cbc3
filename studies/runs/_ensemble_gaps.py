"""Why a thesis number lies outside our band over the worlds (docs/reproduce.md "Ensembles": every remaining gap
is inside the band or has its cause named). One rule per cause, in order; the first that applies names it, and
a gap no rule explains says "unexplained" with its direction, so the count of those is the open work."""

from __future__ import annotations

from collections import Counter

from ._gap_probe import load_probes, matching
from ._gap_tail import load_tails, tail_cause

PROBES = load_probes()  # the gap probe's bands (studies/runs/_gap_probes.json, `causes_probe --gaps`)
TAILS = load_tails()  # many members of one family and method (studies/runs/_gap_tails.json, `causes_probe --tail`)
PROBE_SPACING = 100.0  # cm: the probes' grid (the file's spacing_cm)

# Entries of the thesis's own tables that its notes (`studies/thesis/_notes.py`) call copies or suspect:
# (note id, source label, world, methods or None for every method, hidden k or None for every k)
SUSPECT = (
    ("table5_2_L4_copies_other_rows", "Table 5.2", "ring4", None, None),
    ("table5_4_L4_copies_other_rows", "Table 5.4", "ring4", None, None),
    ("fig5_10_vs_table5_3", "Fig 5.10", "env1", None, (1, 2)),
    ("table5_2_L5_duplicate_columns", "Table 5.2", "ring5", ("delv-compass", "acv"), (2, 3)),  # which is the copy?
    ("table5_2_L6_acv_k3", "Table 5.2", "ring6", ("acv",), (3,)),
    ("table5_4_L3_delv_100", "Table 5.4", "ring3", ("delv-compass",), (1,)),
    ("table5_4_k3_delv_equal", "Table 5.4", None, ("delv-compass",), (3,)),
    # the thesis prints env1's DELV-compass catchments twice: Table 5.3 (and line 902) 49.11 / 40.3 %, Fig 5.10's
    # caption (line 857) 82.04 / 59.11 %; which is right it does not say
    ("fig5_10_vs_table5_3", "Table 5.3", "env1", ("delv-compass",), (1, 2)),
)
SETTING_NAMES = ("2° bearing noise", "physical rules")  # the other settings' bands (`_ensemble_stats.SETTINGS`)


def grid_step(spacing: float, arena: float = 1000.0) -> float:
    """Percentage points one grid point moves a rate or catchment on the members' grid (10 x 10 at 100 cm: 1)."""
    side = round(arena / spacing)
    return 100.0 / (side * side)


def gap_cause(row: dict, spacing: float, probes: list[dict] | None = None, tails: list[dict] | None = None) -> str:
    """The cause of one thesis number's gap (a row of `distribution_rows`): "" inside the band; else the first
    of: a thesis entry its notes call a copy or suspect; inside the band of another unstated setting; a
    catchment between the default and the physical rules' bands; within one grid point of the band; the
    built-in world under five seeds reaching it; inside the band of an alternative the gap probe measured, or
    within one grid point of the probes' grid of it (`probes`, default the committed PROBES; a probe whose band
    holds it first); a world of the family that at least `_gap_tail.MIN_SHARE` % of many members reach (`tails`,
    default the committed `_gap_tails.json`); "unexplained" (above/below)."""
    if row["inside band"]:
        return ""
    for note, source, world, methods, ks in SUSPECT:
        if (
            row["source"] == source
            and world in (None, row["world"])
            and (methods is None or row["method"] in methods)
            and (ks is None or row["k"] in ks)
        ):
            return f"a thesis entry its notes doubt ({note})"
    value = row["thesis"]
    for name in SETTING_NAMES:
        lo, hi = row.get(f"{name}: 5 %"), row.get(f"{name}: 95 %")
        if lo is not None and lo <= value <= hi:
            return f"inside the band with {name} (a setting the thesis does not state)"
    lo, hi = row.get("physical rules: 5 %"), row.get("physical rules: 95 %")
    if (
        row["quantity"] == "catchment %"
        and lo is not None
        and min(lo, row["ours 5 %"]) <= value <= max(hi, row["ours 95 %"])
    ):
        return "between the default and the physical rules' bands (the thesis does not state its rule set)"
    step = grid_step(spacing)
    if row["ours 5 %"] - step <= value <= row["ours 95 %"] + step:
        return f"within one grid point ({step:g} points) of the band"
    spread = row.get("built-in over seeds", "")
    try:
        lo, hi = (float(v) for v in spread.split(" ")[0].split("-"))
    except ValueError:
        lo, hi = float("nan"), float("nan")
    if lo <= value <= hi:
        return "inside the built-in world's range over five seeds"
    found = matching(row, PROBES if probes is None else probes, grid_step(PROBE_SPACING))
    if found:
        p = found[0]
        keeps = p.get("keeps")
        also = f"; {keeps[0]} of its {keeps[2]} thesis numbers inside, {keeps[1]} by default" if keeps else ""
        where = "inside the band" if p["inside"] else "within one grid point of the band"
        return (
            f"{where} with {p['cause']} (gap probe {p['probe']}: {p['lo']:g}-{p['hi']:g} over "
            f"{p['members']} members{also}; causes_probe --gaps)"
        )
    rare = tail_cause(row, TAILS if tails is None else tails)
    if rare:
        return rare
    return "unexplained: thesis " + ("above" if value > row["ours 95 %"] else "below") + " our band"


def cause_counts(rows: list[dict]) -> Counter:
    """How many thesis numbers each cause covers (the general cause, before its parenthesis)."""
    return Counter(r["gap cause"].split(" (")[0] for r in rows if r.get("gap cause"))


def gaps_text(rows: list[dict]) -> str:
    """One sentence: how many thesis numbers are outside the band, and how many each cause explains."""
    counts = cause_counts(rows)
    outside = sum(counts.values())
    unexplained = sum(v for k, v in counts.items() if k.startswith("unexplained"))
    parts = ", ".join(f"{v} {k}" for k, v in counts.most_common())
    return (
        f"{outside} of {len(rows)} thesis numbers lie outside our band: {parts or 'none'}. "
        f"{outside - unexplained} have a named cause, {unexplained} none yet."
    )
