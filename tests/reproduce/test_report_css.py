"""The report's wide tables in a real browser (headless Chromium, skipped where there is none): a table of
13 columns headed like the catchment tables ("default failures (timeout/landmark/arena)") fits the
page, and a table that cannot fit keeps its first column in view while it scrolls (issue 53 point 4)."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest

from delvjax.reproduce._report import CSS

CHROMIUM = next((p for p in map(shutil.which, ("chromium", "chromium-browser", "google-chrome")) if p), None)
PROBE = """<script>window.addEventListener('load',()=>{let out=[];document.querySelectorAll('table').forEach(t=>{
let c=t.querySelector('tr td');out.push(t.scrollWidth+'/'+t.clientWidth+'/'+getComputedStyle(c).position)});
let p=document.createElement('pre');p.id='OUT';p.textContent=out.join(' ');document.body.appendChild(p)});</script>"""


def _table(header: list[str], row: list[str]) -> str:
    cells = "".join(f"<td>{v}</td>" for v in row)
    return "<table><tr>" + "".join(f"<th>{h}</th>" for h in header) + f"</tr><tr>{cells}</tr></table>"


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium here")
def test_catchment_tables_fit_the_page_and_wider_ones_keep_their_first_column(tmp_path):
    rules = [
        h for r in ("default", "homing", "physical") for h in (f"ours {r} %", f"{r} failures (timeout/landmark/arena)")
    ]
    header = ["env", "thesis with compass %", "thesis without compass % (Fig 4.5)", *rules]
    header += ["mean error ° (compass)", "mean error ° (no compass)", "e&gt;45 %", "no compass &gt; compass + 45°"]
    fits = _table(
        header, ["env1", "92.01", "98.52", "100.00", "0/0/0", "100.00", "0/0/0", "90.04", "0/125/0"] + ["7.89"] * 4
    )
    wide = _table([f"2° bearing noise: column {i}" for i in range(30)], ["100.0-100.0 (5 seeds)"] * 30)
    page = tmp_path / "r.html"
    page.write_text(f"<html><head><style>{CSS}</style></head><body>{fits}{wide}{PROBE}</body></html>")
    dom = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--window-size=1280,900"]
        + ["--virtual-time-budget=3000", "--dump-dom", page.as_uri()],
        capture_output=True,
        text=True,
        timeout=120,
    ).stdout
    found = re.search(r'<pre id="OUT">(.*?)</pre>', dom)
    if found is None:
        pytest.skip("Chromium ran no script here")
    (first, wide_one) = [tuple(t.split("/")) for t in found.group(1).split()]
    assert int(first[0]) <= int(first[1]), first  # the 14 columns fit (they were 1490 px of 1200)
    assert int(wide_one[0]) > int(wide_one[1]) and wide_one[2] == "sticky", wide_one  # scrolls, labels stay
