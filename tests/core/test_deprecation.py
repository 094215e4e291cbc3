"""Deprecations point at the user's line and keep the old forms working for one release
(core/deprecation.py): arguments passed by position where they are now keyword-only, old keywords."""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest

import delvjax
from delvjax.core.deprecation import keywords_after


@keywords_after(1, ("b", "c"))
def toy(a, *, b=2, c=3, d=4):
    return a, b, c, d


def test_arguments_by_position_still_work_named_in_a_warning_at_the_callers_line():
    assert toy(1, b=5) == (1, 5, 3, 4)
    with pytest.deprecated_call(match=r"toy\(\): passing b, c by position") as record:
        assert toy(1, 7, 8, d=9) == (1, 7, 8, 9)
    assert Path(record[0].filename).name == Path(__file__).name
    with pytest.raises(TypeError, match="positional arguments at most"):
        toy(1, 2, 3, 4)  # d was never positional
    with pytest.raises(TypeError, match="multiple values"):
        toy(1, 2, b=2)
    assert list(inspect.signature(toy).parameters) == ["a", "b", "c", "d"]  # the new signature is shown


def test_every_wide_public_function_is_keyword_only_after_its_first_arguments():
    """Issue 55: a public function of delvjax with six or more named parameters takes at most its
    first four by position (equinox: 9 of its 10 such functions)."""
    wide = {}
    for name in delvjax.__all__:
        obj = getattr(delvjax, name)
        if not inspect.isfunction(obj):
            continue
        params = [
            p for p in inspect.signature(obj).parameters.values() if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]
        if len(params) >= 6:
            wide[name] = [p.name for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    assert len(wide) >= 10, wide  # catchment, vector_map, homing_loss, run_sweep, load_database, ...
    assert {name: pos for name, pos in wide.items() if len(pos) > 4} == {}


def test_a_method_set_is_one_word_and_its_former_names_still_work():
    """Issue 55: "program" meant both what XLA compiles and the methods compiled together; the latter is a
    `MethodSet` (`method_set=`), and `Program` / `program=` still work for one release, with a warning."""
    from delvjax.core import methods
    from delvjax.options import make_setup, method_set
    from delvjax.sweeps import parse_sweep, point_outcomes

    with pytest.deprecated_call(match="Program is renamed delvjax.MethodSet"):
        assert delvjax.Program is delvjax.MethodSet
    with pytest.deprecated_call(match="Program is now MethodSet"):
        assert methods.Program is methods.MethodSet
    new, _ = make_setup("alv", method_set=["delv", "alv"])
    with pytest.deprecated_call(match="program= is now method_set="):
        old, _ = make_setup("alv", program=["delv", "alv"])
    assert old == new and new == method_set("alv", ["delv", "alv"])[0] and int(new.index) == 1
    with pytest.raises(TypeError, match="former name of method_set="):
        make_setup("alv", program=["alv"], method_set=["alv"])
    with pytest.raises(delvjax.InputError) as e:
        make_setup("alv", method_set=["delv"])
    assert e.value.field == "method_set"
    spec = parse_sweep('[sweep]\nkind = "catchment"\n[axes]\nenv = ["env1"]\nmethod = ["alv"]\nspacing = [500]\n')
    with pytest.raises(TypeError, match="former name of method_set="):  # refused before any work
        point_outcomes(spec, program=("alv",), method_set=("alv",))
