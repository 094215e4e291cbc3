"""The fit's thesis targets, its objective and its search (the `fit` study; docs/reproduce.md "The
fit of the unstated settings").

Targets: every number the thesis prints in Figs 4.5, 5.5, 5.10 (catchment %) and Tables 5.1-5.2
(error point rates e > 45° and e > 90°, %) and 5.3-5.4 (catchment %, k = 0..3 hidden landmarks),
read from `delvjax.studies.thesis`. The thesis's L = 4 rows of Tables 5.2 and 5.4 copy rows of Tables
5.1/5.3 (env1's for DELV and ACV, env2's for ALV; `thesis.NOTES`), so they are no result of their
own and are left out. Fig 5.10's caption disagrees with Table 5.3 for k = 1, 2 (docs/model.md §6):
both stay in, as the thesis prints both, so no setting can reach both.

Objective: mean |ours - thesis| over the targets (percentage points), overall (every target counts
once) and per figure / table. Search: one setting at a time around the defaults, then a small
factorial over the settings with the largest effect (`search`). Plain NumPy: no JAX here.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from collections.abc import Callable

import numpy as np

from .. import thesis

TABLES = {
    "fig4_5": "Fig 4.5",
    "fig5_5": "Fig 5.5",
    "fig5_10": "Fig 5.10",
    "table5_1": "Table 5.1",
    "table5_2": "Table 5.2",
    "table5_3": "Table 5.3",
    "table5_4": "Table 5.4",
}
COPIED = {"ring4"}  # the thesis's L = 4 rows copy other rows (thesis.NOTES): no result of their own
FIELDS = ("gt45", "gt90")  # error point rates of Tables 5.1/5.2


@dataclass(frozen=True)
class Target:
    """One thesis number: table key (TABLES), environment, method, k hidden landmarks, field
    ("catchment", "gt45" or "gt90") and the printed value (%)."""

    table: str
    env: str
    method: str
    k: int
    field: str
    value: float

    @property
    def cell(self) -> tuple[str, str, int]:
        """(env, method, k): the rollout cell whose metric this target reads."""
        return self.env, self.method, self.k


def targets(tables=tuple(TABLES), envs: tuple[str, ...] | None = None) -> list[Target]:
    """The thesis numbers of `tables` (only `envs` if given), in thesis order; ring4 left out (COPIED)."""
    out = []
    for table in tables:
        if table in thesis.CATCHMENT:
            rows = [
                (e, m, k, "catchment", v)
                for e, ms in thesis.CATCHMENT[table].items()
                for m, values in ms.items()
                for k, v in enumerate(values)
            ]
        else:
            rows = [
                (e, m, k, f, v)
                for e, ms in thesis.ERROR_POINTS[table].items()
                for m, fields in ms.items()
                for f in FIELDS
                for k, v in enumerate(fields[f])
            ]
        out += [
            Target(table, e, m, k, f, float(v))
            for e, m, k, f, v in rows
            if e not in COPIED and (envs is None or e in envs)
        ]
    return out


def cells(items: list[Target]) -> list[tuple[str, str, int]]:
    """The distinct (env, method, k) cells the targets read, in first-use order."""
    return list(dict.fromkeys(t.cell for t in items))


def align(values: dict[str, np.ndarray], cell_list: list[tuple[str, str, int]], items: list[Target]) -> np.ndarray:
    """Our number for each target, (S, T): `values[field]` is (S, C) over the S settings and the
    cells of `cell_list` (fields "catchment", "gt45", "gt90")."""
    index = {c: i for i, c in enumerate(cell_list)}
    return np.stack([np.asarray(values[t.field])[:, index[t.cell]] for t in items], axis=1)


def objective(ours: np.ndarray, items: list[Target]) -> dict[str, np.ndarray]:
    """Mean |ours - thesis| (percentage points) for each of S settings: {"overall": (S,), table: (S,)}
    over the targets of each table present. `ours`: (S, T) aligned with `items` (or (T,))."""
    ours = np.atleast_2d(np.asarray(ours, float))
    gap = np.abs(ours - np.array([t.value for t in items])[None, :])
    tables = np.array([t.table for t in items])
    out = {"overall": gap.mean(axis=1)}
    for table in TABLES:
        sel = tables == table
        if sel.any():
            out[table] = gap[:, sel].mean(axis=1)
    return out


# --- the search ------------------------------------------------------------------------------

Setting = tuple[tuple[str, float], ...]  # (name, value) pairs in the grid's order: hashable


def point_key(point: dict, names) -> Setting:
    return tuple((n, float(point[n])) for n in names)


@dataclass
class SearchResult:
    """Every evaluated point with its stage and objective, the fitted (best evaluated) point, and per
    setting the stage-1 objective of each value (`profiles`, name -> [(value, objective)])."""

    evaluated: list[dict] = field(default_factory=list)  # {"stage", "point", "objective"}
    fitted: dict = field(default_factory=dict)
    default: dict = field(default_factory=dict)
    profiles: dict = field(default_factory=dict)
    joint: tuple[str, ...] = ()


def search(
    evaluate: Callable[[list[dict]], list[float]], grid: dict[str, tuple], default: dict, top: int = 2, values: int = 2
) -> SearchResult:
    """Fit the settings of `grid` (name -> values tried; `default` holds every name's default).

    1. One setting at a time: the defaults, then each value of each setting with the others at their
       defaults (one `evaluate` call: a list of points -> their objectives).
    2. Joint: the centre takes each setting's best stage-1 value where it beats the default. The
       `top` settings with the largest effect (the most stage-1 improvement on the defaults, then the
       widest range of the objective over their values) take each of their `values` best stage-1
       values in every combination (a small factorial, the others at the centre): one more call.
    The fitted point is the best point evaluated, so its objective is measured, never extrapolated.
    """
    names = list(grid)
    res = SearchResult(default=dict(default))
    seen: dict[Setting, float] = {}

    def run(stage: str, points: list[dict]) -> None:
        fresh = list({point_key(p, names): p for p in points if point_key(p, names) not in seen}.values())
        if not fresh:
            return
        for p, obj in zip(fresh, evaluate(fresh)):  # one batch: one call of the evaluator
            seen[point_key(p, names)] = float(obj)
            res.evaluated.append({"stage": stage, "point": dict(p), "objective": float(obj)})

    one_at_a_time = [dict(default)] + [{**default, n: v} for n in names for v in grid[n] if v != default[n]]
    run("one at a time", one_at_a_time)
    base = seen[point_key(default, names)]
    for n in names:
        res.profiles[n] = sorted((float(v), seen[point_key({**default, n: v}, names)]) for v in {*grid[n], default[n]})
    centre = dict(default)
    for n in names:
        v, obj = min(res.profiles[n], key=lambda p: p[1])
        if obj < base:
            centre[n] = v
    gain = {n: base - min(o for _, o in res.profiles[n]) for n in names}
    spread = {n: max(o for _, o in res.profiles[n]) - min(o for _, o in res.profiles[n]) for n in names}
    res.joint = tuple(n for n in sorted(names, key=lambda n: (-gain[n], -spread[n])) if len(res.profiles[n]) > 1)[:top]
    choices = [[v for v, _ in sorted(res.profiles[n], key=lambda p: p[1])[:values]] for n in res.joint]
    run("joint", [dict(centre)] + [{**centre, **dict(zip(res.joint, combo))} for combo in itertools.product(*choices)])
    best = min(seen, key=lambda k: seen[k])
    res.fitted = dict(best)
    return res


def describe(point: dict, default: dict) -> str:
    """The settings of `point` that differ from `default`, e.g. "bearing_noise_deg=1, home_radius=25"."""
    changed = [f"{n}={point[n]:g}" for n in point if float(point[n]) != float(default[n])]
    return ", ".join(changed) or "defaults"
