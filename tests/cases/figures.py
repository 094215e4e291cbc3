"""What a reviewer checks in a figure, as code (issue: figures a reviewer accepts): no two texts overlap
(tick labels, axis labels, titles, legends, values written in cells, measured on the drawn figure's
tight bounding boxes), and every panel that shows data has labelled axes."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from itertools import combinations

from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text

SLACK = 1.0  # pixels two boxes may share (antialiasing)


def _drawn_ticklabels(axis) -> list[Text]:
    """The tick labels an axis draws: those of ticks inside its view interval."""
    lo, hi = sorted(axis.get_view_interval())
    span = (hi - lo) * 1e-9
    out = []
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        if lo - span <= tick.get_loc() <= hi + span:
            out += [t for t in (tick.label1, tick.label2) if t.get_visible()]
    return out + [axis.get_offset_text(), axis.label]


def _texts(fig) -> list[tuple[Text, object, object]]:
    """Every text the figure draws, visible and non-empty, with its window extent and its panel (None
    for the figure's own texts)."""
    candidates = [(t, None) for t in fig.texts]
    for legend in fig.legends:
        candidates += [(t, None) for t in legend.get_texts() + [legend.get_title()]]
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        own = [ax.title, ax._left_title, ax._right_title, *ax.texts]  # noqa: SLF001 - the three titles
        if ax.axison:
            own += _drawn_ticklabels(ax.xaxis) + _drawn_ticklabels(ax.yaxis)
        legend = ax.get_legend()
        if legend is not None:
            own += legend.get_texts() + [legend.get_title()]
        candidates += [(t, ax) for t in own]
    renderer = fig.canvas.get_renderer()
    out = []
    for text, ax in candidates:
        if text.get_visible() and text.get_text().strip():
            box = text.get_window_extent(renderer)
            if box.width > 0 and box.height > 0:
                out.append((text, box, ax))
    return out


def _overlap(a, b) -> bool:
    return min(a.x1, b.x1) - max(a.x0, b.x0) > SLACK and min(a.y1, b.y1) - max(a.y0, b.y0) > SLACK


def figure_defects(fig) -> list[str]:
    """What a reviewer would reject: overlapping texts, data panels without axis labels."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    defects = []
    texts = _texts(fig)
    for (ta, a, _), (tb, b, _) in combinations(texts, 2):
        if _overlap(a, b):
            defects.append(f"texts overlap: {ta.get_text()[:40]!r} and {tb.get_text()[:40]!r}")
    renderer = fig.canvas.get_renderer()
    panels = [ax for ax in fig.axes if ax.get_visible() and ax.axison]
    for text, box, owner in texts:  # a label reaching into another panel's plotting area
        for ax in panels:
            if ax is not owner and _overlap(box, ax.patch.get_window_extent(renderer)):
                defects.append(f"text {text.get_text()[:40]!r} reaches into panel {ax.get_title()[:30]!r}")
    for ax in fig.axes:
        if not isinstance(ax, Axes) or not ax.get_visible() or not ax.axison or _is_colorbar(ax):
            continue
        if not (ax.lines or ax.collections or ax.images or ax.patches):
            continue
        for which, label in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
            if not label.strip() and _shows_ticks(ax, which):
                defects.append(f"panel {ax.get_title()[:40]!r} has no {which} label")
    return defects


def legends_over_data(fig) -> list[str]:
    """Legends drawn over a panel's data: a line's point (a marker, a vertex) inside the legend's box."""
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    found = []
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        box = legend.get_window_extent(renderer)
        for line in ax.lines:
            xy = line.get_xydata()
            if not line.get_visible() or not len(xy):
                continue
            points = ax.transData.transform(xy)
            inside = (
                (points[:, 0] > box.x0) & (points[:, 0] < box.x1) & (points[:, 1] > box.y0) & (points[:, 1] < box.y1)
            )
            if inside.any():
                found.append(
                    f"legend of {ax.get_title()[:40]!r} covers {int(inside.sum())} points of {line.get_label()!r}"
                )
    return found


def _is_colorbar(ax) -> bool:
    return hasattr(ax, "_colorbar") or ax.get_label() == "<colorbar>"


def _shows_ticks(ax, which: str) -> bool:
    """An axis with tick labels shown (a shared axis whose labels are hidden needs no label)."""
    axis = ax.xaxis if which == "x" else ax.yaxis
    return any(t.get_visible() and t.get_text() for t in axis.get_ticklabels())


@contextmanager
def recording_defects() -> Iterator[dict[str, list[str]]]:
    """While it runs, every figure delvjax writes is checked after it is saved: file name -> defects."""
    from delvjax.outputs import _files

    found: dict[str, list[str]] = {}
    save = _files._figure_to

    def checked(fig, tmp, target, dpi):
        save(fig, tmp, target, dpi)
        defects = figure_defects(fig)
        if defects:
            found[str(target)] = defects

    _files._figure_to = checked
    try:
        yield found
    finally:
        _files._figure_to = save
