"""The statistics of the `ensembles` study (docs/reproduce.md "Ensembles"): every thesis number's distribution
over the members, which unstated settings the thesis's numbers favour, what the members' coarse grid moves,
and each claim's share of members with the world property that decides it. Plain NumPy on the numbers the
study's sweeps made; no array program here."""

from __future__ import annotations

import math

import numpy as np

from delvjax.envs import world_properties

from .. import thesis
from ..claims import CHECKS, Missing, world_verdict
from ..claims._common import CANNOT_TELL, PARTLY
from ..claims._common import HOLDS as HOLDS_TEXT

SEED_SPREAD = (1, 2, 3, 4)  # extra seeds of the built-in worlds: the spread a seed alone makes
NOISE_DEG = 2.0  # bearing noise (sigma, degrees) of the noisy setting: issue 52 found 2° bring Table 5.1 closest
# the unstated settings the ensembles vary: (key suffix, name); the first is the default of every other study
SETTINGS = (
    ("", "default"),
    (":physical", "physical rules"),
    (f":bearing{NOISE_DEG:g}", f"{NOISE_DEG:g}° bearing noise"),
)
BAND = (5.0, 95.0)  # percentiles of the band


def wilson(k: int, n: int, z: float = 1.96) -> tuple[float, float]:
    """95 % Wilson interval of a share k / n (0..1)."""
    if n == 0:
        return (math.nan, math.nan)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (max(0.0, centre - half), min(1.0, centre + half))


def percentile_of(value: float, sample) -> float:
    """Where `value` falls in `sample` (%): the share below it, ties counted half."""
    v = np.asarray(sample, float)
    return float(100.0 * (np.sum(v < value) + 0.5 * np.sum(v == value)) / len(v))


def thesis_numbers():
    """Every thesis number the ensemble covers: (source, family, method, k, quantity, value), quantity
    "catchment", "gt45" or "gt90" (Figs 4.5, 5.5 and 5.10, Tables 5.1-5.4; the §5.3.1 text repeats Table 5.3's)."""
    rows = []
    for source in ("fig4_5", "fig5_5", "table5_3", "table5_4", "fig5_10"):
        for fam, by_method in thesis.CATCHMENT[source].items():
            for m, values in by_method.items():
                rows += [(source, fam, m, k, "catchment", v) for k, v in enumerate(values)]
    for source, table in thesis.ERROR_POINTS.items():
        for fam, by_method in table.items():
            for m, fields in by_method.items():
                for q, values in fields.items():
                    rows += [(source, fam, m, k, q, v) for k, v in enumerate(values)]
    return rows


SOURCE_LABEL = {"fig4_5": "Fig 4.5", "fig5_5": "Fig 5.5", "table5_3": "Table 5.3", "table5_4": "Table 5.4"}
SOURCE_LABEL.update({"table5_1": "Table 5.1", "table5_2": "Table 5.2", "fig5_10": "Fig 5.10"})


def _sample(worlds: dict[str, dict], labels, key: str, k: int) -> list[float]:
    """The k-th value of `key` in every world of `labels` that has it (NaN left out)."""
    found = [worlds.get(label, {}).get(key) for label in labels]
    return [v[k] for v in found if v is not None and k < len(v) and v[k] is not None and not math.isnan(v[k])]


def distribution_rows(worlds: dict[str, dict], members: int) -> list[dict]:
    """One row per thesis number: our median and band over the members, the thesis's percentile in it, the
    built-in world's value with the range four more seeds give it, and for catchments at k = 0 the band under
    the physical rules (where the ensemble has them)."""
    rows = []
    for source, fam, m, k, q, value in thesis_numbers():
        key = f"occlusion:{fam}:{m}:{q}"
        sample = _sample(worlds, [f"{fam}-m{i}" for i in range(members)], key, k)
        builtin = _sample(worlds, [fam], key, k)
        if not sample or not builtin:
            continue
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
        seeds = builtin + _sample(worlds, [f"{fam}@{s}" for s in SEED_SPREAD], key, k)
        row = {
            "source": SOURCE_LABEL[source],
            "world": fam,
            "method": m,
            "k": k,
            "quantity": {"catchment": "catchment %", "gt45": "e>45 %", "gt90": "e>90 %"}[q],
            "thesis": value,
            "ours median": float(med),
            "ours 5 %": float(lo),
            "ours 95 %": float(hi),
            "thesis percentile": percentile_of(value, sample),
            "inside band": bool(lo <= value <= hi),
            "members": len(sample),
            "at ceiling %": 100.0 * float(np.mean(np.asarray(sample) >= 99.0)) if q == "catchment" else None,
            "built-in world": builtin[0],
            "built-in over seeds": f"{min(seeds):.1f}-{max(seeds):.1f} ({len(seeds)} seeds)",
        }
        for tail, name in SETTINGS[1:]:
            other = _sample(worlds, [f"{fam}-m{i}" for i in range(members)], f"{key}{tail}", k)
            if other:
                o_lo, o_med, o_hi = np.percentile(other, [BAND[0], 50.0, BAND[1]])
                row[f"{name}: median"] = float(o_med)
                row[f"{name}: 5 %"] = float(o_lo)
                row[f"{name}: 95 %"] = float(o_hi)
                row[f"{name}: thesis percentile"] = percentile_of(value, other)
                spread = _sample(worlds, [fam, *(f"{fam}@{s}" for s in SEED_SPREAD)], f"{key}{tail}", k)
                if len(spread) > 1:  # the built-in world under five seeds: what a seed alone moves
                    row[f"{name}: built-in over seeds"] = f"{min(spread):.1f}-{max(spread):.1f} ({len(spread)} seeds)"
        rows.append(row)
    return rows


