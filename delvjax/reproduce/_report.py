"""The reproduction report: `report.md` and a self-contained `report.html` (images embedded).

Built only from the studies' `study.json` records (never recomputing a result): the run's
settings and versions, the claims table with computed verdicts (`delvjax.studies.claims`), then per
study its figures, its tables (ours beside the thesis's numbers), notes and timing.
"""

from __future__ import annotations

import base64
import math
import re
from dataclasses import asdict
from pathlib import Path
from typing import Any

from ..core.rollouts import DEFAULT_RULES, PHYSICAL_RULES
from ..outputs._files import atomic_path

VERDICT_MARK = {  # words, coloured by the CSS below (no emoji: they need a font that may be missing)
    v: f'<span class="verdict {c}">{w}</span>'
    for v, c, w in [
        ("holds", "holds", "holds"),
        ("partly", "partly", "partly"),
        ("fails", "fails", "fails"),
        ("cannot tell", "cannot", "cannot tell"),
        ("n/a", "na", "not run"),
    ]
}
CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;max-width:1200px;margin:2em auto;
padding:0 1em;color:#222;line-height:1.45}
table{border-collapse:collapse;margin:.8em 0;font-size:.8em;display:block;max-width:100%;overflow-x:auto}
th,td{border:1px solid #ccc;padding:.25em .4em;vertical-align:top}
th{background:#f3f3f3;overflow-wrap:anywhere;hyphens:auto;min-width:3.2em}
td{background:#fff}
tr:nth-child(even) td{background:#fafafa}
th:first-child,td:first-child{position:sticky;left:0;z-index:1;box-shadow:1px 0 0 #ccc}
img{max-width:100%;border:1px solid #eee}
code{background:#f4f4f4;padding:0 .2em}
h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:2em}
.verdict{font-weight:600;padding:0 .35em;border-radius:.25em;white-space:nowrap}
.verdict.holds{color:#fff;background:#2e7d32}.verdict.partly{color:#222;background:#f9c74f}
.verdict.fails{color:#fff;background:#c62828}.verdict.cannot{color:#222;background:#d0d0d0}
.verdict.na{color:#555;background:#f0f0f0}
"""


def fmt(v: Any) -> str:
    """A table cell: numbers of magnitude >= 1 to 2 decimals (the thesis's style), smaller ones to 3
    significant figures (0.0114, not 0.01), None/NaN as a dash, text with pipes escaped."""
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return "–" if math.isnan(v) else f"{v:.2f}" if abs(v) >= 1 or v == 0 else f"{v:.3g}"
    if isinstance(v, (list, tuple)):
        return " / ".join(fmt(x) for x in v)
    return str(v).replace("|", "\\|").replace("\n", " ")


def md_table(columns: list[str], rows: list[dict]) -> str:
    lines = ["| " + " | ".join(fmt(c) for c in columns) + " |", "|" + "---|" * len(columns)]  # headers escaped too
    lines += ["| " + " | ".join(fmt(r.get(c)) for c in columns) + " |" for r in rows]
    return "\n".join(lines)


def claims_section(claims: list[dict]) -> str:
    counts = {v: sum(c["verdict"] == v for c in claims) for v in VERDICT_MARK}
    head = (
        f"**{counts['holds']} hold, {counts['partly']} partly, {counts['fails']} fail"
        + (f", {counts['cannot tell']} cannot tell" if counts["cannot tell"] else "")
        + (f", {counts['n/a']} not run" if counts["n/a"] else "")
        + f"** of {len(claims)} claims. "
        "Each verdict is computed from this run's numbers (`studies/claims/__init__.py`); the thesis's "
        "words are quoted with their section. *Cannot tell*: the numbers compared are at the ceiling "
        "(all >= 99 %) or no method loses anything, so they cannot show the claim either way; each "
        "*why* ends with the check's rule and its tolerance; *smallest sample* is the fewest observations "
        "behind any number the check read (an error-curve bin's points, the trials per release distance "
        "or the grid's cells): a verdict on a handful of points is a preview."
    )
    rows = [
        {
            "#": i + 1,
            "claim (thesis)": f"{c['section']}: “{c['quote']}”",
            "what must hold": c["statement"],
            "ours": c["ours"],
            "verdict": VERDICT_MARK[c["verdict"]],
            "smallest sample": c.get("sample", ""),
            "over worlds": c.get("over_worlds", ""),
            "why": c["why"],
        }
        for i, c in enumerate(claims)
    ]
    columns = ["#", "claim (thesis)", "what must hold", "ours", "verdict", "smallest sample", "why"]
    if any(c.get("over_worlds") for c in claims):  # the ensemble study ran (studies/runs/ensembles.py)
        columns.insert(6, "over worlds")
        head += (
            " *Over worlds*: the share of the world ensembles' members (docs/model.md §6.1) in which the same "
            "check holds, with its 95 % Wilson interval: holds in at least 80 %; fails where it holds or partly "
            "holds in at most 20 %; partly where it holds or partly holds in at least 80 %; else it depends on the "
            "world (the `ensembles` study's table names the world property that best separates the members); the "
            "verdict beside it is the built-in world's alone."
        )
    return head + "\n\n" + md_table(columns, rows)


def study_section(rec) -> str:
    parts = [
        f"## {rec.title}",
        f"*Study `{rec.name}`: {rec.seconds:.1f} s wall, of which {rec.compile_seconds:.1f} s compilation "
        f"(0 when the compiled programs came from the cache).*",
    ]
    for t in rec.tables:
        parts.append(f"### {t['title']}" + (f" ({t['source']})" if t["source"] else ""))
        parts.append(md_table(t["columns"], t["rows"]))
        if t["note"]:
            parts.append(f"*{t['note']}*")
        parts.append(f"Data: [`{rec.name}/{t['file']}`]({rec.name}/{t['file']})")
    for f in rec.figures:
        others = [n for n in rec.files if n != f["file"] and Path(n).with_suffix(".png") == Path(f["file"])]
        also = (
            " Also as " + ", ".join(f"[{Path(n).suffix[1:].upper()}]({rec.name}/{n})" for n in others) + "."
            if others
            else ""
        )
        parts.append(f"![{fmt(f['caption'])}]({rec.name}/{f['file']})\n\n*{f['caption']}*{also}")
    return "\n\n".join(parts)


def config_section(config, versions: dict, records: dict, wall_seconds: float, ran: list[str]) -> str:
    rows = [{"setting": k, "value": v} for k, v in asdict(config).items()]
    rows += [
        {
            "setting": "rollout rules (default, docs/model.md §5)",
            "value": ", ".join(f"{k}={v}" for k, v in DEFAULT_RULES.items()),
        },
        {
            "setting": "rollout rules (physical, beside the default)",
            "value": ", ".join(f"{k}={v}" for k, v in PHYSICAL_RULES.items()),
        },
        {"setting": "success", "value": "within 50 cm of home within 50 moves of d = 50 cm"},
    ]
    rows += [{"setting": f"version of {k}", "value": v} for k, v in versions.items()]
    timing = [
        {
            "study": n,
            "wall s": r.seconds,
            "compile s": r.compile_seconds,
            "this run": "ran" if n in ran else "unchanged (skipped)",
        }
        for n, r in records.items()
    ]
    total = sum(r.seconds for r in records.values())
    parts = [
        md_table(["setting", "value"], rows),
        f"This invocation took {wall_seconds:.1f} s; the studies' own recorded wall times add up to {total:.1f} s "
        "(studies run side by side, `--workers`).",
        md_table(["study", "wall s", "compile s", "this run"], timing),
    ]
    from ..studies import FULL_RUN_ONLY  # the studies: loaded only when a report is written (they import the API)

    missing = [n for n in FULL_RUN_ONLY if n not in records]
    if config.quick and missing:
        parts.append(
            "**A preview (`--quick`)**: a 10 x 10 grid, and these studies are left to a full run (or "
            f"`--only`): {', '.join(f'`{n}`' for n in missing)}; claims that read them say *not run*."
        )
    return "\n\n".join(parts)


def choices_section(numbers: dict) -> str:
    """What we chose where the thesis is silent, each with the number it changes (`delvjax.studies.thesis.choices`)."""
    from ..studies.thesis import choices  # the studies: loaded only when a report is written (they import the API)

    return (
        "Where the thesis is silent or ambiguous we had to choose; each choice below with the number it "
        "changes in this run (or, where no study recomputes it, where it was measured). docs/model.md has the "
        "reasons.\n\n" + md_table(["choice", "ours", "alternative", "what it changes"], choices.rows(numbers))
    )


def thesis_notes_section() -> str:
    from ..studies import thesis  # the studies: loaded only when a report is written (they import the API)

    rows = [
        {"where": v.get("section", ""), "what": v.get("text", v.get("description", ""))} for v in thesis.NOTES.values()
    ]
    return md_table(["where", "what"], rows)


QUICK_BANNER = (
    "> **A quick preview (`--quick`).** The maps and catchments come from a coarse 10 x 10 grid (spacing "
    "100 cm) and fewer trials, so some error-curve bins hold one point and their intervals are wide; the "
    "verdicts below are a preview, not the reproduction. Run `delvjax reproduce` without `--quick` for them."
)


def ensemble_section(records: dict, flat: dict) -> list[str]:
    """The world ensembles in a few lines (`studies/runs/ensembles.py`): sizes, thesis numbers inside our band,
    and what the members' coarser grid moves on the built-in worlds, then the other ensemble studies' lines
    (`ensemble_more`); [] when none of them ran."""
    rec = records.get("ensembles")
    if rec is None or "ensemble:members" not in rec.numbers:
        more = ensemble_more(records, flat)
        return ["### Over the worlds the thesis's words allow", *more] if more else []
    from ..studies.runs._ensemble_gaps import gaps_text  # the studies: loaded only when a report is written
    from ..studies.runs._ensemble_stats import grid_check_text  # the studies: loaded only when a report is written

    rows = next((t["rows"] for t in rec.tables if t["id"] == "thesis_numbers_over_worlds"), [])
    inside, total = rec.numbers.get("ensemble:thesis_inside_band", [0, 0])
    text = (
        f"**World ensembles** (study `ensembles`, docs/model.md §6.1): {rec.numbers['ensemble:members']} worlds per "
        f"thesis world, grid spacing {rec.numbers['ensemble:spacing']:g} cm. {inside} of {total} thesis numbers lie "
        "inside our 5-95 % band over the worlds; the claims' *over worlds* column above and the study's tables give "
        "each number's percentile and each claim's share. " + grid_check_text(rows, flat)
    )
    if any("gap cause" in r for r in rows):  # why the others lie outside (studies/runs/_ensemble_gaps.py)
        text += " " + gaps_text(rows)
    return ["### Over the worlds the thesis's words allow", text, *ensemble_more(records, flat)]


def ensemble_more(records: dict, flat: dict) -> list[str]:
    """The other ensemble studies in a few lines each: how many claims they judge over the worlds, the settings the
    thesis's numbers imply (`ensemble_settings`), and the claims whose verdict changes when the families' ranges
    are narrowed or widened by a third (`ensemble_ranges`, SPEC §8)."""
    from ..studies.runs.ensemble_ranges import verdict_change_lines  # the studies: loaded only for a report

    parts = []
    covered = sum(k.startswith("ensemble:claim:") for k in flat)
    judges = [n for n, r in records.items() if any(k.startswith("ensemble:claim:") for k in getattr(r, "numbers", {}))]
    if covered:
        parts.append(
            f"**Claims over the worlds**: {covered} of the thesis's claims are judged over the ensembles' members "
            f"(the claims table's *over worlds* column; studies {', '.join(f'`{n}`' for n in judges)}); "
            "the others say *not covered*."
        )
    rec = records.get("ensemble_settings")
    said = next((t.get("note", "") for t in (rec.tables if rec else []) if t["id"] == "settings_identified"), "")
    if said:  # the table's note is the study's one sentence on what the thesis's numbers identify
        best = flat.get("ensemble_settings:best") or []
        design = next((t["rows"] for t in rec.tables if t["id"] == "settings_design"), [])  # from the best
        names = ("bearing noise (°)", "home radius (cm)", "odometry noise", "rules")
        values = ", ".join(f"{n} {design[0][n]}" for n in names if design and n in design[0])
        score = f" Best combination ({values}): {best[1]:.2f} [{best[2]:.2f}-{best[3]:.2f}]" if len(best) == 4 else ""
        default = flat.get("ensemble_settings:score:default")
        parts.append(
            "**The unstated settings** (study `ensemble_settings`, mean CRPS of the thesis's numbers over the members, "
            f"points): {said}{score}"
            + (f"; every default {default:.2f}." if isinstance(default, (int, float)) else ".")
        )
    if any(k.startswith("ensemble_ranges:") for k in flat):
        lines = verdict_change_lines(flat)
        parts.append(
            "**Ranges narrowed or widened by a third** (study `ensemble_ranges`, SPEC §8): "
            + (" ".join(lines) if lines else "no claim's verdict changes.")
        )
    return parts


def build_markdown(records: dict, config, versions: dict, wall_seconds: float, ran: list[str]) -> str:
    from ..studies.claims import evaluate  # the studies: loaded only when a report is written (they import the API)

    claims = evaluate({n: r.numbers for n, r in records.items()}, asdict(config))
    flat = {k: v for r in records.values() for k, v in r.numbers.items()}
    parts = [
        "# delvjax: reproduction of the thesis's simulation experiments",
        "The thesis is *Distance-Estimated Landmark Vector Model for Vision-Based Homing Navigation* "
        "(chapters 4-5). It gives no landmark coordinates, grid spacing or home radius, so the claims "
        "to check are the trends (who beats whom, how fast each degrades), not the digits. "
        "Our environments, frames and every decision where the thesis is ambiguous: `docs/model.md`.",
        *([QUICK_BANNER] if getattr(config, "quick", False) else []),
        "## Run settings",
        config_section(config, versions, records, wall_seconds, ran),
        "## Claims of the thesis",
        claims_section(claims),
        *ensemble_section(records, flat),
        "## What we chose",
        choices_section(flat),
    ]
    parts += [study_section(r) for r in records.values()]
    parts += ["## Inconsistencies within the thesis", thesis_notes_section()]
    return "\n\n".join(parts) + "\n"


def embed_images(html: str, root: Path) -> str:
    """Replace <img src="relative.png"> by data URIs so the page stands alone."""

    def repl(m: re.Match) -> str:
        path = root / m.group(2)
        if not path.is_file():
            return m.group(0)
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        return f"{m.group(1)}data:image/png;base64,{data}{m.group(3)}"

    return re.sub(r'(<img[^>]*src=")([^"]+\.png)(")', repl, html)


def write_report(
    out: Path, records: dict, config, versions: dict, wall_seconds: float = 0.0, ran: list[str] | None = None
) -> Path:
    """Write out/report.md and out/report.html; returns the HTML path."""
    import markdown  # markdown: loaded only when the HTML report is written

    text = build_markdown(records, config, versions, wall_seconds, ran or [])
    with atomic_path(out / "report.md") as tmp:
        tmp.write_text(text)
    title, rest = text.split("\n", 1)  # the HTML page gets a table of contents with an anchor per section
    body = markdown.markdown(title + "\n\n**Contents**\n\n[TOC]\n" + rest, extensions=["tables", "toc"])
    page = (
        f"<!doctype html><html><head><meta charset='utf-8'><title>delvjax reproduction report</title>"
        f"<style>{CSS}</style></head><body>{embed_images(body, out)}</body></html>\n"
    )
    html = out / "report.html"
    with atomic_path(html) as tmp:
        tmp.write_text(page)
    return html
