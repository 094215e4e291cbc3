"""Shared cases of the reproduction tests: the tiny run config and readers of a results folder."""

from __future__ import annotations

import json
import re
from pathlib import Path

import delvjax.studies as studies
from delvjax.reproduce import _run as reproduce
from delvjax.studies.runs._common import LABEL

TINY = reproduce.RunConfig(spacing=200.0, trials=10)
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
METHOD_OF_LABEL = {v: k for k, v in LABEL.items()}
VERDICTS = {"holds", "partly", "fails", "cannot tell", "n/a"}
# Numbers documented as NaN (JSON null) when their region is empty: e > 45 % inside / outside the
# landmarks' convex hull (delvjax.studies.runs._common.map_numbers) when no grid point lies there.
MAY_BE_NAN = re.compile(r"^map:[^:]+:delv:gt45_(inside|outside)_hull_pct$")


def read_record(out: Path, name: str) -> dict:
    return json.loads((out / name / reproduce.STUDY_FILE).read_text())


def numbers_by_study(out: Path) -> dict[str, dict]:
    return {name: read_record(out, name)["numbers"] for name in studies.STUDIES}


def dot_files(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob(".*"))
