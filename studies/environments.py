"""Draw the built-in environments and write their SPEC §7 JSON files (README's environment table).

Run: python -m studies.environments --out docs
"""

from __future__ import annotations

import argparse

import delvjax
from delvjax.io import save_figure, write_json
from delvjax.plots import environments_figure
from delvjax.scene import PRESETS, env_to_dict


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--out", default="docs")
    a = p.parse_args(argv)
    envs = [delvjax.load_env(n) for n in PRESETS]
    save_figure(environments_figure(envs), f"{a.out}/environments.png", dpi=110)
    for env in envs:
        write_json(f"{a.out}/envs/{env.name}.json", env_to_dict(env))
    print(f"wrote {a.out}/environments.png and {len(envs)} JSON files in {a.out}/envs/")


if __name__ == "__main__":
    main()
