"""The sweeps of the `ensemble_rollouts` study and the claims keys their results become (docs/reproduce.md,
"Ensembles: step distance, success rates, quantization"); the `edge4` family of Fig 4.14b's layout, which
the library's families (`delvjax.envs.FAMILIES`) do not hold. Input preparation and plain NumPy on the
sweeps' Datasets; the array programs are the sweeps'."""

from __future__ import annotations

import dataclasses
import functools
import re

import numpy as np

from delvjax.core.scene import DEFAULT_ARENA, DEFAULT_HOME
from delvjax.core.sensor import Sensor
from delvjax.envs import FAMILIES, member_layouts
from delvjax.envs._ensembles import angular_gaps_deg
from delvjax.sweeps import SweepSpec, parse_sweep

from .quantization import EDGE4
from .step_distance import DS

LEVELS = (1, 2, 3, 5)  # the levels claim 12 reads (with continuous distances)
COMPASS = ("delv-compass", "acv", "alv")  # Fig 5.7b
DEFAULT_D = float(Sensor().d)  # cm: the unit movement of every other study (50)
LAYOUTS = ("env2", "ring3", "ring6", "edge4")  # Fig 4.14 at three levels: the surrounding layouts and edge4
RULE_CELLS = {  # (collisions, first_move) of the rules sweep -> key suffix (docs/model.md §5); the fourth cell unused
    ("ignore", "release"): "",
    ("fail", "release"): ":physical",
    ("ignore", "homing"): ":homing",
}

# --- edge4: home slightly outside the landmarks' hull (Fig 4.14b) --------------------------------------

# Fig 4.14b: "the home location is slightly outside the convex hull of the landmarks" (thesis §4.3, line 624),
# no coordinates. As the point run's edge4 (studies/runs/quantization.py), four landmarks; the family's rules are
# env3's (distances 150-350 cm, radii 15-50 cm, surfaces 20 cm apart, 20° off the unit move's line) with every
# bearing in one half plane (a 180° sector: home outside the hull of the centres), and "slightly": home outside
# the hull of the cylinders (its distance to the centres' hull exceeds the largest radius) by at most
# EDGE_SLIGHT_CM. Member i is the first of draws i * EDGE_BLOCK .. (i + 1) * EDGE_BLOCK - 1 that keeps it (a
# quarter of the draws does; none of 64 in a block: probability 1e-8). The point run's edge4 is a member (13 cm).
EDGE = dataclasses.replace(
    FAMILIES["env3"],
    name="edge4",
    sector_deg=180.0,
    description="four landmarks in one half plane, home slightly outside their hull",
    source="thesis §4.3 (line 624), Fig 4.14b: 'the home location is slightly outside the convex hull of the landmarks'",
)
EDGE_SLIGHT_CM = 50.0
EDGE_BLOCK = 64


def hull_gap_cm(layouts) -> np.ndarray:
    """(...,) the distance (cm) from home to the convex hull of the landmark centres of layouts (..., n, 3)
    whose home lies outside it: the nearest segment between two centres (the hull's edges are among them, and
    every segment lies inside it)."""
    p = np.asarray(layouts, float)[..., :2] - np.asarray(DEFAULT_HOME)
    i, j = np.triu_indices(p.shape[-2], 1)
    a, ab = p[..., i, :], p[..., j, :] - p[..., i, :]
    t = np.clip(-np.sum(a * ab, axis=-1) / np.maximum(np.sum(ab * ab, axis=-1), 1e-12), 0.0, 1.0)
    return np.asarray(np.hypot(*np.moveaxis(a + t[..., None] * ab, -1, 0)).min(axis=-1))


def edge_slightly_outside(layouts) -> np.ndarray:
    """(...,) whether home lies outside the cylinders' hull by at most EDGE_SLIGHT_CM (the family's own rule):
    outside the centres' hull (a gap of more than 180° between bearings seen from home) by more than the
    largest radius and by at most that plus EDGE_SLIGHT_CM."""
    xyr = np.asarray(layouts, float)
    rel = xyr[..., :2] - np.asarray(DEFAULT_HOME)
    outside = angular_gaps_deg(np.arctan2(rel[..., 1], rel[..., 0]), np).max(axis=-1) > 180.0
    gap = hull_gap_cm(xyr) - xyr[..., 2].max(axis=-1)
    return np.asarray(outside & (gap > 0) & (gap <= EDGE_SLIGHT_CM))


