"""Rollouts at the edge (docs/model.md §5): the CLI commands and their CSV/JSON files, the rules
recorded in every file, and bad input (exit 2 without output; `InputError` naming the field)."""

from __future__ import annotations

import csv
import json

import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.core.maps import grid_included, grid_points
from delvjax.envs._presets import make_env
from tests.cases.rollouts import ARENA, DEFAULT, FOUR, HOME, PHYSICAL, run


def write_env(path, landmarks):
    """A docs/model.md §7 environment file."""
    path.write_text(
        json.dumps(
            {
                "name": "four",
                "arena": ARENA,
                "home": HOME,
                "landmarks": [{"x": x, "y": y, "r": r} for x, y, r in landmarks.tolist()],
            }
        )
    )
    return str(path)


def read_rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def test_cli_catchment_success_rate_trajectories(tmp_path):
    out = tmp_path / "c.csv"
    assert (
        main(
            [
                "catchment",
                "env1",
                "--method",
                "alv",
                "--spacing",
                "200",
                "--out",
                str(out),
                "--occlude",
                "1",
                "--summary",
                str(tmp_path / "c.json"),
            ]
        )
        == 0
    )
    header = out.read_text().splitlines()[0].split(",")
    assert header[:6] == ["x", "y", "heading_deg", "success", "counted", "steps"] and "hidden" in header
    env = delvjax.load_env("env1")
    n_points = int(np.sum(np.asarray(grid_included(env, jnp.asarray(grid_points(env.arena, 200.0)), 10.0))))
    assert len(out.read_text().splitlines()) == 1 + env.n_landmarks * n_points  # C(N, 1) masks
    assert (
        main(
            [
                "success-rate",
                "ring4",
                "--method",
                "alv,acv",
                "--trials",
                "10",
                "--distances",
                "50",
                "250",
                "450",
                "--seed",
                "2",
                "--out",
                str(tmp_path / "s.csv"),
            ]
        )
        == 0
    )
    rows = read_rows(tmp_path / "s.csv")
    assert len(rows) == 2 * 3 and all(r["first_move"] == "release" and r["collisions"] == "ignore" for r in rows)
    four = write_env(tmp_path / "four.json", FOUR)
    assert (
        main(
            [
                "trajectories",
                four,
                "--method",
                "alv",
                "--start",
                "100",
                "100",
                "--start",
                "800",
                "300",
                "--start",
                "150",
                "850",
                "--start",
                "850",
                "850",
                "--out",
                str(tmp_path / "t.csv"),
                "--plot",
                str(tmp_path / "t.png"),
            ]
        )
        == 0
    )
    assert (tmp_path / "t.png").stat().st_size > 0
    rows = read_rows(tmp_path / "t.csv")
    assert rows and all(r["first_move"] == "release" and r["collisions"] == "ignore" for r in rows)


@pytest.mark.parametrize(
    "flags, rules",
    [([], DEFAULT), (["--first-move", "release", "--collisions", "fail"], PHYSICAL)],
    ids=["default", "physical"],
)
def test_cli_catchment_records_the_rules(tmp_path, flags, rules):
    """The rules are constant CSV columns and a "rules" dict in the summary JSON."""
    out, summary = tmp_path / "c.csv", tmp_path / "c.json"
    assert (
        main(
            [
                "catchment",
                "env1",
                "--method",
                "alv",
                "--spacing",
                "200",
                "--occlude",
                "1",
                "--out",
                str(out),
                "--summary",
                str(summary),
            ]
            + flags
        )
        == 0
    )
    rows = read_rows(out)
    assert rows and {(r["first_move"], r["collisions"]) for r in rows} == {(rules["first_move"], rules["collisions"])}
    if rules["collisions"] == "ignore":
        assert all(r["outcome"] != "landmark" for r in rows)
    data = json.loads(summary.read_text())
    assert data["rules"] == rules
    assert all(row["landmark_count"] == 0 for row in data["per_mask"]) or rules["collisions"] == "fail"


