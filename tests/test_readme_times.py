"""The README's times of its two commands (first run, cached, the test command, `--help`) are the
numbers `benchmarks/readme_times.py` measured (benchmarks/readme_times.json): each generated sentence
is what the script renders from the JSON, and the section states no other time."""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC = importlib.util.spec_from_file_location("readme_times", ROOT / "benchmarks" / "readme_times.py")
readme_times = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(readme_times)
TIME = re.compile(r"\b\d+(\.\d+)?\s*(s|seconds?|min|minutes?|hours?)\b")


def _section(text: str) -> str:
    return text.split("## Two commands", 1)[1].split("\n## ", 1)[0]


def test_every_generated_sentence_is_the_measured_numbers():
    data = json.loads(readme_times.RESULTS.read_text())
    blocks = dict(readme_times.BLOCK.findall(_section(readme_times.README.read_text())))
    assert sorted(blocks) == ["quick", "tests"]
    for key, text in blocks.items():
        assert text == readme_times.render(key, data), key
    assert {"help", "quick_first", "quick_cached", "tests"} <= set(data["times"])


def test_the_two_commands_state_no_time_the_script_did_not_produce():
    outside = readme_times.BLOCK.sub("", _section(readme_times.README.read_text()))
    assert not TIME.search(outside), TIME.search(outside)


def test_a_stale_sentence_is_caught(tmp_path):
    data = json.loads(readme_times.RESULTS.read_text())
    changed = {**data, "times": {**data["times"], "help": {"seconds": 99.0, "peak_mb": 1}}}
    assert readme_times.render("quick", changed) != readme_times.render("quick", data)
