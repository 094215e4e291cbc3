"""`delvjax.plots` is the public home of the figures and of the drawing pieces the studies compose
(issue 55 point 5): every function it exports says what it does and hints every argument and its
result; the names renamed for the public surface keep their private names working."""

from __future__ import annotations

import inspect

import numpy as np

import delvjax.plots as plots
from delvjax.envs import load_env
from delvjax.plots import _maps, _rollouts

UNHINTED = {("sweep_figure", "ds"): "an xarray.Dataset: its hint would load xarray with every figure"}


def test_every_exported_function_has_a_docstring_and_full_hints():
    functions = {n: f for n, f in vars(plots).items() if inspect.isfunction(f)}
    assert {"subplots", "draw_env", "draw_vector_map", "catchment_panel", "vector_map_figure"} <= set(functions)
    bad = []
    for name, f in sorted(functions.items()):
        sig = inspect.signature(f)
        unhinted = [
            p.name
            for p in sig.parameters.values()
            if p.annotation is p.empty and p.kind != p.VAR_KEYWORD and (name, p.name) not in UNHINTED
        ]
        if not (f.__doc__ or "").strip() or unhinted or sig.return_annotation is sig.empty:
            bad.append(f"{name}: doc {bool(f.__doc__)}, unhinted {unhinted}, return {sig.return_annotation}")
    assert not bad, bad


def test_public_names_are_the_private_objects():
    assert plots.HOMING_ARROW is _maps.ARROW
    assert plots.CATCHMENT_SQUARE is _rollouts.SQUARE
    assert plots.has_uncounted is _rollouts.not_counted
    assert plots.subplots is _maps.subplots


def test_the_public_pieces_draw_a_vector_map_panel():
    """The pieces a study composes (subplots, draw_vector_map, draw_env, vector_map_handles) draw on
    one axes with their hints checked (beartype in the suite): arrows for the valid points, an x for the
    invalid one."""
    env = load_env("env1")
    fig, ax = plots.subplots(figsize=(3.0, 3.0))
    points = np.array([[100.0, 100.0], [200.0, 100.0], [300.0, 100.0]])
    plots.draw_vector_map(
        ax, env, points, np.zeros(3), np.array([True, True, False]), np.ones(3, bool), 100.0, error_deg=np.zeros(3)
    )
    plots.draw_env(ax, env)
    assert len(ax.collections) == 2  # the quiver of two arrows and the scatter of the invalid point
    assert ax.collections[0].N == 2
    assert [h.get_label() for h in plots.vector_map_handles()][0] == "homing direction (unit arrows)"
    assert fig is ax.figure
