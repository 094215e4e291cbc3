"""docs/model.md §8's table of defaults states the defaults the code has."""

from __future__ import annotations

from pathlib import Path

from delvjax.core.rollouts.rules import DEFAULT_FIRST_MOVE

MODEL = Path(__file__).resolve().parents[1] / "docs" / "model.md"


def test_model_md_section_8_gives_the_default_first_move():
    """Issue 52: §8 still gave `first_move="homing"`, the earlier default, after §5's switch to "release"."""
    section = MODEL.read_text().split("## 8. Defaults")[1].split("\n## ")[0]
    row = next(line for line in section.splitlines() if line.startswith("| `delvjax/core/rollouts/rules.py`"))
    assert f'rules `first_move="{DEFAULT_FIRST_MOVE}"`' in row, row
