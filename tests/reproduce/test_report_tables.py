"""The report's tables (docs/reproduce.md): every cell escaped, headers included, and small numbers kept
to three significant figures instead of rounding to 0.00."""

from __future__ import annotations

import markdown

from delvjax.reproduce._report import fmt, md_table


def test_a_pipe_in_a_header_or_cell_does_not_break_the_table():
    text = md_table(["heading |error| deg", "n"], [{"heading |error| deg": "a|b", "n": 3}])
    html = markdown.markdown(text, extensions=["tables"])
    assert html.count("<th>") == 2 and html.count("<td>") == 2 and "|error|" in html


def test_numbers_keep_their_significant_figures():
    assert [fmt(v) for v in (0.0114, 0.000123, 0.5, 0.0, 49.114, 1234.567, float("nan"))] == [
        "0.0114",
        "0.000123",
        "0.5",
        "0.00",
        "49.11",
        "1234.57",
        "–",
    ]


def test_verdicts_are_words_coloured_by_css_not_emoji():
    from delvjax.reproduce._report import CSS, VERDICT_MARK

    for verdict, mark in VERDICT_MARK.items():
        assert mark.isascii() and ("not run" if verdict == "n/a" else verdict) in mark
        css_class = mark.split('class="verdict ')[1].split('"')[0]
        assert f".verdict.{css_class}{{" in CSS


def test_a_quick_report_says_its_verdicts_are_a_preview():
    from delvjax.reproduce._report import QUICK_BANNER, build_markdown
    from delvjax.reproduce._study import RunConfig, versions

    assert QUICK_BANNER in build_markdown({}, RunConfig.make(quick=True), versions(), 1.0, [])
    assert QUICK_BANNER not in build_markdown({}, RunConfig.make(quick=False), versions(), 1.0, [])
