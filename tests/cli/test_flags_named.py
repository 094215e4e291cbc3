"""An error names the option as the user typed it: the flag (`--n-alpha`), not the API keyword a check
raises with (`n_alpha`); a sweep file's keys stay as the file writes them (issue 53 point 7)."""

from __future__ import annotations

import argparse

from delvjax.cli._main import as_typed, build_parser, main
from delvjax.core.errors import InputError


def test_minwarping_on_the_default_width_names_the_flag_to_change(tmp_path, capsys):
    out = tmp_path / "m.csv"
    grid = ["--n-alpha", "96", "--n-psi", "96"]  # the authors' counts: the defaults (72) divide 360
    assert main(["vector-map", "env1", "--method", "minwarping", *grid, "--spacing", "200", "--out", str(out)]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith("delvjax: error: --n-alpha and --n-psi: must divide the panorama width 360"), line
    assert "90" in line and not out.exists()  # a count that divides it


def test_a_registry_option_and_a_parser_option_are_named_by_flag_but_a_sweep_key_is_not():
    parser = build_parser()
    args = parser.parse_args(["vector-map", "env1"])
    assert str(as_typed(InputError("n_psi", 96, "must divide 360"), parser, args)).startswith("--n-psi: ")
    assert str(as_typed(InputError("spacing", 0, "must be > 0"), parser, args)).startswith("--spacing: ")
    assert str(as_typed(InputError("landmarks[0].x", 0, "bad"), parser, args)).startswith("landmarks[0].x: ")
    sweep = argparse.Namespace(command="sweep")
    assert str(as_typed(InputError("n_psi", 96, "must divide 360"), parser, sweep)).startswith("n_psi: ")
