"""Random command lines and API options (hypothesis): every one is run or refused in one line naming
the option (exit 0 or 2, no traceback, no file left by a refusal)."""

from __future__ import annotations

import contextlib
import io
import tempfile
from pathlib import Path

from hypothesis import event, given, settings
from hypothesis import strategies as st

from delvjax import InputError
from delvjax.cli._main import main
from delvjax.evaluate._vector_map import map_request
from tests import hints_unchecked
from tests.cases.strategies import FAST, JUNK

NUM_BAD, INT_BAD = ["0", "-1", "nan", "inf", "abc", "1e400"], ["0", "-2", "1.5", "abc", "99999999999"]
SCENE = {  # option: (good values, bad values); the one good method, alv, reads no image and has no DELV/warping settings
    "--method": (["alv"], ["nosuch", "", ",", "ALV"]),
    "--d": (["30"], NUM_BAD),
    "--clearance": (["0", "15"], ["-1", "nan", "inf", "abc"]),
    "--heading-deg": (["1e30", "-725.5"], ["nan", "inf", "x"]),
    "--seed": (["0", "4294967295"], ["-1", "4294967296", "1.5", "abc"]),
    "--background": (["walls"], ["", "sky"]),
    "--channel": ([], ["gray", "mask", "rgb"]),
    "--levels": ([], [*INT_BAD, "3"]),
    "--n-heading": ([], [*INT_BAD, "4"]),
    "--n-psi": ([], ["7", "0", "8"]),
    "--rho-min": ([], ["0.5", "0", "2", "nan"]),
    "--blur-deg": ([], ["3", "-1"]),
    "--hide": ([], ["99", "-1", "abc", ["0", "99"]]),
    "--bearing-noise-deg": (["0", "2"], ["-1", "nan", "inf", "abc"]),
    "--step-noise": (["0.1"], ["-0.1", "nan"]),
}
GRID = {"--spacing": (["500"], ["0", "-1", "nan", "inf", "abc", "1e30"])}
ROLL = {
    "--max-steps": (["1", "3"], INT_BAD),
    "--home-radius": (["20"], NUM_BAD),
    "--lanes": (["64"], INT_BAD),
    "--first-move": (["homing", "release"], ["", "jump"]),
    "--collisions": (["ignore", "fail"], ["bounce"]),
    "--motion-heading-noise-deg": (["5"], ["-5", "inf"]),  # rollouts only: a vector map refuses it
}
COMMANDS = {
    "vector-map": {**SCENE, **GRID, "--motion-heading-noise-deg": ([], ["5", "0", "-5"])},
    "catchment": {**SCENE, **GRID, **ROLL, "--occlude": ([], ["5", "-1", "abc"])},
    "success-rate": {
        **SCENE,
        **ROLL,
        "--trials": (["1"], INT_BAD),
        "--trials-out": ([], ["{o}/t.txt"]),
        "--distances": (["100", ["50", "150"]], ["0", "-5", "nan", "1e9", "abc"]),
    },
    "trajectories": {
        **SCENE,
        **ROLL,
        "--n-starts": (["1", "2"], INT_BAD),
        "--start": ([["300", "300"]], [["nan", "1"], ["-5", "5"], ["765", "615"], ["abc", "1"]]),
    },
}
COMMON = {
    "env": (["env1"], ["nosuch", "", "{o}", "{f}"]),  # {o}: a folder, {f}: a file that is not JSON
    "out": (
        [["--out", "{o}/o.csv"], ["--summary", "{o}/s.json"]],
        [[], ["--out", "{o}/o.txt"], ["--plot", "{o}/p.gif"], ["--summary", "{o}/s.csv"], ["--out", "{f}/x.csv"]],
    ),
}


@st.composite
def cli_args(draw):
    """(argv with {o} and {f} placeholders, some value is bad, junk tokens appended). Only vector-map may run
    (alv on env1, 4 grid points: two compiled programs); a rollout command always gets a bad value."""
    cmd = draw(st.sampled_from(sorted(COMMANDS)))
    pool = {**COMMON, **COMMANDS[cmd]}
    names = ["env", "out", "--method", *(["--spacing"] if "--spacing" in pool else [])]
    clean = draw(st.integers(0, 2)) == 0  # only good values drawn (a rollout command still gets one bad one)
    rest = sorted(n for n in set(pool) - set(names) if pool[n][0] or not clean)
    names += draw(st.permutations(rest))[: draw(st.integers(0, 6))]
    picks = {}
    for name in names:
        good, bad = pool[name]
        is_bad = not good or (not clean and draw(st.integers(0, 3)) == 0)
        picks[name] = (draw(st.sampled_from(bad if is_bad else good)), is_bad)
    if cmd != "vector-map" and not any(b for _, b in picks.values()):
        name = draw(st.sampled_from(names))
        picks[name] = (draw(st.sampled_from(pool[name][1])), True)
    argv = [cmd, picks.pop("env")[0]] + picks["out"][0]
    for name, (value, _) in picks.items():
        argv += [] if name == "out" else [name, *(value if isinstance(value, list) else [value])]
    bad = any(b for _, b in picks.values()) or argv[1] != "env1"
    junk = draw(st.lists(st.text(max_size=4), max_size=2)) if bad else []
    return argv + junk, bad, bool(junk)


@settings(max_examples=60, **FAST)
@given(case=cli_args())
def test_random_command_lines_exit_0_or_2_without_a_traceback(case, tmp_path_factory):
    argv, bad, junk = case
    base = tmp_path_factory.getbasetemp()
    (base / "notjson").write_text("not json")
    out = tempfile.mkdtemp(dir=base)
    argv = [a.replace("{o}", out).replace("{f}", str(base / "notjson")) for a in argv]
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse: usage errors exit 2, --help exits 0
            code = exc.code
    event(f"{argv[0]} exit {code}")
    assert code in ((0, 2) if junk else (2,) if bad else (0,)), (argv, err.getvalue())
    assert "Traceback" not in err.getvalue()
    if code == 2:
        assert not list(Path(out).iterdir()), (argv, "bad input wrote a file")


@settings(max_examples=100, **FAST)
@given(
    name=st.sampled_from(
        [
            "levels",
            "n_heading",
            "n_alpha",
            "batch_size",
            "clearance",
            "heading_deg",
            "seed",
            "d",
            "step_noise",
            "blur_deg",
        ]
    ),
    value=st.one_of(JUNK, st.floats(), st.integers(-(2**40), 2**70)),
)
def test_api_options_are_accepted_or_refused_by_name(name, value):
    method = {"n_alpha": "warping", "blur_deg": "mfdid"}.get(name, "delv")
    try:
        with hints_unchecked():  # values of every type on purpose: map_request's own errors are tested
            map_request("env1", method=method, spacing=500, **{name: value})
    except InputError as exc:  # a huge clearance leaves no grid point: named as spacing
        assert exc.field in (name, "spacing" if name == "clearance" else name), str(exc)
