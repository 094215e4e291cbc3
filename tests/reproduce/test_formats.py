"""`delvjax reproduce --format png,pdf,svg`: every figure in every format asked for, linked from the
report; the PNG always (the report shows it); anything else refused before any work."""

from __future__ import annotations

from dataclasses import replace

from delvjax.cli import main
from delvjax.reproduce import _run as reproduce
from tests.cases.reproduce import TINY


def test_every_figure_is_written_in_every_format_asked_for(tmp_path):
    config = replace(TINY, formats=("png", "pdf", "svg"))
    reproduce.reproduce(tmp_path, config=config, progress=False, only="environments", workers=1)
    folder = tmp_path / "environments"
    assert (folder / "environments.png").read_bytes().startswith(b"\x89PNG")
    assert (folder / "environments.pdf").read_bytes().startswith(b"%PDF")
    assert b"<svg" in (folder / "environments.svg").read_bytes()[:2000]
    report = (tmp_path / "report.md").read_text()
    assert "Also as [PDF](environments/environments.pdf), [SVG](environments/environments.svg)." in report


def test_an_unknown_format_is_one_line_before_any_work(tmp_path, capsys):
    out = tmp_path / "results"
    assert main(["reproduce", "--only", "environments", "--format", "png,jpg", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--format" in err[0] and "png, pdf, svg" in err[0]
    assert not out.exists()
