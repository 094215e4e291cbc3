"""Figures of a sweep (docs/sweeps.md "Figures"): heat maps over two axes, line plots over one with
95 % intervals, one panel per combination of the remaining axes; seeds are replicates."""

from __future__ import annotations

import itertools

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from ..core.errors import InputError
from ..core.metrics import t_quantile
from ..sweeps._results import axis_name, dim_name
from ._maps import subplots

MAX_PANELS = 24


OVERLAID = dim_name("method")  # line plots draw this axis as one line each, on shared axes, not as panels
MAX_ANNOTATED = 400  # heat-map cells that get their value written in them
MAX_TICKS = 10  # tick labels per axis (more are thinned: they would overlap)


def check_plot(ds, x: str, y: str | None, metric: str) -> None:
    """`InputError` naming --x, --y or --metric when it is not an axis / a metric of the sweep."""
    for flag, name in (("--x", x), ("--y", y)):
        if name is not None and name not in ds.dims:
            if name in ds.coords:  # an axis of one value is a scalar coordinate
                raise InputError(flag, name, f"has one value ({ds[name].item()}): sweep more values to draw it")
            raise InputError(flag, name, f"is not an axis of the sweep (axes: {', '.join(ds.dims)})")
    if y == x:
        raise InputError("--y", y, "must differ from --x")
    if metric not in ds.data_vars:
        raise InputError("--metric", metric, f"is not a metric of the sweep (metrics: {', '.join(ds.data_vars)})")
    facets = _facets(ds, x, y)
    n = int(np.prod([ds.sizes[d] for d in facets])) if facets else 1
    if n > MAX_PANELS:
        raise InputError(
            "--x",
            x,
            f"leaves {n} panels ({', '.join(facets)}); at most {MAX_PANELS}: choose --x/--y "
            "among them or sweep fewer values",
        )


def _facets(ds, x: str, y: str | None) -> list[str]:
    """The axes that get one panel per value: every axis but x, y, the seeds and, in line plots, the methods."""
    drop = {x, y, "seed"} | ({OVERLAID} if y is None else set())
    return [d for d in ds.dims if d not in drop]


def value_label(ds, axis: str, value) -> str:
    """How a value of an axis reads in a title or legend (an environment by its own name)."""
    if axis == "env" and "env_name" in ds.coords:
        names = dict(zip(ds["env"].values.tolist(), np.atleast_1d(ds["env_name"].values).tolist()))
        return str(names.get(value, value))
    return f"{value:g}" if isinstance(value, float) else str(value)


def axis_label(ds, name: str) -> str:
    """An axis or metric label with its units from the data's CF attributes: "d (cm)"."""
    units = ds[name].attrs.get("units", "") if name in ds.variables else ""
    return f"{axis_name(name)} ({units})" if units and units != "1" else axis_name(name)


def panels(ds, x: str, y: str | None) -> list[tuple[str, dict]]:
    """(title, selection) of every panel: one per combination of the facet axes (`_facets`)."""
    facets = _facets(ds, x, y)
    combos = itertools.product(*[ds[d].values.tolist() for d in facets])
    return [
        (", ".join(f"{axis_name(d)}={value_label(ds, d, v)}" for d, v in zip(facets, c)) or "all", dict(zip(facets, c)))
        for c in combos
    ]


DOMAIN = {"percent": (0.0, 100.0), "degree": (0.0, 180.0)}  # what a metric of these CF units can be (issue 53)