@functools.lru_cache(maxsize=4)
def edge_layouts(members: int, seed: int) -> np.ndarray:
    """(members, 4, 3) layouts of the edge4 family (member i from its own block of draws); read-only, kept for
    the run's slices (one draw of every block, not one per slice)."""
    drawn = member_layouts(EDGE, members * EDGE_BLOCK, seed).reshape(members, EDGE_BLOCK, EDGE.n, 3)
    ok = edge_slightly_outside(drawn)
    if not ok.any(axis=1).all():
        raise RuntimeError(f"edge4: no draw of a block of {EDGE_BLOCK} keeps home slightly outside the hull")
    out = drawn[np.arange(members), ok.argmax(axis=1)]
    out.setflags(write=False)
    return out


def world_dict(name: str, layout) -> dict:
    """A layout as a docs/model.md §7 dictionary (the default arena and home)."""
    return {
        "name": name,
        "arena": list(DEFAULT_ARENA),
        "home": list(DEFAULT_HOME),
        "landmarks": [{"x": float(x), "y": float(y), "r": float(r)} for x, y, r in np.asarray(layout)],
    }


def with_worlds(spec: SweepSpec, worlds: list[dict]) -> SweepSpec:
    """`spec` with `worlds` (docs/model.md §7 dictionaries) appended to its env axis, as the ensemble tables'
    members are (`run_sweep` validates every cell of them)."""
    envs = [*spec.axes["env"], *(w["name"] for w in worlds)]
    return dataclasses.replace(
        spec,
        axes={**spec.axes, "env": envs},
        ensemble_envs={**spec.ensemble_envs, **{w["name"]: w for w in worlds}},
    )


# --- the sweeps -----------------------------------------------------------------------------------------


def sweep_specs(
    count: int,
    first: int,
    seed: int,
    offset: int,
    spacing: float,
    trials: int,
    parts: tuple[str, ...],
    members: int | None = None,
) -> list[tuple[str, SweepSpec]]:
    """(name, spec) of the sweeps of one seed slice: members first .. first + count - 1 of the families (their
    layouts from `seed`), the built-in worlds beside them, every rollout and heading under seed + offset.
    `parts`: the sweeps to make (a full run: all of `SWEEPS`); `members`: the run's members of every slice (edge4's
    layouts drawn once for them; default first + count). Every sweep of one program has as many cells, so
    the slices and the sweeps share it (a chunk of another size compiles anew)."""
    s = seed + offset

    def envs(families: list[str]) -> str:
        tables = [f'{{ensemble = "{f}", members = {count}, first = {first}, seed = {seed}}}' for f in families]
        return "[" + ", ".join(tables + [f'"{f}"' for f in families]) + "]"

    env1 = envs(["env1"])
    catch = f'[sweep]\nkind = "catchment"\nmetrics = ["catchment_pct", "mean_error_deg"]\n[axes]\nenv = {env1}\n'
    success = f'[sweep]\nkind = "success-rate"\ntrials = {trials}\n[axes]\nenv = {env1}\n'
    tail = f"spacing = [{spacing}]\nseed = [{s}]\n"
    texts = {
        "steps": catch + f'method = ["delv"]\nd = {list(DS)}\n' + tail,
        "levels": catch + f'method = ["delv"]\nlevels = {list(LEVELS)}\n' + tail,
        "levels_success": success + f'method = ["delv"]\nlevels = {list(LEVELS)}\nseed = [{s}]\n',
        "rules_success": success
        + f'method = ["delv"]\ncollisions = ["ignore", "fail"]\nfirst_move = ["release", "homing"]\nseed = [{s}]\n',
        "compass_success": success + f"method = {_names(COMPASS)}\nseed = [{s}]\n",
        "warping_success": success + f'method = ["warping"]\nseed = [{s}]\n',
        "warping": catch + 'method = ["warping"]\n' + tail,
        "layouts": '[sweep]\nkind = "vector-map"\nmetrics = ["mean_error_deg"]\n[axes]\n'
        f'env = {envs(list(LAYOUTS[:-1]))}\nmethod = ["delv"]\nlevels = [3]\n' + tail,
    }
    out = []
    for name in parts:
        spec = parse_sweep(texts[name], f"ensemble_rollouts:{name}")
        if name == "layouts":  # edge4 has no library family: its members and built-in world join as dictionaries
            lay = edge_layouts(members or first + count, seed)[first:]
            edge = [world_dict(f"edge4-m{first + i}", lay[i]) for i in range(count)]
            spec = with_worlds(spec, edge + [world_dict("edge4", [(x, y, r) for x, y, r in EDGE4])])
        out.append((name, spec))
    return out


SWEEPS = (
    "steps",
    "levels",
    "levels_success",
    "rules_success",
    "compass_success",
    "warping_success",
    "warping",
    "layouts",
)


def _names(names) -> str:
    return "[" + ", ".join(f'"{n}"' for n in names) + "]"