# --- which unstated settings the thesis's numbers favour ----------------------------------------------

IDENTIFIES = 20.0  # points: a setting is favoured when it puts this many more of the thesis's numbers inside the band


def settings_rows(rows: list[dict]) -> list[dict]:
    """Per unstated setting of SETTINGS beyond the default: on the thesis numbers it was run for, the share
    inside its band and the median distance of their percentiles from 50, beside the default's on the same
    numbers (docs/reproduce.md "Ensembles")."""

    def score(sub: list[dict], name: str | None) -> tuple[float, float]:
        lo = "ours 5 %" if name is None else f"{name}: 5 %"
        hi = "ours 95 %" if name is None else f"{name}: 95 %"
        pct = "thesis percentile" if name is None else f"{name}: thesis percentile"
        inside = 100.0 * float(np.mean([r[lo] <= r["thesis"] <= r[hi] for r in sub]))
        return inside, float(np.median([abs(r[pct] - 50.0) for r in sub]))

    out = []
    for _, name in SETTINGS[1:]:
        for group, catchments in (("catchments", True), ("error point rates", False)):
            sub = [r for r in rows if f"{name}: median" in r and (r["quantity"] == "catchment %") == catchments]
            if not sub:
                continue
            (inside, off), (inside0, off0) = score(sub, name), score(sub, None)
            out.append(
                {
                    "setting": name,
                    "numbers": group,
                    "thesis numbers": len(sub),
                    "inside its band %": inside,
                    "inside the default's band %": inside0,
                    "median |percentile - 50|": off,
                    "default's median |percentile - 50|": off0,
                    "the numbers favour": name
                    if inside >= inside0 + IDENTIFIES and off < off0
                    else "default"
                    if inside0 >= inside + IDENTIFIES and off0 < off
                    else "neither (not identified)",
                }
            )
    return out


def settings_text(rows: list[dict]) -> str:
    """One sentence per setting: favoured, or not identified by the thesis's numbers."""
    parts = []
    for r in settings_rows(rows):
        verdict = r["the numbers favour"]
        what = (
            f"favour {verdict}"
            if not verdict.startswith("neither")
            else f"do not identify whether {r['setting']} or the default was used"
        )
        base = r["inside the default's band %"]
        parts.append(
            f"Of the {r['thesis numbers']} thesis {r['numbers']} run under {r['setting']}, {r['inside its band %']:.0f} % "
            f"lie inside its band against {base:.0f} % under the default: they {what}."
        )
    return " ".join(parts)


# --- what the coarse grid moves ---------------------------------------------------------------------

POINT_RUN = {"env1": "env1", "env2": "env2", "env3": "env3", "ring3": "ring3", "ring5": "ring5", "ring6": "ring6"}


def grid_check_rows(rows: list[dict], flat: dict) -> list[dict]:
    """Per thesis number of `distribution_rows` (the table's rows): the built-in world's value on the ensemble's
    grid beside the point run's (the occlusion study: spacing 25 cm, rings 50 cm), their difference and the
    ensemble's 5-95 % band width: a coarse grid is good enough where the shift is well inside the band."""
    out = []
    for r in rows:
        fam = POINT_RUN.get(r["world"])
        q = {"catchment %": "catchment", "e>45 %": "gt45", "e>90 %": "gt90"}[r["quantity"]]
        fine = flat.get(f"occlusion:{fam}:{r['method']}:{q}") if fam else None
        if not isinstance(fine, list) or r["k"] >= len(fine) or fine[r["k"]] is None:
            continue
        width = r["ours 95 %"] - r["ours 5 %"]
        shift = abs(fine[r["k"]] - r["built-in world"])
        out.append(
            {
                "number": f"{r['source']} {r['world']} {r['method']} k={r['k']} {r['quantity']}",
                "built-in, point run's grid": fine[r["k"]],
                "built-in, ensemble's grid": r["built-in world"],
                "shift": shift,
                "band width": width,
                "shift <= band": bool(shift <= width),
            }
        )
    return out


