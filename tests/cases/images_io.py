"""Helpers of the image-database tests (tests/images/test_disk.py, images/test_errors.py, images/test_cli.py):
small renders of the robot world, plain-folder copies, error lines. Their databases are conftest.py fixtures."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import jax
import numpy as np

from delvjax.cli._main import main
from delvjax.images._disk import ENTRIES, POSITIONS

SMALL = ["--cols", "72", "--rows", "12"]
SEED = 7
HEADER = "X [mm], Y [mm], Z [mm], Heading [degrees], Pitch [degrees], Roll [degrees], Filename, Grid X, Grid Y, Grid Z"
CYLINDERS = [(45.0, 135.0, 8.0), (130.0, 150.0, 8.0), (145.0, 55.0, 8.0), (55.0, 42.0, 8.0)]  # docs/images.md §8


# --- helpers ---------------------------------------------------------------------------------------


def render_db(out: Path, *extra: str) -> Path:
    assert main(["images", "render-db", "robot", "--out", str(out), *extra]) == 0
    return out


def writer_argv(command: str, src: Path) -> list[str]:
    """The command line of a command that writes a database, less --out."""
    return ["images", "render-db", "robot", *SMALL] if command == "render-db" else ["images", "import", str(src)]


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    errors = [ln for ln in err if ln.startswith("delvjax: error:")]
    assert len(errors) == 1 and "Traceback" not in "\n".join(err), err  # one line, no traceback
    return errors[0]


def no_leftovers(out: Path) -> None:
    """Nothing at --out and no temporary `.name.*` folder of the writer beside it."""
    assert not out.exists(), sorted(out.iterdir()) if out.is_dir() else out
    assert not list(out.parent.glob(f".{out.name}.*")), list(out.parent.glob(f".{out.name}.*"))


def entries(folder: Path) -> list[dict[str, str]]:
    """The rows of a BoB entries file (BoB writes ", " between fields)."""
    with open(folder / ENTRIES, newline="") as fh:
        return list(csv.DictReader(fh, skipinitialspace=True))


def at(rows: list[dict[str, str]], x_mm: float, y_mm: float) -> dict[str, str]:
    """The entry at (x_mm, y_mm)."""
    return next(r for r in rows if float(r["X [mm]"]) == x_mm and float(r["Y [mm]"]) == y_mm)


def column0_deg(row: dict[str, str]) -> float:
    """The world heading (math, deg) of file column 0 of a BoB entry in BoB's conventions (compass
    bearing of the centre column; columns clockwise; an even width): 270 - heading."""
    return (270.0 - float(row["Heading [degrees]"])) % 360.0


def leaves_equal(a, b) -> None:
    la, lb = jax.tree.leaves(a), jax.tree.leaves(b)
    assert len(la) == len(lb)
    for x, y in zip(la, lb):
        x, y = np.asarray(x), np.asarray(y)
        assert x.shape == y.shape and x.dtype == y.dtype
        np.testing.assert_array_equal(x, y)  # exact; NaN equals NaN


def read_csv(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def by_position(rows: list[dict[str, str]]) -> dict[tuple[float, float], dict[str, str]]:
    out = {(round(float(r["x"]), 3), round(float(r["y"]), 3)): r for r in rows}
    assert len(out) == len(rows)
    return out


def summary_numbers(path: Path) -> dict:
    s = json.loads(path.read_text())
    settings = {k: v for k, v in s.get("command_settings", {}).items() if k != "images"}  # the folder differs
    return {**{k: v for k, v in s.items() if k not in ("images", "seconds")}, "command_settings": settings}


def write_plain(folder: Path, src: Path, rows: list[dict[str, str]], rename=lambda i, f: f, heading=True) -> Path:
    """A plain folder: the images of `rows` (BoB entries of `src`) copied under new names + positions.csv (cm)."""
    folder.mkdir(parents=True)
    with open(folder / POSITIONS, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["filename", "x", "y"] + (["heading_deg"] if heading else []))
        for i, r in enumerate(rows):
            name = rename(i, r["Filename"])
            shutil.copyfile(src / r["Filename"], folder / name)
            w.writerow([name, float(r["X [mm]"]) / 10, float(r["Y [mm]"]) / 10] + ([column0_deg(r)] if heading else []))
    return folder
