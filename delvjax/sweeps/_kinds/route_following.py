"""The route-following kind of sweep (docs/sweeps.md "Route-following sweeps"; docs/familiarity.md §3.2): each
cell a familiarity model (the `method` axis: perfect-memory, infomax, mushroom-body) trained on a route through a
colour world (the `env` axis: robot, natural, or any environment as red cylinders) and `trials` route-following
trials (Ardin et al. 2016) from the route's start (`core.familiarity.cells.following_cells`). Cells are validated
as `delvjax.route_experiments` validates its keywords (`familiarity._setup.following_setup`), and a cell's
numbers are that call's trials, number for number. Beyond the thesis."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

import jax
import numpy as np

from ...core import metrics as table
from ...core.errors import InputError
from ...core.familiarity.cells import FollowingCell, FollowingSums, following_cells
from ...core.rollouts.success import wilson_pct
from ...familiarity._models import SETTINGS
from ...familiarity._routes import view_source
from ...familiarity._setup import following_setup
from ...images._worlds import BUILT_IN, ImageWorld, env_world, image_world
from ...mesh._site import MeshSite, is_mesh_name, mesh_site
from .base import Sweep, SweepKind, descriptions, options, pct

RUN_AXES = {
    "heading_noise_deg": "heading noise added at every move, deg (sigma of a normal; default 10)",
    "route_spacing": "cm between route images (default 4)",
    "step": "cm a move (default: the route spacing)",
    "view_rows": "rows of a view (default 10; 19 in a mesh world)",
    "view_cols": "columns of a view, dividing 360 (default 90)",
    "max_steps": "moves before a trial times out (default 2.1 route lengths)",
}
MODEL_AXES = {  # every model's settings (docs/familiarity.md §2): an axis applies to its model's cells only
    name: f"{', '.join(m for m, s in SETTINGS.items() if name in s)} setting (default {default})"
    for settings in SETTINGS.values()
    for name, default in settings.items()
}
UNITS = {"heading_noise_deg": "degree", "route_spacing": "cm", "step": "cm"}


def following_world(name: str, environment: Callable[[str], object]) -> ImageWorld | MeshSite:
    """An `env` axis value as a world: a built-in image world or a generated mesh habitat (`habitat<seed>`) by
    name, else the environment the landmark kinds would read (`environment(name)`: preset, JSON file, random or
    ensemble member) as red cylinders."""
    if name in BUILT_IN:
        return image_world(name)
    if is_mesh_name(name):
        return mesh_site(name)
    try:
        return env_world(environment(name))
    except InputError as exc:
        raise InputError(
            "env", name, f"is no image world ({', '.join(BUILT_IN)}) nor habitat<seed>, and {exc.expected}"
        ) from None


class RouteFollowing(SweepKind):
    """Route-following success of a familiarity model per cell."""

    name = "route-following"
    metrics = descriptions(table.FOLLOWING_METRICS)
    grid, rollouts, per_distance = False, False, False
    sums = FollowingSums
    own_cells = True
    own_axes = {**RUN_AXES, **MODEL_AXES}
    text_axes = tuple(k for s in SETTINGS.values() for k, v in s.items() if isinstance(v, str))
    defaults = {"env": ["robot"], "method": ["perfect-memory"], "seed": [0]}
    default_trials = 20
    units = UNITS

    def environments(self, names: Sequence[str], environment: Callable[[str], object]) -> dict:
        return {name: following_world(name, environment) for name in names}

    def request(self, env, cell: dict, spec: Sweep, max_points: int, method_set: Sequence[str] | None = None) -> dict:
        s = following_setup(env, cell["method"], seed=cell["seed"], trials=spec.trials, **options(cell))
        key = np.asarray(jax.random.key_data(jax.random.key(s.settings["seed"])))
        return {"model": s.trained, "source": view_source(env, s.camera), "route": s.route.route,
                "rules": s.rules, "key": key, "trials": s.settings["trials"]}  # fmt: skip

    def traced(self, req: dict, mask_rows: int = 1) -> tuple:
        cell = FollowingCell(req["model"], req["source"], req["route"], req["rules"], req["key"], np.bool_(True))
        return (cell,)

    def group_key(self, req: dict) -> tuple:
        """Cells with one pytree structure (models and rules with equal static settings), equal leaf shapes (one
        world layout, route length and view size) and equal trials share a program."""
        leaves, treedef = jax.tree.flatten(self.traced(req))
        return treedef, tuple((np.shape(x), np.asarray(x).dtype.str) for x in leaves), req["trials"]

    def idle_padding(self, stacked: tuple, real: int | None) -> tuple:
        cell = stacked[0]
        rows = len(np.asarray(cell.live))
        live = np.arange(rows) < (rows if real is None else real)
        return (dataclasses.replace(cell, live=live),)

    def inputs(self, setups: list[dict], traced: tuple) -> tuple[tuple, tuple]:
        return (), traced

    def program(self, lanes: int, trials: int | None) -> Callable:
        return lambda cells: following_cells(cells, trials)

    def metrics_of(self, sums: dict) -> dict:
        n = sums["trials"]
        lo, hi = wilson_pct(sums["successes"], n)
        with np.errstate(invalid="ignore", divide="ignore"):
            per = lambda x: np.where(n > 0, x / np.maximum(n, 1), np.nan)  # noqa: E731
        return {
            "route_success_pct": pct(sums["successes"], n),
            "route_success_ci95_lo_pct": lo,
            "route_success_ci95_hi_pct": hi,
            "mean_route_errors": per(sums["errors"]),
            "mean_moves": per(sums["moves"]),
            "trials_run": n.astype(np.int64),
        }

    def cell_seconds(self, spec: Sweep) -> float:
        """A trial of the robot route: about 25 moves of 3 ms, and the model's training; of a habitat's 8 m route
        about 200 moves, each a mesh view rendered (8 trials side by side: 15 moves a second)."""
        envs = spec.axes.get("env", self.defaults["env"])
        mesh = sum(isinstance(e, str) and is_mesh_name(e) for e in envs) / max(len(envs), 1)
        return spec.trials * (0.1 * (1 - mesh) + 1.7 * mesh)


ROUTE_FOLLOWING = RouteFollowing()