def summarize(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mean over the last axis (seeds) and the half-width of its Student-t 95 % interval (NaN for one seed)."""
    n = values.shape[-1]
    mean = values.mean(axis=-1)
    if n < 2:
        return mean, np.full(mean.shape, np.nan)
    return mean, t_quantile(n) * values.std(axis=-1, ddof=1) / np.sqrt(n)


def _labels(ds, axis: str) -> list[str]:
    """Tick labels of an axis's values (numbers in %g, environments by name)."""
    return [value_label(ds, axis, v) for v in ds[axis].values.tolist()]


def _wilson(ds, sel: dict, x: str, metric: str) -> tuple[np.ndarray, np.ndarray] | None:
    """The Wilson interval of a success rate along x (one seed), if the sweep kept it."""
    names = ("success_ci95_lo_pct", "success_ci95_hi_pct")
    if metric != "success_pct" or not all(n in ds.data_vars for n in names):
        return None
    bounds = []
    for n in names:
        da = ds[n].sel(sel)
        da = da.squeeze([d for d in da.dims if d != x], drop=True)
        bounds.append(da.values)
    return bounds[0], bounds[1]


def _seeded(da, keep: tuple[str, ...]):
    """`da` over `keep` and the seeds (a seed axis of one value when the sweep has one seed)."""
    rest = [d for d in da.dims if d not in (*keep, "seed")]
    da = da.squeeze(rest, drop=True) if rest else da
    if "seed" in keep:  # the seeds drawn along an axis (--x seed): each value one replicate, no interval
        return da.transpose(*keep).expand_dims(replicate=[0], axis=-1)
    if "seed" not in da.dims:
        da = da.expand_dims(seed=[0])
    return da.transpose(*keep, "seed")


def _lines(ax, ds, sel: dict, x: str, metric: str, title: str) -> list[dict]:
    """One line per method (shared axes) with its 95 % band; the rows drawn."""
    methods = ds[OVERLAID].values.tolist() if OVERLAID in ds.dims and x != OVERLAID else [None]
    one = OVERLAID in ds.coords and ds[OVERLAID].size == 1
    colours = [f"C{i % 10}" for i in range(len(methods))]
    rows = []
    xs = ds[x].values
    for method, colour in zip(methods, colours):
        pick = {**sel, OVERLAID: method} if method is not None else sel
        mean, half = summarize(_seeded(ds[metric].sel(pick), (x,)).values)
        lo, hi, what = mean - half, mean + half, "95 % interval over seeds"
        bounds = DOMAIN.get(ds[metric].attrs.get("units", ""))
        if bounds is not None and ((lo < bounds[0]) | (hi > bounds[1])).any():  # a rate's band stays a rate
            lo, hi = np.clip(lo, *bounds), np.clip(hi, *bounds)
            what += f" (Student-t, clipped to {bounds[0]:g}-{bounds[1]:g})"
        wilson = _wilson(ds, pick, x, metric)
        if not np.isfinite(half).any() and wilson is not None:  # one seed: the trials' own interval
            (lo, hi), what = wilson, "95 % Wilson interval"
        elif not np.isfinite(half).any():
            what = "none: one seed per point"
        if method is not None:
            name = method
        else:  # one line: the method of a sweep of one method, else the metric
            name = value_label(ds, OVERLAID, ds[OVERLAID].item()) if one else metric
        ax.plot(xs, mean, marker="o", color=colour, label=str(name))
        if np.isfinite(lo).any():
            ax.fill_between(xs, lo, hi, color=colour, alpha=0.2, linewidth=0)
        named = {"panel": title, axis_name(OVERLAID): name}
        rows += [
            {**named, axis_name(x): v, metric: m, "ci95_lo": a, "ci95_hi": b, "interval": what}
            for v, m, a, b in zip(xs.tolist(), mean, lo, hi)
        ]
    handles, _ = ax.get_legend_handles_labels()
    bands = sorted({r["interval"] for r in rows if np.isfinite(r["ci95_lo"])})
    if bands:  # what the shading is
        handles.append(Patch(color="0.5", alpha=0.3, label="shaded: " + "; ".join(bands)))
    ax.legend(handles=handles, fontsize=7, loc="best")
    if np.issubdtype(xs.dtype, np.number) and len(xs) <= MAX_TICKS:  # every value a tick, when they fit
        ax.set_xticks(xs)
    return rows


def _heat_mean(ds, sel: dict, x: str, y: str, metric: str) -> np.ndarray:
    """The mean over seeds of one panel, (y, x)."""
    return summarize(_seeded(ds[metric].sel(sel), (y, x)).values)[0]


def _heat(fig, ax, ds, mean: np.ndarray, x: str, y: str, metric: str, title: str, limits) -> list[dict]:
    """A heat map of one panel's mean over seeds (`_heat_mean`) with each cell's value written in it, on the
    colour scale limits (vmin, vmax) that every panel shares; the rows drawn."""
    im = ax.imshow(mean, origin="lower", aspect="auto", cmap="viridis", vmin=limits[0], vmax=limits[1])
    for axis, name in ((ax.xaxis, x), (ax.yaxis, y)):  # at most MAX_TICKS labels, evenly thinned
        step = -(-ds.sizes[name] // MAX_TICKS)
        axis.set_ticks(range(0, ds.sizes[name], step), _labels(ds, name)[::step])
    fig.colorbar(im, ax=ax, label=axis_label(ds, metric))
    if mean.size <= MAX_ANNOTATED and max(mean.shape) <= 2 * MAX_TICKS:  # values that fit in their cells
        middle = (limits[0] + limits[1]) / 2 if limits[0] is not None else 0.0  # dark text on the light half
        size = 7 if mean.size <= 100 else 5
        for (i, j), v in np.ndenumerate(mean):
            text = "n/a" if not np.isfinite(v) else f"{v:.3g}"
            colour = "black" if np.isfinite(v) and v > middle else "white"
            ax.text(j, i, text, ha="center", va="center", fontsize=size, color=colour)
    return [
        {"panel": title, axis_name(y): vy, axis_name(x): vx, metric: float(mean[i, j])}
        for i, vy in enumerate(ds[y].values.tolist())
        for j, vx in enumerate(ds[x].values.tolist())
    ]


def sweep_figure(ds, x: str, y: str | None, metric: str) -> tuple[Figure, list[dict]]:
    """(figure, rows): heat maps of `metric` over (x, y) with their values written in, or lines over x
    with 95 % intervals over seeds, every method on one shared axes; one panel per combination of the
    other axes. Axis labels carry the units of the data's attributes."""
    items = panels(ds, x, y)
    cols = min(len(items), 4)
    rows_n = -(-len(items) // cols)
    fig, axes = subplots(
        rows_n, cols, figsize=(4.6 * cols, 3.8 * rows_n), squeeze=False, sharey=y is None, layout="constrained"
    )
    rows = []
    limits, means = (None, None), [None] * len(items)
    if y is not None:  # one colour scale for every panel: the same colour is the same number
        means = [_heat_mean(ds, sel, x, y, metric) for _, sel in items]
        finite = np.concatenate([m.ravel() for m in means])
        finite = finite[np.isfinite(finite)]
        limits = (finite.min(), finite.max()) if finite.size else limits
    for ax, (title, sel), mean in zip(axes.ravel(), items, means):
        if y is None:
            rows += _lines(ax, ds, sel, x, metric, title)
            ax.set_ylabel(axis_label(ds, metric))
        else:
            rows += _heat(fig, ax, ds, mean, x, y, metric, title, limits)
            ax.set_ylabel(axis_label(ds, y))
        ax.set_xlabel(axis_label(ds, x))
        ax.set_title(title, fontsize=9)
    for ax in axes.ravel()[len(items) :]:
        ax.set_visible(False)
    over_seeds = "seed" in ds.dims and ds.sizes["seed"] > 1 and "seed" not in (x, y)
    fig.suptitle(f"{metric}" + (" (mean over seeds)" if over_seeds else ""))
    return fig, rows
