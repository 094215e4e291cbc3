"""Landmark layouts designed for homing (beyond the thesis; docs/differentiable.md "Layout design").

The landmarks of the thesis's environments are moved by optimistix BFGS on the soft homing loss
of DELV smoothed at 5 cm (without and, in the full run, with one landmark hidden), then the
optimised layouts are compared with the originals by the ordinary evaluation over several seeds:
hard loss, catchment and error point rates, each change judged against the seed-to-seed spread.
"""

from __future__ import annotations

import numpy as np

from delvjax.envs import env_to_dict
from delvjax.gradients import optimise_layout
from delvjax.plots import layout_figure

from ._common import env

TITLE = "Optimised landmark layouts against the thesis's environments (gradients; beyond the thesis)"
COST = 85  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 4


def run(ctx) -> None:
    quick = ctx.config.quick or ctx.config.spacing >= 100
    cases = [("env1", 0), ("env2", 0)] if quick else [("env1", 0), ("env2", 0), ("env3", 0), ("env1", 1)]
    steps = 10 if quick else 60
    rows, layouts = [], {}
    for name, k in cases:
        r = optimise_layout(
            env(name),
            "delv",
            occlude=k,
            spacing=ctx.config.spacing,
            seed=ctx.config.seed,
            steps=steps,
            seeds=2 if quick else 3,
        )
        before, after = r.rows
        key = f"{name}:delv" + (f":occlude={k}" if k else "")
        for row in r.rows:
            rows.append(
                {
                    "env": name,
                    "occlude": k,
                    **{
                        c: row[c]
                        for c in (
                            "layout",
                            "catchment_pct",
                            "catchment_min_pct",
                            "gt45_pct",
                            "gt90_pct",
                            "hard_loss",
                            "hard_loss_sd",
                            "soft_objective",
                            "seeds",
                        )
                    },
                    "steps": len(r.objective) - 1,
                    "seconds": r.seconds,
                    **{
                        f"{m}_change": v["reading"] if row["layout"] == "optimised" else ""
                        for m, v in r.verdict.items()
                    },
                }
            )
        ctx.number(f"layout:{key}:catchment_pct", [before["catchment_pct"], after["catchment_pct"]])
        ctx.number(f"layout:{key}:gt45_pct", [before["gt45_pct"], after["gt45_pct"]])
        layouts[key] = {
            "start": env_to_dict(r.start),
            "optimised": env_to_dict(r.optimised),
            "moved_cm": np.hypot(
                *(
                    np.asarray(r.optimised.landmarks)[np.asarray(r.optimised.valid), :2]
                    - np.asarray(r.start.landmarks)[np.asarray(r.start.valid), :2]
                ).T
            ).tolist(),
        }
        ctx.figure(
            f"layout_{name}{'_occlude' + str(k) if k else ''}.png",
            layout_figure(r, ctx.config.spacing),
            f"{name}, DELV{' with ' + str(k) + ' landmark(s) hidden' if k else ''}: the thesis's layout and the "
            "optimised one (catchment squares, vector map), and the soft objective per BFGS step.",
        )
        ctx.step(key)
    ctx.table(
        "layouts",
        "DELV on the thesis's layouts and on layouts optimised for it (ordinary evaluation)",
        rows,
        source="beyond the thesis",
        note="Landmarks move, radii stay; each stays r + 40 cm from home and pairs r_i + r_j + 20 cm apart. "
        "The objective is the soft loss smoothed at 5 cm on a 50 cm grid; the table is the ordinary evaluation, "
        "means over the seeds, with each change read against the seed-to-seed spread ('no change' where every "
        "seed gives the same number, as a catchment at 100 % does).",
        columns=[
            "env",
            "occlude",
            "layout",
            "hard_loss",
            "hard_loss_sd",
            "catchment_pct",
            "gt45_pct",
            "gt90_pct",
            "seeds",
            "hard_loss_change",
            "catchment_pct_change",
            "steps",
        ],
    )
    ctx.json("layouts.json", layouts)
