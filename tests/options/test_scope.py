"""Options a command does not use are not accepted silently (issue 10, item 8): refused in one line
naming the option, exit 2, no file; the options it offers reach the API."""

from __future__ import annotations

import pytest

from delvjax.cli import _rollouts as cli_rollouts
from delvjax.cli._main import main
from delvjax.core.errors import InputError


def error_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


@pytest.mark.parametrize(
    "argv",
    [
        ["success-rate", "env1", "--trials", "2", "--distances", "100"],
        ["trajectories", "env1", "--start", "400", "400"],
    ],
)
def test_spacing_is_refused_where_no_grid_is_evaluated(tmp_path, capsys, argv):
    out = tmp_path / "r.csv"
    assert main(argv + ["--spacing", "50", "--out", str(out)]) == 2
    assert error_line(capsys) == f"delvjax: error: --spacing: is not used by {argv[0]} (it evaluates no grid), got 50.0"
    assert not out.exists()


@pytest.mark.parametrize(
    "command, offered", [("vector-map", True), ("catchment", True), ("success-rate", False), ("trajectories", False)]
)
def test_the_help_offers_spacing_only_where_it_is_used(capsys, command, offered):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    assert ("--spacing" in capsys.readouterr().out) == offered


def test_n_starts_with_explicit_starts_is_refused(tmp_path, capsys):
    out = tmp_path / "r.csv"
    assert main(["trajectories", "env1", "--start", "400", "400", "--n-starts", "3", "--out", str(out)]) == 2
    assert error_line(capsys) == "delvjax: error: --n-starts: cannot be combined with --start, got 3"
    assert not out.exists()


@pytest.mark.parametrize("command, api", [("success-rate", "success_rate"), ("trajectories", "trajectories")])
def test_heading_and_lanes_reach_the_rollout(tmp_path, capsys, monkeypatch, command, api):
    """--heading-deg fixes the release headings and --lanes bounds memory on both commands."""
    seen = {}

    def record(env, **kw):
        seen.update(kw)
        raise InputError("stop", None, "recorded")

    monkeypatch.setattr(cli_rollouts.api_rollouts, api, record)
    argv = [command, "env1", "--heading-deg", "30", "--lanes", "7", "--out", str(tmp_path / "r.csv")]
    assert main(argv) == 2
    assert seen["grid"].heading_deg == 30.0 and seen["rules"].lanes == 7 and "spacing" not in seen
