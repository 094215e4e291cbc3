"""The design of the `ensemble_settings` study: the unstated settings and their values, their full factorial,
and the rollouts of every (combination, world, member, method, k) as cells of one compiled catchment program
(docs/reproduce.md "Which settings the thesis's numbers imply").

Every combination of bearing noise, home radius and odometry noise is run (4 x 3 x 2 = 24 runs); the rule set
costs no rollouts: every cell runs under `collisions = "ignore"` and its catchment is restated under the
physical rules from the same trials (`catchment_physical_pct`, docs/sweeps.md), so each run is two
combinations (48). A cell is one of a catchment sweep's (validated by `sweeps._kinds.cell_setup`, run by
`sweeps._kinds.evaluate`); the cells are listed here, not from a sweep file's product, because DELV without a
compass is needed at k = 0 only and each member runs under its own seed: every cell of the study is one
program (the four methods one `MethodSet`, the worlds padded alike, the settings traced leaves)."""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np

from delvjax.core.checks import SEED_LIMIT
from delvjax.envs import ensemble_envs, env_from_dict
from delvjax.options import MAX_POINTS, method_set
from delvjax.sweeps import SweepSpec
from delvjax.sweeps._kinds import catchment_metrics, cell_setup, evaluate

from ._ensemble_stats import thesis_numbers

FAMILIES = ("env1", "env2", "env3")  # ring4's thesis rows copy other rows (docs/model.md §6): left out
METHODS = ("delv", "delv-compass", "acv", "alv")  # the methods of Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3
# (method, hidden landmarks) of every thesis number on env1-3: DELV without a compass only at k = 0 (Fig 4.5)
PAIRS = (("delv", 0),) + tuple((m, k) for m in METHODS[1:] for k in (0, 1, 2))
SLOTS = 4  # landmark slots: env1-3 have four
MASK_ROWS = 6  # C(4, 2): the most visibility masks of any cell (every cell padded to it: one program)
CHUNK = 64  # cells per call of the program (the last chunk padded with copies)
RULES = ("ignore", "fail")  # collisions under the default rules and the physical ones (docs/model.md §5)

# setting -> (name, values, unit); the first value of each is the project's default (docs/model.md §2.5, §5).
# Odometry noise is one setting: none, or the move's length (sigma 0.1 d) and the reported turn (sigma 3°)
# noisy together (the values the old fit tried one at a time). The rules: the default (landmarks are no
# obstacles) or the physical ones (a move ending inside a landmark fails); both with Algorithm 2's first move
SETTINGS = {
    "bearing_noise_deg": ("bearing noise", (0.0, 1.0, 2.0, 3.0), "°"),
    "home_radius": ("home radius", (50.0, 25.0, 75.0), " cm"),
    "odometry": ("odometry noise", ("none", "step 0.1 d, turn 3°"), ""),
    "rules": ("rules", ("default", "physical"), ""),
}
ODOMETRY = {
    "none": {"step_noise": 0.0, "odometry_turn_noise_deg": 0.0},
    "step 0.1 d, turn 3°": {"step_noise": 0.1, "odometry_turn_noise_deg": 3.0},
}
_SPEC = SweepSpec(kind="catchment", axes={}, metrics=["catchment_pct"], text="")  # the kind, for cell_setup


def design(runs: list[tuple[int, ...]] | None = None) -> np.ndarray:
    """(C, 4) value indices into SETTINGS (in its order) of every combination: every run (value indices of the
    settings but the rule set: the full factorial, or the `runs` given) under each rule set, the default rules
    first. Combination 0 is every default."""
    sizes = [len(v[1]) for n, v in SETTINGS.items() if n != "rules"]
    runs = list(itertools.product(*map(range, sizes))) if runs is None else runs
    return np.array([(*r, rule) for r in runs for rule in range(len(RULES))], int)


def combination(levels) -> dict:
    """{setting: value} of one row of `design`."""
    return {name: SETTINGS[name][1][int(i)] for name, i in zip(SETTINGS, levels)}


