"""Every script of examples/ runs as a newcomer would run it (`python examples/NAME.py` from a fresh
folder) and writes what its docstring promises."""

from __future__ import annotations

import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
WRITES = {  # what each example's docstring says it writes under examples_out/
    "vector_map.py": ["vector_map.png", "vector_map.csv"],
    "sweep_xarray.py": ["sweep/sweep.nc", "sweep/sweep.csv", "sweep/sweep.toml"],
    "gradient.py": [],
    "image_database.py": ["robot_db/database_entries.csv", "robot_db/database_metadata.yaml", "robot_db.png"],
}


def test_every_example_is_tested():
    assert sorted(p.name for p in EXAMPLES.glob("*.py")) == sorted(WRITES)


@pytest.mark.parametrize("name", sorted(WRITES))
def test_the_example_runs_and_writes_what_it_says(name, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    runpy.run_path(str(EXAMPLES / name), run_name="__main__")
    printed = capsys.readouterr().out
    assert printed.strip(), name
    for file in WRITES[name]:
        assert (tmp_path / "examples_out" / file).stat().st_size > 0, file
    docstring = (EXAMPLES / name).read_text().split('"""')[1]
    assert f"python examples/{name}" in docstring
