"""The report in a real browser (headless Chromium through Playwright; skipped where neither can be
found, `tests.cases.browser`): every image loads, every link to an anchor resolves, no markdown is
left as raw text, and the page does not scroll sideways at 1280 px."""

from __future__ import annotations

import pytest

from tests.cases.browser import browser, report_defects


@pytest.fixture(scope="module")
def app():
    with browser() as found:
        if found is None:
            pytest.skip("no Playwright or no Chromium here (pip install playwright; apt-get install chromium)")
        yield found


def test_the_checks_find_each_defect_drawn_on_purpose(app, tmp_path):
    page = tmp_path / "bad.html"
    page.write_text(
        "<html><body><p>| a | b |\n|---|---|</p><img src='missing.png' alt='lost'>"
        "<a href='#nowhere'>x</a><div style='width:3000px'>wide</div></body></html>"
    )
    found = report_defects(app, page)
    assert found["broken"] == ["lost"] and found["dangling"] == ["#nowhere"]
    assert found["raw"] == ["| a | b |", "|---|---|"] and found["width"] > found["viewport"]


def test_the_report_renders_without_a_defect(app, run):
    out, _, _ = run
    found = report_defects(app, out / "report.html", screenshot=out.parent / "report-top.png")
    assert found["images"] >= 40 and found["tables"] >= 30 and found["links"] >= 40, found  # a real report
    assert found["broken"] == [] and found["dangling"] == [] and found["raw"] == [], found
    assert found["width"] <= found["viewport"], found