# --- results -> the keys the claims read -------------------------------------------------------------


def world_label(env: str, offset: int) -> str:
    """A sweep's env label as the claims' world label: a member by family and index whatever the layouts' seed
    (`env1-s3-m5` -> `env1-m5`), a built-in world with `@<offset>` for a slice's seed offset beyond the first."""
    if re.search(r"-m\d+$", env):
        return re.sub(r"-s\d+-m(\d+)$", r"-m\1", env)
    return env if offset == 0 else f"{env}@{offset}"


def _cell(ds, **coords):
    """The cell at `coords`, selecting only the axes that are dimensions (an axis of one value is a scalar)."""
    return ds.sel({k: v for k, v in coords.items() if k in ds.dims})  # by a dict: any axis name is taken


def _values(ds, axis: str) -> list:
    return [v.item() if hasattr(v, "item") else v for v in np.atleast_1d(ds[axis].values)]


def _success(cell) -> tuple[list[float], float]:
    """(success % per release distance, overall success % of the placed trials) of one success-rate cell."""
    pct = np.asarray(cell["success_pct"].values, float)
    placed = np.asarray(cell["placed"].values, float)
    overall = float(100.0 * np.sum(np.round(pct * placed / 100.0)) / max(np.sum(placed), 1.0))
    return [float(v) for v in pct], overall


def sweep_numbers(name: str, ds, offset: int = 0) -> dict[str, dict]:
    """{world label: {claims key: value}} of one sweep's Dataset, under the keys the point runs record
    (studies/runs/step_distance.py, quantization.py, image_matching.py, comparators.py): `catchment:env1:delv
    :d=<d>` and `map:env1:delv:d=<d>:mean_error_deg` (d = 50 cm is also the default `catchment:env1:delv`,
    `...:continuous`), `catchment:env1:delv:Q<q>`, `success:env1:<method>[:Q<q>|:continuous][:physical|:homing]`
    (a list over the release distances) with `success_overall:...`, `catchment:env1:warping` and
    `map:<layout>:delv:Q3:mean_error_deg`."""
    out: dict[str, dict] = {}
    for env in _values(ds, "env"):
        nums: dict = {}
        at = lambda **c: _cell(ds, env=env, **c)  # noqa: E731, B023
        if name == "steps":
            for d in _values(ds, "d"):
                cell = at(d=d)
                catch, err = float(cell["catchment_pct"]), float(cell["mean_error_deg"])
                nums[f"catchment:env1:delv:d={d:g}"] = catch
                nums[f"map:env1:delv:d={d:g}:mean_error_deg"] = err
                if d == DEFAULT_D:  # the sensor's default d: the plain DELV of every other claim
                    for tag in ("", ":continuous"):
                        nums[f"catchment:env1:delv{tag}"] = catch
                        nums[f"map:env1:delv{tag}:mean_error_deg"] = err
        elif name == "levels":
            for q in _values(ds, "levels"):
                cell = at(levels=q)
                nums[f"catchment:env1:delv:Q{q:g}"] = float(cell["catchment_pct"])
                nums[f"map:env1:delv:Q{q:g}:mean_error_deg"] = float(cell["mean_error_deg"])
        elif name == "levels_success":
            for q in _values(ds, "levels"):
                nums[f"success:env1:delv:Q{q:g}"], nums[f"success_overall:env1:delv:Q{q:g}"] = _success(at(levels=q))
        elif name == "rules_success":
            for (collisions, first_move), tail in RULE_CELLS.items():
                by, overall = _success(at(collisions=collisions, first_move=first_move))
                for tag in ("", ":continuous"):
                    nums[f"success:env1:delv{tag}{tail}"], nums[f"success_overall:env1:delv{tag}{tail}"] = by, overall
        elif name in ("compass_success", "warping_success"):
            for m in _values(ds, "homing_method"):  # the axis `method` (docs/sweeps.md)
                nums[f"success:env1:{m}"], nums[f"success_overall:env1:{m}"] = _success(at(homing_method=m))
        elif name == "warping":
            cell = at()
            nums["catchment:env1:warping"] = float(cell["catchment_pct"])
            nums["map:env1:warping:mean_error_deg"] = float(cell["mean_error_deg"])
        elif name == "layouts":
            family = str(env).rsplit("-", 1)[0] if re.search(r"-m\d+$", str(env)) else str(env)
            family = re.sub(r"-s\d+$", "", family)
            nums[f"map:{family}:delv:Q3:mean_error_deg"] = float(at()["mean_error_deg"])
        else:
            raise ValueError(f"ensemble_rollouts: no sweep {name!r}")
        out.setdefault(world_label(str(env), offset), {}).update(nums)
    return out
