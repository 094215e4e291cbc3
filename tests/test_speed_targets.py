"""Issue 54's speed targets in the README are what `benchmarks/speed_targets.py` measured
(benchmarks/speed_targets.json): the generated block is the JSON rendered, each row's value is the one its
script's saved output gives, and a target marked met has its value on the right side of its threshold."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _load(name: str):
    """A benchmark script as a module (registered, so that speed_targets' `from readme_times import` finds it)."""
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
        sys.modules[name] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys.modules[name])
    return sys.modules[name]


_load("readme_times")
speed_targets = _load("speed_targets")
DATA = json.loads(speed_targets.OUT.read_text())


def test_the_readme_block_is_the_json_rendered():
    blocks = speed_targets.BLOCK.findall(speed_targets.README.read_text())
    assert len(blocks) == 1
    assert blocks[0][1] == speed_targets.render(DATA)
    assert not DATA["smoke"]  # the README quotes a full run, never the smoke sizes


def test_each_row_is_what_the_saved_outputs_give():
    """The rows again from the scripts' saved outputs: a reader pointing at the wrong number fails."""
    assert DATA["rows"] == speed_targets.rows(DATA["outputs"], DATA["suite"])
    assert len(DATA["rows"]) == len(speed_targets.TARGETS) + 1  # and the suite's
    assert all(r["value"] is not None for r in DATA["rows"]), "a full run measures every target"


def test_a_target_marked_met_is_on_the_right_side_of_its_threshold():
    for r in DATA["rows"]:
        v, x = r["value"], r["threshold"]
        assert r["met"] == {"<": v < x, "<=": v <= x, ">=": v >= x}[r["op"]], r


@pytest.mark.parametrize(
    "word, op",
    [("grid size", "<"), ("import jax", "<"), ("loop / sweep", ">="), ("every core", ">="), ("L = 32", "<=")],
)
def test_each_target_points_the_way_the_issue_asks(word, op):
    """Smaller is better for compile share, start-up and the L = 32 / L = 8 ratio; larger for loop / sweep
    and 1 core / every core: a flipped sign would mark 0.87x met against >= 1.5x."""
    ops = {t[3] for t in speed_targets.TARGETS if word in t[0]}
    assert ops == {op}
    assert speed_targets.met(">=", 0.87, 1.5) is False and speed_targets.met("<", 635.0, 480.0) is False
    assert speed_targets.met("<=", 20.0, 20.0) is True and speed_targets.met("<", 1.41, 2.0) is True


def test_every_target_has_its_own_name():
    """`ratios` keys each script's values by target: two rows of one name would read one value twice."""
    names = [t[0] for t in speed_targets.TARGETS]
    assert len(set(names)) == len(names)


def test_a_stale_block_or_an_unmeasured_row_is_caught():
    changed = {**DATA, "rows": [{**DATA["rows"][0], "value": None, "met": None}, *DATA["rows"][1:]]}
    assert speed_targets.render(changed) != speed_targets.render(DATA)
    assert "not measured" in speed_targets.table(changed)
