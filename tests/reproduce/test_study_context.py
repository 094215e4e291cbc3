"""A study's context: its progress bar never counts past its total (issue 53 point 4)."""

from __future__ import annotations

import os

from tqdm import tqdm

from delvjax.reproduce._study import Settings, StudyContext, StudyRecord
from delvjax.studies.runs import _common, comparators, image_matching


def test_a_study_taking_more_steps_than_it_declares_never_shows_more_than_its_total(tmp_path):
    with open(os.devnull, "w") as sink, tqdm(total=2, file=sink) as bar:
        ctx = StudyContext(tmp_path, StudyRecord(name="s", title="t"), Settings(), bar)
        for i in range(3):
            ctx.step(f"step {i}")
            assert bar.n <= bar.total
        assert ctx.steps == bar.n == bar.total == 3


def test_image_matching_and_comparators_declare_the_steps_they_take():
    """image_matching took 14 steps (11 in the issue's version) and declared 8; comparators 12 of 10:
    per method and rule set one catchment and one success-rate step."""
    rules = len(_common.RULES)
    assert image_matching.STEPS == 2 * len(image_matching.METHODS) * rules + 2 == 14
    assert comparators.STEPS == len(comparators.ENVS) + len(comparators.METHODS) * rules == 12
