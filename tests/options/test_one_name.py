"""One name, one meaning (docs/options.md): an option several methods declare (`n_alpha`, `n_rho`) is one
option, checked and defaulted by the declaration of each method it sets; the method-prefixed names of earlier
releases (`mw_n_alpha`) still work for one release, each with a warning."""

from __future__ import annotations

from pathlib import Path

import pytest

from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.core.methods.alv import ALV
from delvjax.core.settings import setting
from delvjax.options._schema import _options, all_options, renamed
from delvjax.options._setup import make_setup
from delvjax.sweeps._spec import parse_sweep

DOCS = Path(__file__).resolve().parents[2] / "docs" / "options.md"


def test_every_former_name_is_listed_in_the_docs():
    page = DOCS.read_text()
    assert renamed(), "no renamed options: drop this test and the docs section next release"
    missing = [old for old in renamed() if f"`{old}`" not in page]
    assert not missing, missing


def test_a_shared_name_keeps_each_method_s_default_and_check():
    n_rho = all_options()["n_rho"]
    assert {t.__name__ for t in n_rho.owners} == {"Warping", "Warping2D"}
    assert "(default 15)" in n_rho.help and "(default 20)" in n_rho.help  # each method's default in the help
    m, _ = make_setup("warping2d", n_pix=72, rho_min=0.0)  # 0 is Warping2D's default and valid there
    assert m.rho_min == 0.0 and m.n_rho == 20
    with pytest.raises(InputError) as e:  # the 1D warping needs 0 < rho < 1
        make_setup("warping", rho_min=0.0)
    assert e.value.field == "rho_min"


def test_one_option_sets_every_method_that_has_it():
    mw, _ = make_setup("minwarping", n_pix=72, n_alpha=36, n_psi=36)
    w2, _ = make_setup("warping2d", n_pix=72, n_alpha=36, n_psi=36)
    assert (mw.n_alpha, mw.n_psi, w2.n_alpha, w2.n_psi) == (36, 36, 36, 36)
    with pytest.raises(InputError, match="not a setting of the method delv"):
        make_setup("delv", n_alpha=36)  # a name means one thing, and DELV has no movement directions


def test_former_keywords_work_with_a_deprecation_warning():
    with pytest.deprecated_call(match="'mw_n_alpha' is now 'n_alpha'"):
        m, _ = make_setup("minwarping", n_pix=72, mw_n_alpha=36, mw_n_psi=36)
    assert (m.n_alpha, m.n_psi) == (36, 36)
    with pytest.deprecated_call(match="'hybrid_rms_max' is now 'rms_max'"):
        h, _ = make_setup("hybrid", n_pix=72, hybrid_rms_max=10.0, n_alpha=36, n_psi=36)
    assert h.rms_max == 10.0
    with pytest.raises(InputError, match="former name") as e:  # both: which one was meant?
        make_setup("minwarping", n_pix=72, mw_n_alpha=36, n_alpha=72)
    assert e.value.field == "mw_n_alpha"


def test_former_flags_work_with_a_warning_line(capsys):
    # 7 divides no panorama width: the error names today's flag, the warning the old one
    assert main(["vector-map", "env1", "--method", "minwarping", "--mw-n-alpha", "7", "--summary", "x.json"]) == 2
    err = capsys.readouterr().err
    assert "warning: --mw-n-alpha is now --n-alpha" in err
    assert "error: --n-alpha" in err


def test_former_sweep_axes_are_read_with_a_deprecation_warning():
    with pytest.deprecated_call(match="'mw_n_psi' is now 'n_psi'"):
        spec = parse_sweep('[axes]\nenv = ["env1"]\nmethod = ["minwarping"]\nmw_n_psi = [36, 72]\n')
    assert spec.axes["n_psi"] == [36, 72] and "mw_n_psi" not in spec.axes


def test_one_name_with_two_kinds_of_value_is_a_developer_error():
    class Other(ALV):
        turn: str = setting("a", check="choice", choices=("a", "b"), help="a choice")

    class Another(ALV):
        turn: float = setting(1.0, check="positive", help="a number")

    with pytest.raises(TypeError, match="'turn'"):
        _options((Other, Another))


def test_the_docs_table_shows_each_method_s_declaration_of_a_shared_name():
    from delvjax.options._docs import options_markdown

    rows = [r for r in options_markdown().splitlines() if r.startswith("| `rho_min` |")]
    assert len(rows) == 2 and "| 0.1 |" in rows[0] and "| 0 |" in rows[1]  # Warping's, Warping2D's default
