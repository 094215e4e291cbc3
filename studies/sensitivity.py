"""Bearing-noise sensitivity maps by automatic differentiation (jax.grad; beyond the thesis).

At every grid point: gain = ||d direction / d current bearings||, the first-order std of
the homing direction per unit std of bearing noise (discrete choices held fixed).
Run: python -m studies.sensitivity --out results/sensitivity [--env env1]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import delvjax
from delvjax.core import maps
from delvjax.core.sensitivity import bearing_noise_gain
from delvjax.core.sensor import Sensor
from delvjax.io import write_csv, write_figure, write_json
from delvjax.plots import draw_env, subplots
from delvjax.registry import METHODS as REGISTRY

METHODS = ("delv", "delv-compass", "alv", "acv")


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="results/sensitivity")
    p.add_argument("--env", default="env1")
    p.add_argument("--spacing", type=float, default=25.0)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args(argv)
    out = Path(a.out)
    summary: dict = {}
    env = delvjax.load_env(a.env)
    heading, key = delvjax.api.resolve_headings(None, a.seed)
    pts = maps.grid_points(env.arena, a.spacing)
    inc = np.asarray(maps.grid_included(env, pts, 10.0))
    headings = maps.random_headings(key, pts.shape[0])
    fig, axes = subplots(1, len(METHODS), figsize=(4.4 * len(METHODS), 4.6))
    for ax, m in zip(axes, METHODS):
        print(f"[sensitivity] {m}: d direction / d bearings on {env.name}", file=sys.stderr, flush=True)
        gain, ok = bearing_noise_gain(env, pts, headings, key, Sensor(), REGISTRY[m])
        gain, ok = np.asarray(gain), np.asarray(ok) & inc
        write_csv(out / f"gain_{m}_{env.name}.csv",
                  {"x": pts[inc, 0], "y": pts[inc, 1], "heading_deg": np.degrees(np.asarray(headings))[inc],
                   "gain_deg_per_deg": gain[inc], "valid": ok[inc]})
        summary[m] = {"median_gain": float(np.median(gain[ok])), "p90_gain": float(np.percentile(gain[ok], 90))}
        n = int(round(np.sqrt(pts.shape[0])))
        img = np.where(ok, gain, np.nan).reshape(n, n)
        xmin, ymin, xmax, ymax = np.asarray(env.arena)
        im = ax.imshow(np.log10(img), origin="lower", extent=(xmin, xmax, ymin, ymax), cmap="viridis", vmin=-1, vmax=1.5)
        draw_env(ax, env)
        ax.set_title(f"{m}: median {summary[m]['median_gain']:.2f}°/°", fontsize=10)
    fig.colorbar(im, ax=axes, shrink=0.8, label="log10 gain (deg of direction per deg of bearing noise)")
    write_figure(fig, out / f"bearing_gain_{env.name}.png")
    write_json(out / "sensitivity.json", {"env": env.name, "spacing": a.spacing, "seed": a.seed, **summary})
    print(f"wrote {out}/bearing_gain_{env.name}.png and the CSV/JSON beside it")


if __name__ == "__main__":
    main()
