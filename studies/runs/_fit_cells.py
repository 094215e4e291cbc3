"""The fit's rollouts: every (setting, environment, method, k) as one cell of a catchment sweep
(docs/sweeps.md "One program per shape"), all cells of the fit in ONE compiled program.

A cell is validated and built by the sweep machinery (`sweep_kinds.cell_setup`, the validation of
`delvjax.catchment`) and evaluated by `sweep_kinds.evaluate` (`core.rollouts.cells.catchment_cells`,
a `lax.map` over the stacked cells); the metrics are the sweep's (`sweep_results.catchment_metrics`):
catchment % and error point rates of the first directions, pooled over the C(N, k) masks (the
mean over the choices of hidden landmarks, as the occlusion study reports, thesis §5.3.1). One
program serves every cell because
  * the four methods are one `Program` (`registry.program`: a traced index picks the method),
  * every environment is padded to `common.PAD` slots (the landmark radius scale only changes
    numbers),
  * the settings are traced leaves (noise sigmas and the reference heading alpha_r of the
    `Sensor`, docs/model.md §1, §2.5; the home radius of the rollout cell) and the masks are
    padded to the most of any cell,
  * every call stacks the same number of cells (the last chunk is padded with copies).
Settings beyond the sweep file's axes (alpha_r_deg, the landmark radius scale) are the same
public options (`delvjax.catchment`'s alpha_r_deg) and environments, so no sweep file can hold
them; the cells are built here instead of from a `SweepSpec`'s product.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from delvjax.core.sensor import Sensor
from delvjax.options._limits import MAX_POINTS
from delvjax.envs._presets import env_from_dict, env_to_dict
from delvjax.options._registry import program
from delvjax.sweeps._kinds import cell_setup, evaluate, group_key, mask_rows, programs_compiled
from delvjax.sweeps._results import catchment_metrics
from delvjax.sweeps._spec import SweepSpec

from ._common import HOME_RADIUS, PAD, RULES, env

METHODS = ("delv", "delv-compass", "acv", "alv")  # the methods of Figs 4.5, 5.5, 5.10, Tables 5.1-5.4
SENSOR_SETTINGS = ("bearing_noise_deg", "step_noise", "odometry_turn_noise_deg", "alpha_r_deg")
RADIUS_SCALE = "landmark_radius_scale"
DEFAULTS = {
    "bearing_noise_deg": 0.0,
    "step_noise": 0.0,
    "odometry_turn_noise_deg": 0.0,
    "home_radius": HOME_RADIUS,
    "alpha_r_deg": math.degrees(Sensor().alpha_r),
    RADIUS_SCALE: 1.0,
}
"""The settings the thesis does not give, at the project's defaults (docs/model.md §1, §2.5, §5, §6):
noise-free sensing and odometry, `common.HOME_RADIUS`, the home unit move along alpha_r = 0, the
landmark radii of docs/envs (scale 1)."""
FIELD = {"catchment": "catchment_pct", "gt45": "gt45_pct", "gt90": "gt90_pct"}
_SPEC = SweepSpec(kind="catchment", axes={}, metrics=list(FIELD.values()), text="")  # kind, for cell_setup


def scaled_env(name: str, scale: float):
    """The layout `name` padded to `common.PAD` slots with every landmark radius times `scale`
    (validated as a docs/model.md §7 environment: no overlap, inside the arena, clear of home)."""
    if scale == 1.0:
        return env(name)
    spec = env_to_dict(env(name))
    spec["landmarks"] = [{**lm, "r": lm["r"] * scale} for lm in spec["landmarks"]]
    return env_from_dict(spec, pad_to=PAD)


def env_key(name: str, scale: float) -> str:
    return name if scale == 1.0 else f"{name}@r{scale:g}"


def cell(point: dict, target_cell: tuple[str, str, int], spacing: float, seed: int, methods: dict) -> dict:
    """The sweep cell of one (env, method, k) under the settings `point` (default rollout rules)."""
    name, method, k = target_cell
    return {
        "env": env_key(name, float(point[RADIUS_SCALE])),
        "method": methods[method],
        "seed": seed,
        "occlude": k,
        "spacing": spacing,
        "home_radius": float(point["home_radius"]),
        **RULES["default"],
        **{s: float(point[s]) for s in SENSOR_SETTINGS},
    }


class Evaluator:
    """Runs lists of settings points on the cells `cell_list`; keeps the time, cells, trials and
    programs compiled of every call (the study's cost table)."""

    def __init__(
        self,
        cell_list: list[tuple[str, str, int]],
        spacing: float,
        seed: int,
        step: Callable[[str], None] | None = None,
    ):
        self.cell_list, self.spacing, self.seed, self.step = cell_list, spacing, seed, step
        self.methods = {m: program(m, METHODS)[0] for m in METHODS}
        self.envs: dict = {}
        self.seconds, self.cells, self.trials, self.points = 0.0, 0, 0, 0
        self.programs = 0
        self.rows = 1
        for name, _, k in cell_list:  # the most masks of any cell: one program for every k
            self.rows = max(self.rows, math.comb(env(name).n_landmarks, k))

    def __call__(self, points: list[dict]) -> dict[str, np.ndarray]:
        """Metrics "catchment", "gt45", "gt90" (%), each (len(points), len(cell_list))."""
        t0, compiled = time.perf_counter(), programs_compiled()
        for p in points:
            for name in dict.fromkeys(c[0] for c in self.cell_list):
                k = env_key(name, float(p[RADIUS_SCALE]))
                if k not in self.envs:
                    self.envs[k] = scaled_env(name, float(p[RADIUS_SCALE]))
        cells = [cell(p, c, self.spacing, self.seed, self.methods) for p in points for c in self.cell_list]
        setups = [cell_setup(_SPEC, self.envs, c, MAX_POINTS) for c in cells]
        rows = max(self.rows, *(mask_rows(s) for s in setups))
        width = len(self.cell_list)  # cells per call: one settings point (every call the same shape)
        groups: dict = {}
        for i, s in enumerate(setups):
            groups.setdefault(group_key(s), []).append(i)
        sums: dict[str, np.ndarray] = {}
        for members in groups.values():  # one group: every cell shares the program (module docstring)
            for start in range(0, len(members), width):  # a handful of chunks, one call each
                chunk = members[start : start + width]
                batch = [setups[i] for i in chunk] + [setups[chunk[0]]] * (width - len(chunk))
                res = evaluate(_SPEC.kind, batch, None, rows)
                for name, v in res.items():
                    sums.setdefault(name, np.zeros(len(setups), v.dtype))[chunk] = v[: len(chunk)]
                if self.step is not None:
                    self.step(f"fit: {start + len(chunk)}/{len(members)} cells")
        metrics = catchment_metrics(sums)
        shape = (len(points), len(self.cell_list))
        self.seconds += time.perf_counter() - t0
        self.cells += len(cells)
        self.trials += int(sums["trials"].sum())
        self.points += len(points)
        self.programs += programs_compiled() - compiled
        return {f: np.asarray(metrics[m], float).reshape(shape) for f, m in FIELD.items()}
