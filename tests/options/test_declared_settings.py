"""A setting is declared once, on the field it configures (core/settings.py), and everything else
is made from it: a method defined in this file alone, with one new setting, gets a CLI flag with
its help, a refusal of a bad value naming it, an API keyword and a sweep axis, with no other file
touched (docs/architecture.md "Settings")."""

from __future__ import annotations

import json
import math

import jax.numpy as jnp
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.core.methods.alv import ALV
from delvjax.core.settings import setting
from delvjax.options import all_options, register, unregister
from delvjax.sweeps import load_sweep, run_sweep, save_sweep
from delvjax.sweeps._spec import parse_sweep


class Toy(ALV):
    """ALV with a compass, its homing direction turned by `turn_deg`: a method of one file."""

    turn_deg: float = setting(0.0, check="non_negative", unit="deg", help="extra turn of the homing direction")

    def __call__(self, home, view):
        angle, valid = super().__call__(home, view)
        return jnp.mod(angle + self.turn_deg * (math.pi / 180.0), 2 * math.pi), valid


@pytest.fixture
def toy():
    register("toy", Toy(), "ALV turned by a fixed angle (a test method)")  # the one registry line
    yield
    unregister("toy")


def test_the_setting_is_an_option_with_its_declared_check_unit_and_help(toy):
    opt = all_options()["turn_deg"]
    assert opt.owners == (Toy,) and opt.flag == "--turn-deg" and opt.type is float
    assert opt.help == "Toy: extra turn of the homing direction, deg (default 0)"
    unregister("toy")
    assert "turn_deg" not in all_options()  # read from the registry now, not at import


def test_the_setting_is_a_cli_flag_with_its_help(toy, capsys):
    with pytest.raises(SystemExit):
        main(["vector-map", "--help"])
    assert "--turn-deg" in capsys.readouterr().out


def test_the_cli_flag_sets_the_field_and_a_bad_value_is_refused_naming_it(toy, tmp_path, capsys):
    def mean_error(turn: str) -> float:
        out = tmp_path / f"s{turn}.json"
        assert (
            main(
                ["vector-map", "env1", "--method", "toy", "--spacing", "200", "--turn-deg", turn, "--summary", str(out)]
            )
            == 0
        )
        return json.loads(out.read_text())["mean_error_deg"]

    straight, turned = mean_error("0"), mean_error("90")
    assert turned > straight + 45  # the setting reached the field
    capsys.readouterr()
    out = tmp_path / "bad.json"
    assert main(["vector-map", "env1", "--method", "toy", "--turn-deg", "-5", "--summary", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--turn-deg" in err[0] and "must be >= 0" in err[0] and not out.exists()
    # a method without the setting refuses it, naming it
    assert main(["vector-map", "env1", "--method", "alv", "--turn-deg", "10", "--summary", str(out)]) == 2
    assert "--turn-deg: is not a setting of the method alv" in capsys.readouterr().err


def test_the_setting_is_an_api_keyword(toy):
    vm = delvjax.vector_map("env1", method="toy", turn_deg=180.0, grid=Grid(spacing=200))
    assert float(jnp.mean(vm.error_deg)) > 90
    with pytest.raises(InputError, match="turn_deg"):
        delvjax.vector_map("env1", method="toy", turn_deg=float("nan"), grid=Grid(spacing=200))


def test_the_setting_is_a_sweep_axis(toy, tmp_path):
    text = (
        '[sweep]\nkind = "vector-map"\nmetrics = ["mean_error_deg"]\n'
        '[axes]\nmethod = ["toy"]\nspacing = [200]\nturn_deg = [0.0, 90.0]\n'
    )
    spec = parse_sweep(text)
    assert spec.axes["turn_deg"] == [0.0, 90.0]
    data = run_sweep(spec)
    save_sweep(data, tmp_path / "sweep")
    assert load_sweep(tmp_path / "sweep")["mean_error_deg"].shape == data["mean_error_deg"].shape
    errors = data["mean_error_deg"].squeeze().values
    assert errors[1] > errors[0] + 45
    with pytest.raises(InputError, match="turn_deg"):
        parse_sweep(text.replace("[0.0, 90.0]", '["left"]'))


def test_the_docs_option_table_is_made_from_the_declarations():
    """docs/options.md holds no table of its own: the site puts the declarations' table in place of its
    mark (docs/_ext/generated.py), so a new setting edits no page."""
    from pathlib import Path

    from delvjax.options._docs import OPTIONS_MARK, generated_page, options_markdown

    page = (Path(__file__).resolve().parents[2] / "docs" / "options.md").read_text()
    assert page.count(OPTIONS_MARK) == 1 and "| `levels` |" not in page
    built = generated_page("options.md", page)
    assert options_markdown().rstrip("\n") in built and OPTIONS_MARK not in built


def test_a_relation_between_settings_applies_only_to_the_methods_that_have_them():
    from delvjax.options import make_setup

    module, sensor = make_setup("delv", n_pix=7)  # DELV has no psi hypotheses: any ring width
    assert sensor.n_pix == 7
    with pytest.raises(InputError, match="n_psi: must divide n_pix = 7"):
        make_setup("warping", n_pix=7)