@pytest.mark.parametrize(
    "argv, field",
    [
        (["catchment", "env1", "--occlude", "99"], "occlude"),
        (["catchment", "env1", "--bearing-noise-deg", "-1"], "bearing_noise_deg"),
        (["catchment", "env1", "--max-steps", "0"], "max_steps"),
        (["catchment", "env1", "--first-move", "bogus"], "first_move"),
        (["catchment", "env1", "--collisions", "bounce"], "collisions"),
        (["success-rate", "env1", "--motion-step-noise", "-0.1"], "motion_step_noise"),
        (["success-rate", "env1", "--trials", "0"], "trials"),
        (["success-rate", "env1", "--first-move", "bogus"], "first_move"),
        (["trajectories", "env1", "--start", "1500", "500"], "starts[0]"),
        (["trajectories", "env1", "--home-radius", "0"], "home_radius"),
        (["trajectories", "env1", "--collisions", "bounce"], "collisions"),
    ],
)
def test_bad_input_exits_2_without_output(tmp_path, capsys, argv, field):
    out = tmp_path / "o.csv"
    assert main(argv + ["--out", str(out)]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.startswith("delvjax: error: ") and (field in last or field.replace("_", "-") in last)
    assert not out.exists()


def test_api_bad_input_raises_input_error():
    with pytest.raises(InputError, match="occlude"):
        delvjax.catchment("ring3", occlude=4)
    with pytest.raises(InputError, match="occlude"):
        delvjax.catchment("env1", occlude=1, hidden=[0])
    with pytest.raises(InputError, match="max_steps"):
        delvjax.success_rate("env1", rules=Rules(max_steps=0))
    with pytest.raises(InputError, match="distances"):
        delvjax.success_rate("env1", distances=[])
    with pytest.raises(InputError, match=r"starts\[0\]"):  # inside a landmark
        delvjax.trajectories(make_env(FOUR), starts=[[330.0, 640.0]])


@pytest.mark.parametrize("call", [delvjax.catchment, delvjax.success_rate, delvjax.trajectories])
@pytest.mark.parametrize(
    "field, value", [("first_move", "x"), ("collisions", "x"), ("first_move", "Homing"), ("collisions", None)]
)
def test_bad_rules_raise_input_error_naming_the_field(call, field, value):
    with pytest.raises(InputError, match=field) as info:
        call("env1", rules=Rules(**{field: value}))
    assert info.value.field == field
    with pytest.raises(InputError, match=field) as info, pytest.deprecated_call():  # the old keyword alike
        call("env1", **{field: value})
    assert info.value.field == field


def test_run_trials_checks_the_rules():
    env = make_env(FOUR)
    starts = np.array([[150.0, 150.0]], np.float32)
    with pytest.raises(InputError, match="first_move"):
        run(env, starts, np.zeros(1, np.float32), "alv", first_move="straight")
    with pytest.raises(InputError, match="collisions"):
        run(env, starts, np.zeros(1, np.float32), "alv", collisions="bounce")


def test_numpy_arrays_are_taken_wherever_lists_are():
    """Hidden landmarks, release distances and release points as NumPy arrays (NumPy integers too) give
    the lists' numbers; a bad NumPy index is refused naming it (it once read "0..3, got np.int64(1)")."""
    kw = {"hidden": [0, 2], "distances": [100.0, 300.0]}
    lists = delvjax.success_rate("env1", "alv", trials=4, **kw)
    arrays = delvjax.success_rate("env1", "alv", trials=4, **{k: np.asarray(v) for k, v in kw.items()})
    same(lists, arrays, "outcome")
    same(lists, arrays, "start")
    c = delvjax.catchment("env1", "alv", hidden=np.array([1], np.int32), grid=Grid(spacing=200))
    same(c, delvjax.catchment("env1", "alv", hidden=[1], grid=Grid(spacing=200)), "outcome")
    assert c.hidden == ((1,),)
    v = delvjax.vector_map("env1", "alv", hidden=np.array([1, 3]), grid=Grid(spacing=200))
    same(v, delvjax.vector_map("env1", "alv", hidden=[1, 3], grid=Grid(spacing=200)), "direction")
    t = delvjax.trajectories("env1", "alv", starts=np.array([[300.0, 300.0], [700.0, 250.0]]))
    same(t, delvjax.trajectories("env1", "alv", starts=[[300.0, 300.0], [700.0, 250.0]]), "path")
    with pytest.raises(InputError, match="0..3, got np.int64.4."):
        delvjax.catchment("env1", "alv", hidden=np.array([4]), grid=Grid(spacing=200))


def same(a, b, field: str) -> None:
    """Field `field` of two results equal bit for bit."""
    np.testing.assert_array_equal(np.asarray(getattr(a, field)), np.asarray(getattr(b, field)))


def test_numpy_integers_are_integers(untyped):
    """A loop over np.arange hands NumPy integers to trials, seed, occlude, max_steps and n_starts: they are
    integers (they were refused as "must be an integer, got np.int64(3)"); NumPy's True is no seed."""
    a = delvjax.success_rate("env1", "alv", trials=np.int64(3), distances=[100.0], seed=np.int32(2))
    b = delvjax.success_rate("env1", "alv", trials=3, distances=[100.0], seed=2)
    same(a, b, "outcome")
    same(a, b, "start")
    c = delvjax.catchment(
        "env1", "alv", occlude=np.int64(1), grid=Grid(spacing=200), rules=Rules(max_steps=np.int16(20))
    )
    same(c, delvjax.catchment("env1", "alv", occlude=1, grid=Grid(spacing=200), rules=Rules(max_steps=20)), "outcome")
    assert np.asarray(delvjax.trajectories("env1", "alv", n_starts=np.uint8(2)).steps).shape == (2,)
    for bad in (np.bool_(True), np.int64(-1)):
        with pytest.raises(InputError) as exc:
            delvjax.vector_map("env1", "alv", seed=bad, grid=Grid(spacing=200))
        assert exc.value.field == "seed"