def grid_check_text(rows: list[dict], flat: dict) -> str:
    """The report's paragraph on the coarse grid (docs/reproduce.md "Ensembles")."""
    check = grid_check_rows(rows, flat)
    if not check:
        return ""
    shifts = np.array([c["shift"] for c in check])
    widths = np.array([c["band width"] for c in check])
    inside = int(sum(c["shift <= band"] for c in check))
    return (
        f"The members run on a coarser grid than the point run. On the built-in worlds, the {len(check)} numbers "
        f"move by a median of {np.median(shifts):.1f} points (largest {shifts.max():.1f}) between the point run's "
        f"grid and the ensemble's, against a median band width of {np.median(widths):.1f}: {inside} of "
        f"{len(check)} shifts are at most their band's width."
    )


# --- claims over the members ------------------------------------------------------------------------


def claim_rows(
    worlds: dict[str, dict], members: int, layouts: dict[str, np.ndarray], ids: set[str] | None = None
) -> list[dict]:
    """Per claim whose check reads only numbers the ensemble makes: the verdict in each member (member i =
    the i-th world of every family), the share that holds with its Wilson interval, the ensemble verdict
    and, where it depends on the world, the deciding property. `ids`: only these claims (a study of the
    ensembles judges the claims it covers; two studies never record the same `ensemble:claim:<id>`)."""
    props = {fam: world_properties(lay) for fam, lay in layouts.items()}
    families = sorted({label.rsplit("-m", 1)[0] for label in worlds if "-m" in label})
    rows = []
    for number, claim in enumerate(thesis.CLAIMS, 1):
        fn = CHECKS.get(claim["id"])
        if fn is None or (ids is not None and claim["id"] not in ids):
            continue
        verdicts, read = [], set()
        for i in range(members):
            flat = {}
            for fam in families:
                flat.update(worlds.get(f"{fam}-m{i}", {}))

            def get(key, flat=flat):
                read.add(key)
                if key not in flat or flat[key] is None:
                    raise Missing(key)
                return flat[key]

            try:
                verdicts.append(fn(get)[1])
            except Missing:
                verdicts = []
                break
            except (TypeError, ValueError, IndexError, ZeroDivisionError):
                verdicts.append("n/a")
        if not verdicts:
            continue
        n = len(verdicts)
        held = np.array([v == HOLDS_TEXT for v in verdicts])
        ceiling = sum(v == CANNOT_TELL for v in verdicts)
        partly = sum(v == PARTLY for v in verdicts)
        p = held.mean()
        lo, hi = wilson(int(held.sum()), n)
        verdict = world_verdict(100.0 * p, 100.0 * ceiling / n, 100.0 * partly / n)
        row = {
            "#": number,
            "id": claim["id"],
            "section": claim["section"],
            "holds %": 100.0 * p,
            "95 % interval": f"{100 * lo:.1f}-{100 * hi:.1f}",
            "members": n,
            "cannot tell %": 100.0 * ceiling / n,
            "partly %": 100.0 * partly / n,
            "verdict over worlds": verdict,
            "decided_by": "",
        }
        if verdict in ("depends on the world", "partly") and 0 < held.sum() < n:  # where it holds, and where not
            read_families = sorted({k.split(":")[1] for k in read if k.split(":")[1] in props})
            best = deciding_property(held, {f: props[f] for f in read_families})
            if best is not None:
                fam, prop, auc, values = best
                row["decided_by"] = f"{fam} {prop} (AUC {auc:.2f})"
                row["decided_by_values"] = {"family": fam, "property": prop, "values": values, "holds": held.tolist()}
        rows.append(row)
    return rows


def auc(values: np.ndarray, labels: np.ndarray) -> float:
    """The probability that a member where the claim holds has a larger value than one where it does not
    (ties half): the Mann-Whitney AUC."""
    pos, neg = values[labels], values[~labels]
    if not len(pos) or not len(neg):
        return 0.5
    diff = pos[:, None] - neg[None, :]
    return float(np.mean((diff > 0) + 0.5 * (diff == 0)))


def deciding_property(held: np.ndarray, props: dict[str, dict[str, np.ndarray]]):
    """(family, property, AUC, values) of the world property that best separates holds from not (|AUC - 0.5|
    largest); None when no family's property is known."""
    best = None
    for fam, table in props.items():
        for prop, values in table.items():
            v = np.asarray(values)[: len(held)]
            a = auc(v, held)
            if best is None or abs(a - 0.5) > abs(best[2] - 0.5):
                best = (fam, prop, a, v.tolist())
    return best
