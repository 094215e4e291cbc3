"""Bad and odd input found by trying the tool as a new user would (issue "hardening"): each case fails
with one line naming the field and exit 2, or works as documented."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core.errors import InputError


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err  # one line, no traceback
    return err[0]


@pytest.mark.parametrize("seed", ["99999999999999999999", "4294967296", "-1"])
def test_a_seed_out_of_range_is_one_line_naming_it(tmp_path, capsys, seed):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", "--seed", seed, "--spacing", "200", "--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --seed:")
    assert not out.exists()


def test_a_negative_seed_of_a_random_layout_is_one_line_naming_it(tmp_path, capsys):
    """optimise-layout --landmarks N draws its layout from --seed before any other check saw it (a traceback once)."""
    out = tmp_path / "o"
    assert main(["optimise-layout", "--landmarks", "4", "--seed", "-3", "--out", str(out)]) == 2
    assert error_line(capsys) == "delvjax: error: --seed: must be an integer in 0..4294967295, got -3"
    assert not out.exists()


def test_seeds_at_the_32_bit_limit_are_distinct_and_valid():
    """PRNGKey keeps 32 bits: 2**32 would silently repeat seed 0, so the largest seed is 2**32 - 1."""
    with pytest.raises(InputError, match="seed"):
        delvjax.vector_map("env1", seed=2**32, bearing_noise_deg=2.0, grid=Grid(spacing=200.0))
    a = delvjax.vector_map("env1", seed=2**32 - 1, bearing_noise_deg=2.0, grid=Grid(spacing=200.0))
    b = delvjax.vector_map("env1", seed=0, bearing_noise_deg=2.0, grid=Grid(spacing=200.0))
    assert not np.array_equal(np.asarray(a.heading), np.asarray(b.heading))


def test_a_huge_heading_is_reduced_in_float64_before_the_core():
    kw = dict(method="delv-compass")
    reduced = math.fmod(1e30, 360.0)
    huge = delvjax.vector_map("env1", grid=Grid(spacing=200.0, heading_deg=1e30), **kw)
    same = delvjax.vector_map("env1", grid=Grid(spacing=200.0, heading_deg=reduced), **kw)
    assert np.array_equal(np.asarray(huge.direction), np.asarray(same.direction), equal_nan=True)
    inc = np.asarray(huge.included)
    assert float(np.asarray(huge.error_deg)[inc].mean()) < 30.0  # not the 90 deg of a float32 overflow
    a = delvjax.vector_map("env1", grid=Grid(spacing=200.0, heading_deg=30.0 + 3600.0), **kw)
    b = delvjax.vector_map("env1", grid=Grid(spacing=200.0, heading_deg=30.0), **kw)
    assert np.array_equal(np.asarray(a.direction), np.asarray(b.direction), equal_nan=True)


@pytest.mark.parametrize(
    "spec, field",
    [
        (
            {
                "name": "e",
                "arena": [0, 0, 1000, 1000],
                "home": [500, 500],
                "landmarks": [{"x": 200, "y": 200, "r": 20}],
                "lanmarks": [],
            },
            "lanmarks",
        ),
        (
            {
                "name": "e",
                "arena": [0, 0, 1000, 1000],
                "home": [500, 500],
                "landmarks": [{"x": 200, "y": 200, "r": 20, "radius": 30}],
            },
            "landmarks[0].radius",
        ),
    ],
)
def test_unknown_fields_of_an_environment_file_are_named(tmp_path, capsys, spec, field):
    path = tmp_path / "env.json"
    path.write_text(json.dumps(spec))
    out = tmp_path / "m.csv"
    assert main(["vector-map", str(path), "--out", str(out)]) == 2
    assert error_line(capsys).startswith((f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:"))
    assert not out.exists()


def test_a_plot_alone_needs_no_csv_and_no_output_at_all_is_an_error(tmp_path, capsys):
    png = tmp_path / "m.png"
    assert main(["vector-map", "env1", "--spacing", "200", "--plot", str(png)]) == 0
    assert png.exists() and not list(tmp_path.glob("*.csv"))
    capsys.readouterr()
    assert main(["vector-map", "env1", "--spacing", "200"]) == 2
    assert "no output asked for" in error_line(capsys)


def test_a_setting_the_method_does_not_have_is_refused(tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", "--method", "alv", "--levels", "3", "--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --levels:")
    assert not out.exists()


def test_the_help_says_what_each_noise_perturbs(capsys):
    with pytest.raises(SystemExit):
        main(["vector-map", "--help"])
    text = capsys.readouterr().out
    assert "MFDID (docs/model.md" in text and "rollouts only: error of the executed heading" in text


@pytest.mark.parametrize(
    "argv",
    [
        ["catchment", "env1", "--max-steps", "0"],
        ["catchment", "env1", "--method", "alv", "--levels", "3"],
        ["success-rate", "env1", "--method", "delv,alv", "--levels", "3", "--trials", "2"],
        ["success-rate", "env1", "--trials", "0"],
        ["trajectories", "env1", "--start", "330", "640", "--method", "alv", "--home-radius", "-1"],
    ],
)
def test_rollout_commands_validate_everything_before_announcing_work(tmp_path, capsys, argv):
    out = tmp_path / "r.csv"
    assert main(argv + ["--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: ")  # no progress line before the error
    assert not out.exists()


@pytest.mark.parametrize(
    "argv, field",
    [
        (["vector-map", "env1", "--spacing", "5000"], "spacing"),
        (["catchment", "env1", "--spacing", "5000"], "spacing"),
        (["success-rate", "env1", "--distances", "5000", "--trials", "2"], "distances"),
    ],
)
def test_what_cannot_produce_a_result_is_refused(tmp_path, capsys, argv, field):
    out = tmp_path / "r.csv"
    assert main(argv + ["--out", str(out)]) == 2
    assert error_line(capsys).startswith((f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:"))
    assert not out.exists()


@pytest.mark.parametrize(
    "argv",
    [
        ["vector-map", "env1", "--method", "delv", "--hide", "0", "1", "2", "3", "--spacing", "200"],
        ["catchment", "ring3", "--method", "delv", "--occlude", "3", "--spacing", "200"],
    ],
)
def test_a_result_with_every_point_invalid_warns_in_one_line(tmp_path, capsys, argv):
    out = tmp_path / "r.csv"
    assert main(argv + ["--out", str(out)]) == 0
    warnings = [line for line in capsys.readouterr().err.splitlines() if line.startswith("delvjax: warning:")]
    assert len(warnings) == 1 and "every" in warnings[0] and "invalid" in warnings[0]
    assert out.exists()


def test_a_channel_for_a_method_that_reads_no_image_is_refused(tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", "--method", "delv", "--channel", "gray", "--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --channel:")
    assert not out.exists()
    assert (
        main(["vector-map", "env1", "--method", "warping", "--channel", "gray", "--spacing", "200", "--out", str(out)])
        == 0
    )


@pytest.mark.parametrize(
    "argv, field",
    [
        (["vector-map", "env1", "--d", "1e39", "--out", "r.csv"], "d"),  # float32 would overflow to inf
        (["vector-map", "env1", "--bearing-noise-deg", "1e39", "--out", "r.csv"], "bearing_noise_deg"),
        (["images", "render-db", "robot", "--light-deg", "inf", "--out", "db"], "light_deg"),
        (["images", "render-db", "robot", "--light-deg", "nan", "--out", "db"], "light_deg"),
        (["catchment", "env1", "--max-steps", "2147483648", "--out", "r.csv"], "max_steps"),
    ],
)
def test_a_value_beyond_what_the_computation_holds_is_one_line(tmp_path, capsys, monkeypatch, argv, field):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    assert error_line(capsys).startswith((f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:"))
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("flag, value", [("--seed", "1.5"), ("--spacing", "wide"), ("--bogus", "1")])
def test_a_malformed_flag_is_one_line_not_the_usage(tmp_path, capsys, flag, value):
    with pytest.raises(SystemExit) as exc:
        main(["vector-map", "env1", flag, value, "--out", str(tmp_path / "r.csv")])
    assert exc.value.code == 2
    line = error_line(capsys)
    assert flag in line and line.endswith("--help)")
    assert list(tmp_path.iterdir()) == []


def test_a_file_where_a_study_folder_goes_is_one_line(tmp_path, capsys):
    (tmp_path / "environments").write_text("not a folder")
    assert main(["reproduce", "--only", "environments", "--out", str(tmp_path)]) == 2
    assert "holds a file environments" in error_line(capsys)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["environments"]


@pytest.mark.parametrize("flag", ["--motion-heading-noise-deg", "--motion-step-noise"])
def test_a_rollout_only_noise_on_a_vector_map_is_refused_not_ignored(tmp_path, capsys, flag):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", flag, "0.1", "--spacing", "200", "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith(f"delvjax: error: {flag}:") and "acts only in rollouts" in line
    assert not out.exists()
    with pytest.raises(InputError, match="acts only in rollouts"):
        delvjax.vector_map("env1", grid=Grid(spacing=200.0), **{flag[2:].replace("-", "_"): 0.1})


@pytest.mark.parametrize(
    "typed, meant",
    [("ALV", "alv"), ("delv_compass", "delv-compass"), ("Delv Compass", "delv-compass"), ("minwarp", "minwarping")],
)
def test_a_method_name_typed_otherwise_is_refused_with_the_name_meant(tmp_path, capsys, typed, meant):
    """Names are exact (they are CSV columns and sweep coordinates), but the error says which was meant."""
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", "--method", typed, "--spacing", "200", "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith("delvjax: error: --method: unknown method") and f"(did you mean {meant!r}?)" in line
    assert not out.exists()
    assert main(["success-rate", "env1", "--method", f"delv,{typed}", "--trials", "1", "--out", str(out)]) == 2
    assert f"(did you mean {meant!r}?)" in error_line(capsys)
    with pytest.raises(InputError, match="did you mean"):
        delvjax.vector_map("env1", typed, grid=Grid(spacing=200.0))


def test_a_name_like_no_method_gets_no_guess(tmp_path, capsys):
    assert main(["vector-map", "env1", "--method", "xyz", "--spacing", "200", "--out", str(tmp_path / "m.csv")]) == 2
    assert "did you mean" not in error_line(capsys)


@pytest.mark.parametrize(
    "option, flag",
    [
        (["--home", "100", "100"], "--home"),
        (["--arena", "0", "0", "10", "10"], "--arena"),
        (["--hue-deg", "30"], "--hue-deg"),
        (["--max-blobs", "0"], "--max-blobs"),
        (["--elevation", "60", "-15"], "--elevation"),
        (["--heading-convention", "math"], "--heading-convention"),
        (["--camera-height", "5"], "--camera-height"),
        (["--chunk", "0"], "--chunk"),
    ],
)
@pytest.mark.parametrize("command", ["vector-map", "catchment"])
def test_an_image_option_without_images_is_refused_not_recorded(tmp_path, capsys, option, flag, command):
    """The --images group's options read a database: on an environment they changed nothing while the summary
    recorded them (a --home that moved no home)."""
    out = tmp_path / "s.json"
    assert main([command, "env1", "--spacing", "200", *option, "--summary", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith(f"delvjax: error: {flag}: is used only with --images"), line
    assert not out.exists()


def test_classes_without_a_figure_is_refused(tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["vector-map", "env1", "--spacing", "200", "--classes", "--out", str(out)]) == 2
    assert error_line(capsys).startswith("delvjax: error: --classes: marks the figure: give --plot")
    assert not out.exists()


@pytest.mark.parametrize("method, refused", [("delv", True), ("delv-visual", True), ("alv", False)])
def test_compass_noise_is_refused_where_no_method_reads_a_compass(tmp_path, capsys, method, refused):
    out = tmp_path / "s.json"
    code = main(["vector-map", "env1", "--method", method, "--spacing", "200", "--compass-noise-deg", "5",
                 "--summary", str(out)])  # fmt: skip
    if refused:
        assert code == 2 and not out.exists()
        line = error_line(capsys)
        assert line.startswith("delvjax: error: --compass-noise-deg: is read only by methods with a compass"), line
        assert "delv-compass" in line and f"not by {method}" in line
    else:
        assert code == 0 and json.loads(out.read_text())["command_settings"]["compass_noise_deg"] == 5.0


def test_compass_noise_with_one_compass_method_of_several_runs(tmp_path):
    out = tmp_path / "s.csv"
    args = ["success-rate", "env1", "--method", "delv,alv", "--trials", "2", "--distances", "100"]
    assert main([*args, "--compass-noise-deg", "5", "--out", str(out)]) == 0


@pytest.mark.parametrize(
    "option, field, says",
    [
        (["--method", "delv,delv"], "--method", "names delv twice"),
        (["--method", ",delv"], "--method", "none empty"),
        (["--distances", "100", "200", "100"], "--distances", "is given twice"),
    ],
)
def test_a_repeated_method_or_distance_is_refused(tmp_path, capsys, option, field, says):
    """Repeats gave rows twice in the CSV and once in the JSON, or repeated (distance, trial) keys."""
    out = tmp_path / "s.csv"
    assert main(["success-rate", "env1", "--trials", "2", *option, "--out", str(out)]) == 2
    line = error_line(capsys)
    assert line.startswith(f"delvjax: error: {field}:") and says in line, line
    assert not out.exists()


def test_release_points_that_could_not_be_placed_are_said(tmp_path, capsys):
    """A release 699 cm from env1's home falls outside the arena for most directions: the count is warned, the rows
    say not_placed."""
    out = tmp_path / "s.csv"
    assert main(["success-rate", "env1", "--trials", "5", "--distances", "699", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    warned = [line for line in err.splitlines() if "could not be placed" in line]
    assert len(warned) == 1 and warned[0].startswith("delvjax: warning: "), err
    n = int(warned[0].split("warning: ")[1].split()[0])
    assert 1 <= n <= 5 and "of 5 release points of delv" in warned[0]


def test_continuous_levels_are_recorded_as_continuous(tmp_path):
    """DELV's default levels (0 inside the model) is recorded as its help shows it: `--levels 0` is refused."""
    out = tmp_path / "s.json"
    assert main(["vector-map", "env1", "--spacing", "200", "--summary", str(out)]) == 0
    assert json.loads(out.read_text())["command_settings"]["levels"] == "continuous"
