"""Adding a method is its file, one registry line, a twin and a test (CONTRIBUTING "Add a method";
issue 55 point 2): everything else is made from those. `Toy` below is that method file (a method of
one setting), registered the way a method of your own is (`delvjax.options.register`, the run-time
form of a REGISTRY line): a test file rather than a file written into delvjax/core/methods/, which
the architecture and docstring tests read while other tests run. It is then public, documented, a
CLI choice, a sweep axis and a map made again the same from its recorded settings."""

from __future__ import annotations

import json
from pathlib import Path

import jax.numpy as jnp
import numpy as np
import pytest

import delvjax
from delvjax import Grid
from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.core.geometry import angle_of, unit, wrap
from delvjax.core.methods.base import HomingMethod
from delvjax.core.methods.cartwright_collett import CartwrightCollett
from delvjax.core.methods.warping import Warping
from delvjax.core.settings import radians, setting
from delvjax.options import all_options, make_setup, public_classes, register, unregister
from delvjax.options._docs import API_END, API_START, api_methods_markdown, generated_page
from delvjax.options._setup import method_settings
from delvjax.sweeps import parse_sweep

ROOT = Path(__file__).resolve().parents[2]


class Toy(HomingMethod):
    """Toward the current view's mean landmark bearing, turned by `toy_turn_deg` (a test method)."""

    turn: float = setting(
        0.0, check="angle_deg", unit="deg", option="toy_turn_deg", to_field=radians, help="turn of the direction"
    )

    def __call__(self, home, view):
        end = view.end
        mean = jnp.sum(jnp.where(end.valid[:, None], unit(end.bearing), 0.0), axis=0)
        valid = jnp.any(end.valid)
        return jnp.where(valid, wrap(angle_of(mean) + self.turn), jnp.nan), valid


@pytest.fixture
def toy():
    register("toy", Toy(), "toward the mean landmark bearing, turned (a test method)")  # the one registry line
    yield
    unregister("toy")


def test_a_registered_method_is_public_and_documented(toy):
    # would catch: a method class exported only through hand-written lists (delvjax._LAZY, __all__, docs/api.md)
    assert delvjax.Toy is Toy and "Toy" in delvjax.__all__ and "Toy" in dir(delvjax)
    api, options = (generated_page(p, (ROOT / "docs" / p).read_text()) for p in ("api.md", "options.md"))
    assert f"::: {__name__}.Toy\n" in api  # the site's pages, as they are built (docs/_ext/generated.py)
    assert "| `toy_turn_deg` | `--toy-turn-deg` | turn of the direction | deg |" in options
    unregister("toy")
    assert "Toy" not in delvjax.__all__ and not hasattr(delvjax, "Toy")  # read from the registry now


def test_a_registered_method_is_a_cli_choice_and_its_map_is_made_again_the_same(toy, tmp_path, capsys):
    # would catch: a CLI whose --method choices or flags are a list of their own; a setting lost on the way
    out = tmp_path / "toy.json"
    argv = ["vector-map", "env1", "--method", "toy", "--spacing", "300", "--toy-turn-deg", "30", "--summary"]
    assert main([*argv, str(out)]) == 0
    recorded = json.loads(out.read_text())
    vm = delvjax.vector_map("env1", method="toy", toy_turn_deg=30.0, grid=Grid(spacing=300))
    assert recorded["mean_error_deg"] == pytest.approx(
        delvjax.summarize_map(vm.error_deg, vm.valid, vm.included)["mean_error_deg"], abs=1e-9
    )
    again = delvjax.vector_map("env1", method="toy", toy_turn_deg=30.0, grid=Grid(spacing=300))
    np.testing.assert_array_equal(np.asarray(vm.direction), np.asarray(again.direction))
    capsys.readouterr()
    assert main(["vector-map", "env1", "--method", "toyy", "--summary", str(tmp_path / "x.json")]) == 2
    assert "toy" in capsys.readouterr().err  # did you mean


def test_a_registered_method_and_its_setting_are_sweep_axes(toy):
    spec = parse_sweep('[sweep]\nkind = "vector-map"\n[axes]\nmethod = ["toy", "alv"]\ntoy_turn_deg = [0.0, 30.0]\n')
    assert spec.axes["method"] == ["toy", "alv"] and spec.axes["toy_turn_deg"] == [0.0, 30.0]


def test_every_method_of_the_registry_is_public_and_the_api_page_is_current():
    # would catch: MinWarping, Warping2D and Hybrid exported nowhere (before issue 55); docs/api.md not regenerated
    for name, cls in public_classes().items():
        assert getattr(delvjax, name) is cls and name in delvjax.__all__
    assert {"MinWarping", "Warping2D", "Hybrid"} <= set(public_classes())
    page = (ROOT / "docs" / "api.md").read_text()  # the markers only: the site fills them (docs/_ext/generated.py)
    assert page[page.index(API_START) + len(API_START) : page.index(API_END)].strip() == ""
    built = generated_page("api.md", page)
    assert api_methods_markdown() in built and "::: delvjax.core.methods.minwarping.MinWarping" in built


def test_a_relation_between_settings_is_declared_once_on_the_method():
    # would catch: the edge checking n_psi | n_pix and rho_min <= rho_max itself again (it did, besides
    # core.methods.warping.check_hypotheses); the error still names the field and its value
    assert method_settings({"rho_min": 0.5, "rho_max": 0.3, "n_psi": 7}) == {"rho_min": 0.5, "rho_max": 0.3, "n_psi": 7}
    with pytest.raises(InputError, match=r"rho_max: must be in \[rho_min = 0\.5, 1\), got 0\.3"):
        make_setup("warping", rho_min=0.5, rho_max=0.3)
    with pytest.raises(InputError, match=r"rho_max: must be in \[rho_min = 0\.5, 1\), got 0\.3"):
        Warping(rho_min=0.5, rho_max=0.3).check_input(360)  # the same check, on the method
    with pytest.raises(InputError, match="n_psi: .*must divide n_pix = 90"):
        make_setup("warping", n_pix=90, n_psi=72)
    assert make_setup("warping", n_pix=90, n_psi=45)[0].n_psi == 45


def test_the_worked_example_declares_a_setting():
    # would catch: CartwrightCollett's radial_weight as a plain field (no flag, keyword or sweep axis)
    option = all_options()["radial_weight"]
    assert option.owners == (CartwrightCollett,) and option.flag == "--radial-weight"
    assert make_setup("cc", radial_weight=0.5)[0].radial_weight == 0.5
    with pytest.raises(InputError, match="radial_weight"):
        make_setup("cc", radial_weight=-1.0)
