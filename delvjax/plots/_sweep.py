"""Figures of a sweep (docs/sweeps.md "Figures"): heat maps over two axes, line plots over one with
95 % intervals, one panel per combination of the remaining axes; seeds are replicates."""

from __future__ import annotations

import itertools

import numpy as np

from ..core.errors import InputError
from ..core.metrics import t_quantile
from ._maps import subplots

MAX_PANELS = 24


def check_plot(ds, x: str, y: str | None, metric: str) -> None:
    """`InputError` naming --x, --y or --metric when it is not an axis / a metric of the sweep."""
    for flag, name in (("--x", x), ("--y", y)):
        if name is not None and name not in ds.dims:
            raise InputError(flag, name, f"is not an axis of the sweep (axes: {', '.join(ds.dims)})")
    if y == x:
        raise InputError("--y", y, "must differ from --x")
    if metric not in ds.data_vars:
        raise InputError("--metric", metric, f"is not a metric of the sweep (metrics: {', '.join(ds.data_vars)})")
    facets = [d for d in ds.dims if d not in (x, y, "seed") and ds.sizes[d] > 1]
    n = int(np.prod([ds.sizes[d] for d in facets])) if facets else 1
    if n > MAX_PANELS:
        raise InputError(
            "--x",
            x,
            f"leaves {n} panels ({', '.join(facets)}); at most {MAX_PANELS}: choose --x/--y "
            "among them or sweep fewer values",
        )


def panels(ds, x: str, y: str | None) -> list[tuple[str, dict]]:
    """(title, selection) of every panel: one per combination of the axes other than x, y and seed."""
    facets = [d for d in ds.dims if d not in (x, y, "seed") and ds.sizes[d] > 1]
    combos = itertools.product(*[ds[d].values.tolist() for d in facets])
    return [(", ".join(f"{d}={v}" for d, v in zip(facets, c)) or "all", dict(zip(facets, c))) for c in combos]


def summarize(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mean over the last axis (seeds) and the half-width of its Student-t 95 % interval (NaN for one seed)."""
    n = values.shape[-1]
    mean = values.mean(axis=-1)
    if n < 2:
        return mean, np.full(mean.shape, np.nan)
    return mean, t_quantile(n) * values.std(axis=-1, ddof=1) / np.sqrt(n)


def _labels(ds, axis: str) -> list[str]:
    """Tick labels of an axis's values (numbers in %g)."""
    return [f"{v:g}" if isinstance(v, float) else str(v) for v in ds[axis].values.tolist()]


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


def sweep_figure(ds, x: str, y: str | None, metric: str):
    """(figure, rows): heat maps of `metric` over (x, y), or lines over x with 95 % intervals over seeds."""
    items = panels(ds, x, y)
    cols = min(len(items), 4)
    rows_n = -(-len(items) // cols)
    fig, axes = subplots(rows_n, cols, figsize=(4.2 * cols, 3.4 * rows_n), squeeze=False)
    rows = []
    for ax, (title, sel) in zip(axes.ravel(), items):
        da = ds[metric].sel(sel)
        rest = [d for d in da.dims if d not in (x, y, "seed")]
        da = da.squeeze(rest, drop=True) if rest else da
        if "seed" not in da.dims:
            da = da.expand_dims(seed=[0])
        if y is None:
            mean, half = summarize(da.transpose(x, "seed").values)
            xs = ds[x].values
            lo, hi, what = mean - half, mean + half, "95 % interval over seeds"
            wilson = _wilson(ds, sel, x, metric)
            if not np.isfinite(half).any() and wilson is not None:  # one seed: the trials' own interval
                (lo, hi), what = wilson, "95 % Wilson interval"
            ax.plot(xs, mean, marker="o", color="tab:blue")
            if np.isfinite(lo).any():
                ax.fill_between(xs, lo, hi, color="tab:blue", alpha=0.25, label=what)
            ax.set_xlabel(x)
            ax.set_ylabel(metric)
            rows += [
                {"panel": title, x: v, metric: m, "ci95_lo": a, "ci95_hi": b, "interval": what}
                for v, m, a, b in zip(xs.tolist(), mean, lo, hi)
            ]
        else:
            mean, _ = summarize(da.transpose(y, x, "seed").values)
            im = ax.imshow(mean, origin="lower", aspect="auto", cmap="viridis")
            ax.set_xticks(range(ds.sizes[x]), _labels(ds, x))
            ax.set_yticks(range(ds.sizes[y]), _labels(ds, y))
            ax.set_xlabel(x)
            ax.set_ylabel(y)
            fig.colorbar(im, ax=ax, label=metric)
            rows += [
                {"panel": title, y: vy, x: vx, metric: float(mean[i, j])}
                for i, vy in enumerate(ds[y].values.tolist())
                for j, vx in enumerate(ds[x].values.tolist())
            ]
        ax.set_title(title, fontsize=9)
    for ax in axes.ravel()[len(items) :]:
        ax.set_visible(False)
    fig.suptitle(f"{metric}" + (" (mean over seeds)" if "seed" in ds.dims and ds.sizes["seed"] > 1 else ""))
    fig.tight_layout()
    return fig, rows
