"""The reviewer's checks of `tests.cases.figures` (applied to every figure the suite writes, by the
autouse fixture of tests/conftest.py) catch what they claim to: each defect is drawn on purpose."""

from __future__ import annotations

from delvjax import Grid
from delvjax.plots._maps import subplots
from tests.cases.figures import figure_defects


def test_overlapping_texts_are_found():
    fig, ax = subplots(figsize=(3, 3))
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")
    ax.text(0.5, 0.5, "first label")
    ax.text(0.5, 0.5, "second label")
    assert any("texts overlap" in d and "first label" in d for d in figure_defects(fig))


def test_a_label_reaching_into_the_next_panel_is_found():
    fig, axes = subplots(1, 2, figsize=(4, 2.5))  # no layout engine: a long y label runs into panel 0
    for ax in axes:
        ax.plot([0, 1], [0, 1])
        ax.set_xlabel("x")
        ax.set_title("left" if ax is axes[0] else "right")
    axes[0].set_ylabel("y")
    axes[1].set_ylabel("a very long label " * 3)
    axes[1].set_yticks([0.0, 1.0], ["0.0000000000001", "1.0000000000001"])
    defects = figure_defects(fig)
    assert any("reaches into panel 'left'" in d for d in defects), defects


def test_a_data_panel_without_axis_labels_is_found_and_a_picture_is_not():
    fig, axes = subplots(1, 2, figsize=(6, 3), layout="constrained")
    axes[0].plot([0, 1], [0, 1])
    axes[0].set_title("data")
    axes[1].imshow([[0, 1], [1, 0]])
    axes[1].set_xticks([])
    axes[1].set_yticks([])  # a picture: no ticks, no labels needed
    defects = figure_defects(fig)
    assert defects == ["panel 'data' has no x label", "panel 'data' has no y label"]


def test_a_clean_figure_passes():
    fig, ax = subplots(figsize=(4, 3), layout="constrained")
    ax.plot([0, 1], [0, 1], label="line")
    ax.set_xlabel("d (cm)")
    ax.set_ylabel("error (degree)")
    ax.legend()
    assert figure_defects(fig) == []


def test_a_catchment_map_under_occlusion_has_labelled_panels_and_says_what_its_cells_mean():
    import delvjax
    from delvjax.plots import catchment_figure

    c = delvjax.catchment("env1", occlude=1, grid=Grid(spacing=200.0))  # one panel per hidden landmark
    fig = catchment_figure(delvjax.load_env("env1"), c, 200.0, "DELV, one landmark hidden")
    assert figure_defects(fig) == []
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert "hidden landmark" in labels and "blank: release point that fails" in labels
    assert "not counted (within d of a wall)" not in labels  # every grid point counts at this spacing


def test_cells_not_counted_are_hatched_and_named_not_drawn_as_failures():
    import delvjax
    from delvjax.plots import catchment_figure

    c = delvjax.catchment("env1", d=150.0, grid=Grid(spacing=200.0))  # grid points 100 cm from a wall: not counted
    fig = catchment_figure(delvjax.load_env("env1"), c, 200.0, "DELV, d = 150 cm")
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert "not counted (within d of a wall)" in labels
    hatched = [p for p in fig.axes[0].collections if p.get_hatch() == "////"]
    assert len(hatched) == 1 and len(hatched[0].get_paths()) == 16  # the 16 grid points of the outer ring
