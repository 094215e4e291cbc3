"""The built-in environments (thesis §4.2, §5.3.1; docs/environments.png and docs/envs/*.json).

Run `python -m delvjax.studies.runs.environments --out docs` to redraw the figure and JSON files in docs/.
"""

from __future__ import annotations

import argparse
import math

import delvjax
from delvjax.envs import PRESET_DESCRIPTIONS, PRESETS, env_to_dict
from delvjax.outputs import write_figure, write_json
from delvjax.plots import environments_figure

TITLE = "The environments (thesis §4.2 and Tables 5.1-5.4)"
COST = 1  # rough seconds of a full run (2 CPU cores, two studies side by side): the longest start first
STEPS = 1


def layout_rows() -> list[dict]:
    """Per landmark of every preset: bearing and distance from home."""
    rows = []
    for name in PRESETS:  # seven presets: tabulation
        d = env_to_dict(delvjax.load_env(name))
        hx, hy = d["home"]
        for i, lm in enumerate(d["landmarks"]):
            rows.append(
                {
                    "env": name,
                    "landmark": i,
                    "x": lm["x"],
                    "y": lm["y"],
                    "r": lm["r"],
                    "bearing from home °": math.degrees(math.atan2(lm["y"] - hy, lm["x"] - hx)) % 360,
                    "distance from home cm": math.hypot(lm["x"] - hx, lm["y"] - hy),
                }
            )
    return rows


def run(ctx) -> None:
    envs = [delvjax.load_env(n) for n in PRESETS]
    ctx.figure(
        "environments.png",
        environments_figure(envs),
        "The built-in environments: arena 1000 x 1000 cm, home (black square) at (500, 500). "
        + "; ".join(f"{n}: {PRESET_DESCRIPTIONS[n]}" for n in ("env1", "env2", "env3"))
        + ".",
    )
    ctx.table(
        "landmarks",
        "Landmarks of the built-in environments",
        layout_rows(),
        note="The thesis gives no coordinates; ours follow its descriptions (docs/env1.md explains env1). "
        "ring4 and env2 are the same layout (four landmarks 250 cm from home at 45/135/225/315°).",
    )
    for e in envs:
        ctx.json(f"envs/{e.name}.json", env_to_dict(e))
    ctx.step("environments")


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--out", default="docs")
    a = p.parse_args(argv)
    envs = [delvjax.load_env(n) for n in PRESETS]
    write_figure(environments_figure(envs), f"{a.out}/environments.png", dpi=110)
    for e in envs:
        write_json(f"{a.out}/envs/{e.name}.json", env_to_dict(e))
    print(f"wrote {a.out}/environments.png and {len(envs)} JSON files in {a.out}/envs/")


if __name__ == "__main__":
    main()
