"""A rare world of the family: how many of many members reach a thesis number that lies outside our 5-95 % band
(docs/reproduce.md "The gap probe's third round: rare worlds"). The gap probe (`_gap_probe`) asks whether another
reading of the thesis moves the band over a number; this asks whether the family itself holds worlds that give
it. `python -m delvjax.studies.runs.causes_probe --tail FAMILY METHOD` runs one catchment sweep over many members
(k = 0, the ensembles' grid and lanes) and writes TAIL_FILE; `_ensemble_gaps.gap_cause` reads it: a thesis number
that at least MIN_SHARE of the members reach, on the side where it lies, has "a world in the family's outer x %"
as its cause, with the world property that best separates those members from the rest."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from delvjax.envs import FAMILIES, member_layouts, world_properties
from delvjax.sweeps import parse_sweep, run_sweep

TAIL_FILE = Path(__file__).with_name("_gap_tails.json")
QUANTITIES = {"e>45 %": "gt45_pct", "e>90 %": "gt90_pct", "catchment %": "catchment_pct"}
MIN_SHARE = 1.0  # % of the members: at least this many must reach a thesis number for it to be "a rare world"
LANES = 128  # the ensembles' rollout lanes (no number depends on them)


def sweep_text(family: str, method: str, members: int, spacing: float, seed: int) -> str:
    """One catchment sweep of `members` members of `family` (layouts and release headings from `seed`), k = 0."""
    metrics = ", ".join(f'"{m}"' for m in QUANTITIES.values())
    return (
        f'[sweep]\nkind = "catchment"\nmetrics = [{metrics}]\n'
        f'[axes]\nenv = [{{ensemble = "{family}", members = {members}, seed = {seed}}}]\n'
        f'method = ["{method}"]\nocclude = [0]\nspacing = [{spacing}]\nseed = [{seed}]\n'
    )


def measure(family: str, method: str, members: int = 200, spacing: float = 100.0, seed: int = 0) -> dict:
    """Every member's k = 0 numbers and world properties: {"world", "method", "members", "spacing_cm", "seed",
    quantity: [members values], "properties": {name: [members values]}} (one sweep: one compiled program)."""
    ds = run_sweep(parse_sweep(sweep_text(family, method, members, spacing, seed), "tail"), lanes=LANES)
    row: dict = {"world": family, "method": method, "members": members, "spacing_cm": spacing, "seed": seed}
    for quantity, var in QUANTITIES.items():
        row[quantity] = [round(float(v), 4) for v in np.ravel(ds[var].values)]
    props = world_properties(member_layouts(family, members, seed), FAMILIES[family].home)
    row["properties"] = {k: [round(float(x), 3) for x in v] for k, v in props.items()}
    return row


def load_tails(path: Path = TAIL_FILE) -> list[dict]:
    """The committed tail rows (empty when the file is missing)."""
    return json.loads(path.read_text())["rows"] if path.exists() else []


def write_tails(rows: list[dict], path: Path = TAIL_FILE) -> None:
    """Replace the rows of the same world and method in `path`, keep the others."""
    kept = [r for r in load_tails(path) if (r["world"], r["method"]) not in {(n["world"], n["method"]) for n in rows}]
    doc = {"command": "python -m delvjax.studies.runs.causes_probe --tail FAMILY METHOD [--members N]"}
    doc["rows"] = kept + rows
    path.write_text(json.dumps(doc, indent=1) + "\n")


def separating_property(reach: np.ndarray, properties: dict) -> tuple[str, float, tuple[float, float], float]:
    """The world property whose values best separate the members in `reach` from the others (the largest
    |AUC - 0.5|, AUC the chance that a reaching member's value exceeds another's): (name, AUC, the reaching
    members' range, the others' median)."""
    best = ("", 0.5, (float("nan"), float("nan")), float("nan"))
    for name, values in properties.items():
        v = np.asarray(values, float)
        a, b = v[reach], v[~reach]
        if not len(a) or not len(b):
            continue
        auc = float(np.mean(a[:, None] > b[None, :]) + 0.5 * np.mean(a[:, None] == b[None, :]))
        if abs(auc - 0.5) > abs(best[1] - 0.5):
            best = (name, auc, (float(a.min()), float(a.max())), float(np.median(b)))
    return best


def tail_cause(row: dict, tails: list[dict]) -> str:
    """The rare-world cause of a gap row (a `distribution_rows` row outside our band, k = 0), or "" when no tail
    row measured its world and method, or fewer than MIN_SHARE % of the members reach the thesis number."""
    if int(row["k"]) != 0 or row["quantity"] not in QUANTITIES:
        return ""
    for t in tails:
        if t["world"] != row["world"] or t["method"] != row["method"]:
            continue
        values = np.asarray(t[row["quantity"]], float)
        above = row["thesis"] > row["ours 95 %"]
        reach = values >= row["thesis"] - 1e-9 if above else values <= row["thesis"] + 1e-9
        share = 100.0 * float(reach.mean())
        if share < MIN_SHARE:
            return ""
        name, auc, (lo, hi), other = separating_property(reach, t["properties"])
        prop = f"; theirs {name} {lo:.0f}-{hi:.0f}, the others' median {other:.0f} (AUC {auc:.2f})" if name else ""
        return (
            f"a world in the family's outer {share:.1f} % ({int(reach.sum())} of {len(values)} members reach it"
            f"{prop}; causes_probe --tail {t['world']} {t['method']})"
        )
    return ""