def sweep_settings(levels) -> dict:
    """The sweep cell's settings of one row of `design` (odometry noise as its two sigmas, the rules as
    `collisions`)."""
    c = combination(levels)
    odometry = ODOMETRY[c.pop("odometry")]
    rules = SETTINGS["rules"][1].index(c.pop("rules"))
    return {**c, **odometry, "collisions": RULES[rules]}


def member_seed(seed: int, i: int) -> int:
    """Member i runs under the run's seed + i: every member its own release headings and noise draws, the
    same in every combination (the combinations are compared on the same draws)."""
    return (seed + i) % SEED_LIMIT


def rollouts(
    runs: np.ndarray,
    members: int,
    spacing: float,
    seed: int,
    lanes: int,
    tick: Callable[[int], None] | None = None,
) -> dict[str, np.ndarray]:
    """Every cell of the rows `runs` (R, 4) of `design` under the default rules (their physical twins are
    restated from the same trials): "catchment", "catchment_physical", "gt45", "gt90" (%), each (R, F, M, P)
    over FAMILIES, members and PAIRS. `tick(runs done)` after each chunk that completes a row."""
    methods = {m: method_set(m, METHODS)[0] for m in METHODS}
    envs = {}
    for fam in FAMILIES:  # layouts from the run's seed: the members of the ensembles study
        for i, spec in enumerate(ensemble_envs(fam, members, seed)):
            envs[(fam, i)] = env_from_dict(spec, pad_to=SLOTS)
    keys = {f"{fam}-m{i}": e for (fam, i), e in envs.items()}
    cells = [
        {
            "env": f"{fam}-m{i}",
            "method": methods[m],
            "seed": member_seed(seed, i),
            "occlude": k,
            "spacing": spacing,
            "first_move": "release",
            **{**sweep_settings(levels), "collisions": "ignore"},
        }
        for levels in runs
        for fam in FAMILIES
        for i in range(members)
        for m, k in PAIRS
    ]
    setups = [cell_setup(_SPEC, keys, c, MAX_POINTS) for c in cells]  # input preparation, one small pytree each
    per_run = len(cells) // max(len(runs), 1)
    sums: dict[str, np.ndarray] = {}
    done = 0
    for start in range(0, len(setups), CHUNK):  # one program, every call the same shape
        chunk = setups[start : start + CHUNK]
        res = evaluate(_SPEC.kind, chunk + [chunk[0]] * (CHUNK - len(chunk)), None, MASK_ROWS, lanes=lanes)
        for name, v in res.items():
            sums.setdefault(name, np.zeros((len(setups),) + v.shape[1:], v.dtype))[start : start + len(chunk)] = v[
                : len(chunk)
            ]
        now = (start + len(chunk)) // per_run
        if tick is not None and now > done:
            tick(now)
            done = now
    metrics = catchment_metrics(sums)
    shape = (len(runs), len(FAMILIES), members, len(PAIRS))
    fields = {"catchment": "catchment_pct", "catchment_physical": "catchment_physical_pct"}
    fields |= {"gt45": "gt45_pct", "gt90": "gt90_pct"}
    return {f: np.asarray(metrics[m], float).reshape(shape) for f, m in fields.items()}


def targets() -> list[tuple]:
    """The thesis numbers the design makes: (source, family, method, k, quantity, value) of
    `_ensemble_stats.thesis_numbers` on FAMILIES."""
    return [r for r in thesis_numbers() if r[1] in FAMILIES and (r[2], r[3]) in PAIRS]


def numbers(values: dict[str, np.ndarray], items: list[tuple]) -> np.ndarray:
    """(C, N, M): our value of each thesis number of `items` (`targets`) in every combination (rows of
    `design`: each run under each rule set) and member; a catchment under the physical rules is the restated
    one, the error point rates are the same trials' under both."""
    runs, _, members, _ = values["gt45"].shape
    out = np.zeros((runs, len(RULES), len(items), members))
    for n, (_, fam, method, k, q, _) in enumerate(items):  # a few hundred numbers: indexing, no arithmetic
        f, p = FAMILIES.index(fam), PAIRS.index((method, k))
        for r, rule in enumerate(RULES):
            field = f"{q}_physical" if q == "catchment" and rule == "fail" else q
            out[:, r, n, :] = values[field][:, f, :, p]
    return out.reshape(runs * len(RULES), len(items), members)
