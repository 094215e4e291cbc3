"""`vector-map --images` and `catchment --images` (docs/images.md §6-7): options that do not apply are
refused, rules and options are checked before any work, empty or all-invalid maps warn, nearest-snapshot
rollouts repeat with their seed, and odd databases (one image, a home without a neighbour)."""

from __future__ import annotations

import json
import math

import pytest

from delvjax.cli._main import main
from tests.cases.images_io import at, entries, error_line, no_leftovers, read_csv, summary_numbers, write_plain

# --- vector-map / catchment --images options ---------------------------------------------------------


@pytest.mark.parametrize(
    "command, flags, field",
    [
        ("vector-map", ["--bearing-noise-deg", "2"], "--bearing-noise-deg"),
        ("vector-map", ["--hide", "0"], "--hide"),
        ("vector-map", ["--heading-deg", "90"], "--heading-deg"),
        ("vector-map", ["--d", "10"], "--d"),
        ("vector-map", ["--turn-noise-deg", "3"], "--turn-noise-deg"),
        ("vector-map", ["robot"], "env"),
        ("catchment", ["--lanes", "8"], "--lanes"),
        ("catchment", ["--first-move", "homing"], "--first-move"),
        ("catchment", ["--step-noise", "0.1"], "--step-noise"),
        ("catchment", ["env1"], "env"),
    ],
)
def test_options_that_do_not_apply_to_images_are_refused(small_db, tmp_path, capsys, command, flags, field):
    out = tmp_path / "m.csv"
    argv = [command, *flags, "--images", str(small_db), "--out", str(out)]
    if flags[0] in ("robot", "env1"):  # the positional first
        argv = [command, flags[0], "--images", str(small_db), "--out", str(out)]
    assert main(argv) == 2
    line = error_line(capsys)
    assert line.startswith((f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:")), line
    assert not out.exists() and not list(tmp_path.iterdir())


@pytest.mark.parametrize("command", ["vector-map", "catchment"])
def test_neither_an_environment_nor_images_is_an_error(tmp_path, capsys, command):
    out = tmp_path / "m.csv"
    assert main([command, "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: env:") and "--images" in line, line
    assert not out.exists()


def test_catchment_images_refuses_an_unknown_collision_rule(small_db, tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["catchment", "--images", str(small_db), "--collisions", "maybe", "--summary", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --collisions:")
    assert not out.exists()


@pytest.mark.parametrize("flags", [["--method", "magic"], ["--levels", "0"], ["--chunk", "0"]])
def test_vector_map_images_checks_options_before_announcing_work(small_db, tmp_path, capsys, flags):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "--images", str(small_db), *flags, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert not out.exists()
    assert len(err) == 1 and err[0].startswith("delvjax: error: "), err


def test_a_database_map_with_every_point_invalid_warns(small_db, tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "--images", str(small_db), "--hue-deg", "180", "--out", str(out)]) == 0  # no red
    assert all(r["valid"] == "0" for r in read_csv(out))
    warnings = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("delvjax: warning:")]
    assert len(warnings) == 1 and "invalid" in warnings[0]


def test_catchment_on_a_database(small_db, tmp_path, capsys):
    res = {}
    for rule in ("ignore", "fail"):
        out, summary = tmp_path / f"{rule}.csv", tmp_path / f"{rule}.json"
        assert (
            main(
                [
                    "catchment",
                    "--images",
                    str(small_db),
                    "--method",
                    "delv",
                    "--collisions",
                    rule,
                    "--out",
                    str(out),
                    "--summary",
                    str(summary),
                ]
            )
            == 0
        )
        res[rule] = json.loads(summary.read_text()), read_csv(out)
    capsys.readouterr()
    for rule, (s, rows) in res.items():
        assert 0 <= s["catchment_pct"] <= 100 and s["collisions"] == rule
        assert s["releases"] == len(rows) == 71 - 5  # every image farther than the spacing from home
        assert s["home_radius_cm"] == 20 and s["step_cm"] == 20
        shares = [s[f"{k}_pct"] for k in ("catchment", "timeout", "landmark", "arena", "undefined")]
        assert sum(shares) == pytest.approx(100)
        assert {r["outcome"] for r in rows} <= {"success", "timeout", "landmark", "arena", "undefined"}
        assert s["catchment_pct"] == pytest.approx(100 * sum(r["outcome"] == "success" for r in rows) / len(rows))
        assert all(math.hypot(float(r["x"]) - 90, float(r["y"]) - 90) > 20 for r in rows)
    ignore, fail = res["ignore"][0], res["fail"][0]
    assert ignore["landmark_pct"] == 0 and fail["landmark_pct"] > 0  # obstacles count only with --collisions fail
    assert fail["catchment_pct"] <= ignore["catchment_pct"]
    for a, b in zip(res["ignore"][1], res["fail"][1]):  # a trial that hits a cylinder fails instead
        if b["outcome"] != a["outcome"]:
            assert b["outcome"] == "landmark"


def test_noisy_rollouts_repeat_with_the_same_seed(small_db, tmp_path, capsys):
    def run(seed: int, tag: str):
        out, summary = tmp_path / f"{tag}.csv", tmp_path / f"{tag}.json"
        assert (
            main(
                [
                    "catchment",
                    "--images",
                    str(small_db),
                    "--method",
                    "alv",
                    "--seed",
                    str(seed),
                    "--motion-heading-noise-deg",
                    "40",
                    "--motion-step-noise",
                    "0.3",
                    "--out",
                    str(out),
                    "--summary",
                    str(summary),
                ]
            )
            == 0
        )
        return out.read_bytes(), summary_numbers(summary)

    a, b, c = run(5, "a"), run(5, "b"), run(6, "c")
    capsys.readouterr()
    assert a == b
    assert c[0] != a[0]  # the noise is drawn from the seed


# --- edge databases ----------------------------------------------------------------------------------


def test_a_database_of_one_image(small_db, tmp_path, capsys):
    home = at(entries(small_db), 900, 900)
    one = write_plain(tmp_path / "one", small_db, [home], heading=False)
    out = tmp_path / "imported"
    assert main(["images", "import", str(one), "--out", str(out)]) == 2
    line = error_line(capsys)
    assert "one image" in line and "spacing" in line and str(one) in line, line
    no_leftovers(out)
    assert main(["vector-map", "--images", str(one), "--summary", str(tmp_path / "s.json")]) == 2
    assert "spacing" in error_line(capsys)
    assert not (tmp_path / "s.json").exists()
    # with a spacing, the lone image is home and has no neighbour for the home record's unit move
    assert main(["images", "import", str(one), "--out", str(out), "--spacing", "20"]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --home:") and "unit move" in line and "home" in line, line
    no_leftovers(out)


def test_a_home_without_an_axis_neighbour_does_not_pass_silently(small_db, tmp_path, capsys):
    """docs/images.md §6: the home record is the move from home to its first axis neighbour. Here home
    has none; a home record of a zero-length move (home -> home) must not give a valid-looking map: an
    error naming home, a warning naming home, or every point invalid. (The four neighbours are moved
    7 cm off the grid rather than removed: the database keeps its shape and its compiled programs.)"""
    gone = {(1100, 900), (700, 900), (900, 1100), (900, 700)}
    rows = [dict(r) for r in entries(small_db)]
    for r in rows:
        if (round(float(r["X [mm]"])), round(float(r["Y [mm]"]))) in gone:
            r["X [mm]"], r["Y [mm]"] = str(float(r["X [mm]"]) + 70), str(float(r["Y [mm]"]) + 70)
    iso = write_plain(tmp_path / "iso", small_db, rows)
    out = tmp_path / "m.csv"
    rc = main(
        [
            "vector-map",
            "--images",
            str(iso),
            "--method",
            "delv",
            "--home",
            "90",
            "90",
            "--spacing",
            "20",
            "--out",
            str(out),
        ]
    )
    err = capsys.readouterr().err
    if rc == 2:  # refused, naming home
        assert "delvjax: error: --home" in err and not out.exists(), err
        return
    assert rc == 0
    rows = read_csv(out)
    warned = any(ln.startswith("delvjax: warning:") and "home" in ln for ln in err.splitlines())
    assert warned or all(r["valid"] == "0" for r in rows), err
