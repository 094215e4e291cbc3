"""A figure's legend covers none of its data (issue 53 point 4: Fig 5.7b's nine entries sat on the
curves), checked with `tests.cases.figures.legends_over_data`, and no other defect appears."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from delvjax.plots._rollouts import success_rate_figure
from delvjax.studies.runs import visual_compass
from delvjax.studies.runs._common import LABEL
from tests.cases.figures import figure_defects, legends_over_data


def _rows(top: float, bottom: float) -> list[dict]:
    pct = np.linspace(top, bottom, 8)
    return [
        {"distance_cm": 50.0 * (i + 1), "success_pct": p, "ci_lo_pct": max(p - 8, 0), "ci_hi_pct": min(p + 8, 100)}
        | {"successes": int(p), "placed": 100}
        for i, p in enumerate(pct)
    ]


def test_the_check_finds_a_legend_drawn_on_the_data():
    fig = Figure()
    ax = fig.add_subplot()
    x, y = np.meshgrid(np.linspace(0, 1, 20), np.linspace(0, 1, 20))
    ax.plot(x.ravel(), y.ravel(), "o", label="everywhere")
    ax.legend(loc="center")
    assert legends_over_data(fig)


def test_the_success_rate_legend_leaves_every_curve_in_view():
    """Three methods under three rule sets (Fig 5.7b), curves from 100 % down to 0 % at every corner."""
    tables = {
        f"{m} ({rules})": _rows(top, bottom)
        for m, (top, bottom) in zip(("DELV (compass)", "ACV", "ALV"), ((100, 0), (0, 100), (50, 5)))
        for rules in ("default", "homing", "physical")
    }
    fig = success_rate_figure(tables, "env1, with a compass")
    assert legends_over_data(fig) == []
    assert figure_defects(fig) == []


def test_lines_on_one_another_stay_distinguishable():
    """compass_noise_catchment.png: DELV's and ALV's lines both at 100 % (DELV's was hidden under ALV's)."""
    rows = [
        {"method": LABEL[m], "compass sigma °": s, "catchment %": 100.0 if m != "acv" else 96.0 + s / 15}
        for m in visual_compass.TRUE
        for s in visual_compass.SIGMAS
    ]
    fig = visual_compass.compass_noise_figure(rows)
    lines = fig.axes[0].lines
    assert len({(ln.get_marker(), ln.get_linestyle()) for ln in lines}) == len(lines) == 3
    under, over = lines[0], lines[2]  # drawn first, larger: its marker shows around the one on top
    assert under.get_markersize() > over.get_markersize() and under.get_zorder() < over.get_zorder()
    assert legends_over_data(fig) == [] and figure_defects(fig) == []
