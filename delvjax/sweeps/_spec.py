"""Sweep files (TOML, `tomllib`): axes, metrics, validation before any work (docs/sweeps.md)."""

from __future__ import annotations

import itertools
import math
import tomllib
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from ..core.errors import InputError, did_you_mean, is_finite_number
from ..core.rollouts.rules import DEFAULT_DISTANCES, TRIALS_PER_DISTANCE
from ..envs._ensembles import FAMILIES
from ..envs._ensembles import ensemble_envs as ensemble_envs_of
from ..options._schema import ROLLOUT_ONLY, all_options, upgraded
from ._kinds import KINDS, SweepKind

# axis -> what it sets (the public option of `delvjax.vector_map` / `catchment` / `success_rate` of the same name).
# Besides these, every setting declared on the modules is an axis (`options._schema`; read when a file is
# parsed, so that a method registered later brings its settings): see `axes(kind)`.
SCENE_AXES = {
    "env": "environment: preset name, JSON path, {random = COUNT, landmarks = N | [N, ...], seed = S} or "
    "{ensemble = FAMILY, members = COUNT, seed = S, factor = F, first = I}",
    "method": "registry name",
    "spacing": "grid spacing, cm",
    "seed": "seed of headings, release points and noise, 0..2^32-1",
}
ROLLOUT_AXES = {
    "occlude": "landmarks hidden while homing: every choice of k (the metrics pool the C(N, k) masks)",
    "first_move": "release | homing (rollout rule, docs/model.md section 5)",
    "collisions": "ignore | fail (rollout rule)",
    "home_radius": "success radius, cm",
    "max_steps": "moves before a trial times out",
}


def setting_axes() -> dict[str, str]:
    """Every declared setting (method, sensor, noise) as an axis: name -> what it sets."""
    return {name: opt.help for name, opt in all_options().items()}


def axes(kind: SweepKind) -> dict[str, str]:
    """The axes of a kind of sweep: name -> what it sets (no `spacing` without a grid; the rollout
    axes and the motion noise only for rollouts)."""
    if kind.own_axes is not None:  # route following: its worlds, models and settings (docs/sweeps.md)
        scene = {k: v for k, v in SCENE_AXES.items() if k != "spacing"}
        scene["env"] = "colour world: robot, natural, or an environment as for the other kinds (red cylinders)"
        scene["method"] = "familiarity model: perfect-memory, infomax or mushroom-body"
        return {**scene, **kind.own_axes}
    settings = setting_axes()
    scene = {k: v for k, v in SCENE_AXES.items() if kind.grid or k != "spacing"}
    if not kind.rollouts:
        return {**scene, **{k: v for k, v in settings.items() if not k.startswith(ROLLOUT_ONLY)}}
    return {**scene, **settings, **ROLLOUT_AXES}


UNITS = {"cm": "cm", "deg": "degree", "fraction of d": "1"}  # a setting's declared unit -> CF (UDUNITS)
AXIS_UNITS = {"spacing": "cm", "home_radius": "cm", "seed": "1", "max_steps": "1", "occlude": "1"}


def axis_units(name: str) -> dict[str, str]:
    """{"units": ...} of an axis (from the setting's declaration or the scene axes); {} for a name axis."""
    if name in AXIS_UNITS:
        return {"units": AXIS_UNITS[name]}
    for kind in KINDS.values():  # a kind's own axes (route following)
        if kind.own_axes and name in kind.own_axes and name not in all_options():
            return {} if name in kind.text_axes else {"units": kind.units.get(name, "1")}
    option = all_options().get(name)
    if option is None or option.type is str:
        return {}
    return {"units": UNITS.get(option.setting.unit, option.setting.unit or "1")}


def metric_units(name: str) -> str:
    """A metric's units from its name: percent, degree or a count."""
    return "percent" if name.endswith("_pct") else "degree" if name.endswith("_deg") else "1"


def name_axes() -> tuple[str, ...]:
    """The axes whose values are names (strings)."""
    own = (n for k in KINDS.values() for n in k.text_axes)  # a kind's own name axes (route following's `kind`, ...)
    return ("env", "method", "first_move", "collisions", *(n for n, o in all_options().items() if o.type is str), *own)


DEFAULTS = {"env": ["env1"], "method": ["delv"], "spacing": [25.0], "seed": [0]}
DISTANCES = DEFAULT_DISTANCES  # success-rate release distances, cm
TRIALS = TRIALS_PER_DISTANCE  # success-rate trials per distance
RANDOM_ENVS = 10_000  # seeded random layouts one sweep file may ask for
MAX_VALUES = 100_000  # values of one axis
MAX_CELLS = 1_000_000  # cells of one sweep (each is validated before any work: about 1 ms a cell, 17 min here)


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: axes in file order (name -> values), metrics, the file's text, and for
    success-rate sweeps the release distances and trials per distance."""

    kind: SweepKind | str  # a str: the kind's name, with what the kind knows
    axes: dict[str, list]
    metrics: list[str]
    text: str
    distances: tuple[float, ...] = DISTANCES
    trials: int = TRIALS
    random_envs: dict[str, tuple[int, int]] = field(default_factory=dict)  # env label -> (seed, landmarks)
    ensemble_envs: dict[str, dict] = field(default_factory=dict)  # env label -> its docs/model.md §7 dictionary
    env_files: dict[str, str] = field(default_factory=dict)  # env label -> the file it names (`read_sweep`)

    def __post_init__(self):
        if not isinstance(self.kind, SweepKind):  # a kind given by its name
            if self.kind not in KINDS:
                raise InputError("kind", self.kind, f"must be one of {', '.join(KINDS)}")
            object.__setattr__(self, "kind", KINDS[self.kind])

    def cells(self) -> Iterator[dict]:
        """Every combination of the axes (the last axis varies fastest), one at a time."""
        names = list(self.axes)
        return (dict(zip(names, combo)) for combo in itertools.product(*self.axes.values()))

    def cell(self, i: int) -> dict:
        """Cell `i` of `cells()`."""
        index = np.unravel_index(i, self.shape)
        return {name: values[int(j)] for (name, values), j in zip(self.axes.items(), index)}

    def describe(self) -> dict[str, dict[str, str]]:
        """CF-style `long_name` and `units` of every metric and axis of the results (`dataset`)."""
        known, options = axes(self.kind), all_options()
        out = {m: {"long_name": self.kind.metrics[m], "units": metric_units(m)} for m in self.metrics}
        for name in self.axes:
            text = options[name].setting.help if name in options else known.get(name, name)
            out[name] = {"long_name": text, **axis_units(name)}
        if self.kind.per_distance:
            out["distance_cm"] = {"long_name": "release distance from home", "units": "cm"}
        return out

    def seconds(self) -> float:
        """A rough warm time of the whole sweep on 2 CPU cores (the kind's `cell_seconds`; compilation not
        included), which a sweep states before it starts."""
        return self.n_cells * self.kind.cell_seconds(self)

    @property
    def n_cells(self) -> int:
        return math.prod(self.shape)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.axes.values())


def _values(name: str, raw, field: str | None = None) -> list:
    """An axis's values: a list, one value, or an inclusive range (`field` names it in errors)."""
    field = field or f"axes.{name}"
    if isinstance(raw, dict):
        unknown = sorted(set(raw) - {"start", "stop", "step", "num"})
        if unknown or "start" not in raw or "stop" not in raw or ("step" in raw and "num" in raw):
            raise InputError(field, raw, "a range is {start, stop, step} or {start, stop, num}")
        start, stop = raw["start"], raw["stop"]
        if not all(is_finite_number(v) for v in (start, stop, raw.get("step", 1), raw.get("num", 2))):
            raise InputError(field, raw, "range bounds must be finite numbers")
        if "num" in raw:
            num = raw["num"]
            if not isinstance(num, int) or num < 1:
                raise InputError(field, raw, "num must be an integer >= 1")
            if num > MAX_VALUES:
                raise InputError(field, raw, f"has {num} values, more than {MAX_VALUES}")
            values = [start + (stop - start) * i / max(num - 1, 1) for i in range(num)]
        else:
            step = raw.get("step", 1)
            if step <= 0 or stop < start:
                raise InputError(field, raw, "is empty (need start <= stop and step > 0)")
            ratio = (stop - start) / step  # inf for a subnormal step
            count = math.floor(ratio + 1e-9) + 1 if math.isfinite(ratio) else math.inf
            if count > MAX_VALUES:
                raise InputError(field, raw, f"has {count:.3g} values, more than {MAX_VALUES}")
            values = [start + i * step for i in range(count)]
    elif isinstance(raw, list):
        if len(raw) > MAX_VALUES:  # a list is capped as a range is (issue 53 point 9)
            raise InputError(field, f"a list of {len(raw)} values", f"has more than {MAX_VALUES} values")
        values = raw
    else:
        values = [raw]
    if not values:
        raise InputError(field, raw, "is empty")
    kinds = {type(v) for v in values} - {bool}
    names = name_axes()
    if name in names and kinds != {str}:
        raise InputError(field, raw, "must be names (strings)")
    if name not in names and (not kinds <= {int, float} or any(isinstance(v, bool) for v in values)):
        raise InputError(field, raw, "must be numbers")
    seen: set = set()
    for v in values:  # 50 and 50.0 are one value (equal numbers hash alike)
        if v in seen:
            raise InputError(field, raw, f"repeats the value {v!r}")
        seen.add(v)
    return values


def _env_labels(raw, random_envs: dict[str, tuple[int, int]], ensemble_envs: dict[str, dict]) -> list:
    """The env axis with every table replaced by the labels of the worlds it stands for:
    {random = COUNT, landmarks = N or [N, ...], seed = S} by its seeded random layouts
    (`envs._presets.random_env(S + i, N)`: "random<S+i>-<N>", recorded in `random_envs`) and
    {ensemble = FAMILY, members = COUNT, seed = S, factor = F, first = I} by the members of a world family
    (`envs.ensemble_envs`, docs/model.md §6.1: "env1-m0", ..., recorded in `ensemble_envs`)."""
    items = raw if isinstance(raw, list) else [raw]
    labels = []
    for item in items:
        if not isinstance(item, dict):
            labels.append(item)
        elif "ensemble" in item:
            labels += _ensemble_labels(item, len(random_envs), ensemble_envs)
        else:
            labels += _random_labels(item, random_envs, len(ensemble_envs))
    return labels


def _random_labels(item: dict, random_envs: dict[str, tuple[int, int]], others: int) -> list[str]:
    field_ = "axes.env"
    if sorted(set(item) - {"random", "landmarks", "seed"}) or "random" not in item or "landmarks" not in item:
        raise InputError(
            field_,
            item,
            "a table is {random = COUNT, landmarks = N or [N, ...], seed = S} or "
            "{ensemble = FAMILY, members = COUNT, seed = S, factor = F, first = I}",
        )
    count, seed = item["random"], item.get("seed", 0)
    counts = item["landmarks"] if isinstance(item["landmarks"], list) else [item["landmarks"]]
    ints = [count, seed, *counts]
    if (
        not all(isinstance(v, int) and not isinstance(v, bool) for v in ints)
        or count < 1
        or seed < 0
        or not counts
        or min(counts) < 1
        or max(counts) > 12
    ):
        raise InputError(field_, item, "random and seed must be integers >= 1 and >= 0, landmarks in 1..12")
    if count * len(counts) + len(random_envs) + others > RANDOM_ENVS:
        raise InputError(field_, item, f"asks for more than {RANDOM_ENVS} generated layouts")
    labels = []
    for n in counts:
        for s_ in range(seed, seed + count):
            label = f"random{s_}-{n}"
            random_envs[label] = (s_, n)
            labels.append(label)
    return labels


def _ensemble_labels(item: dict, others: int, ensemble_envs: dict[str, dict]) -> list[str]:
    field_ = "axes.env"
    unknown = sorted(set(item) - {"ensemble", "members", "seed", "factor", "first"}, key=str)
    if unknown or "members" not in item:
        what = f"unknown key {unknown[0]!r}" if unknown else "members is missing"
        raise InputError(
            field_,
            item,
            f"{what}: an ensemble is {{ensemble = FAMILY, members = COUNT, seed = S, factor = F, first = I}}",
        )
    members, seed, factor = item["members"], item.get("seed", 0), item.get("factor", 1.0)
    first = item.get("first", 0)
    if isinstance(first, bool) or not isinstance(first, int) or first < 0:
        raise InputError(f"{field_}.first", first, "must be an integer >= 0 (the first member's index)")
    if not isinstance(item["ensemble"], str) or item["ensemble"] not in FAMILIES:
        raise InputError(f"{field_}.ensemble", item["ensemble"], f"must be a world family ({', '.join(FAMILIES)})")
    if isinstance(members, bool) or not isinstance(members, int) or members < 1:
        raise InputError(f"{field_}.members", members, "must be an integer >= 1")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError(f"{field_}.seed", seed, "must be an integer >= 0")
    if isinstance(factor, bool) or not isinstance(factor, (int, float)) or not 0 < factor <= 2:
        raise InputError(f"{field_}.factor", factor, "must be a number in (0, 2] (1: the family's own ranges)")
    if members + first + len(ensemble_envs) + others > RANDOM_ENVS:
        raise InputError(field_, item, f"asks for more than {RANDOM_ENVS} generated layouts")
    worlds = ensemble_envs_of(item["ensemble"], members, seed, float(factor), first)
    for w in worlds:
        ensemble_envs[w["name"]] = w
    return [w["name"] for w in worlds]


def parse_sweep(text: str, source: str = "sweep") -> SweepSpec:
    """Validate a sweep file's text (structure, axes, metrics); `InputError` naming the field."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(source, source, f"is not valid TOML ({exc})") from None
    if not data:  # almost surely a mistake (a file not saved yet): it would run the default map
        raise InputError(source, source, "is empty: a sweep file names its axes under [axes] (docs/sweeps.md)")
    unknown = sorted(set(data) - {"sweep", "axes"})
    if unknown:
        raise InputError(unknown[0], source, "unknown table (a sweep file has [sweep] and [axes])")
    head, table = data.get("sweep", {}), data.get("axes", {})
    if not isinstance(head, dict) or not isinstance(table, dict):
        raise InputError("sweep", source, "[sweep] and [axes] must be tables")
    table = upgraded(table, "sweep axis")  # mw_n_psi = [...] read as n_psi, with a DeprecationWarning
    fields = ("kind", "metrics", "distances", "trials")
    for key in sorted(set(head) - set(fields)):
        every_axis = sorted({a for k in KINDS.values() for a in axes(k)})
        near_field, near_axis = did_you_mean(key, fields), did_you_mean(key, every_axis)
        if key in every_axis:
            what = "is an axis: put it under [axes]"
        else:
            what = f"unknown field{near_field}" if near_field else f"unknown field{near_axis or ''}"
            what += "" if near_field or not near_axis else ", and axes go under [axes]"
        raise InputError(f"sweep.{key}", head[key], f"{what} (the fields of [sweep]: {', '.join(fields)})")
    name = head.get("kind", "vector-map")
    if name not in KINDS:
        raise InputError("sweep.kind", name, f"must be one of {', '.join(KINDS)}")
    kind = KINDS[name]
    for key in ("distances", "trials"):
        if key in head and not (kind.per_distance or (key == "trials" and kind.default_trials)):
            takes = [k for k, v in KINDS.items() if v.per_distance or (key == "trials" and v.default_trials)]
            users = " or ".join(f'"{k}"' for k in takes)
            raise InputError(f"sweep.{key}", head[key], f"is a setting of kind = {users} only")
    known = kind.metrics
    metrics = head.get("metrics", list(known))
    if not isinstance(metrics, list) or not metrics:
        raise InputError("sweep.metrics", metrics, "must be a non-empty list")
    for i, m in enumerate(metrics):
        if not isinstance(m, str):
            raise InputError(f"sweep.metrics[{i}]", m, f"must be a metric name (choose from {', '.join(known)})")
        if m not in known:
            other = [k for k, v in KINDS.items() if m in v.metrics]
            hint = f' (a metric of kind = "{other[0]}")' if other else did_you_mean(m, known)
            raise InputError(
                f"sweep.metrics[{i}]", m, f'unknown metric of kind = "{kind}"{hint} (choose from {", ".join(known)})'
            )
    kind_axes = {k: axes(v) for k, v in KINDS.items()}
    every = {k: v for kind_ in kind_axes.values() for k, v in kind_.items()}  # the axes of any kind
    for name in table:
        if name not in every:
            raise InputError(
                f"axes.{name}", table[name], f"unknown axis{did_you_mean(name, every)} (choose from {', '.join(every)})"
            )
        if name not in kind_axes[kind]:
            users = [k for k in KINDS if name in kind_axes[k]]
            raise InputError(
                f"axes.{name}",
                table[name],
                f'is not an axis of kind = "{kind}" (an axis of kind = {" or ".join(repr(k) for k in users)})',
            )
    random_envs: dict[str, tuple[int, int]] = {}
    ensemble_envs: dict[str, dict] = {}
    if "env" in table:
        table = {**table, "env": _env_labels(table["env"], random_envs, ensemble_envs)}
    values = {name: _values(name, raw) for name, raw in table.items()}
    for name, default in (kind.defaults or DEFAULTS).items():
        if name in kind_axes[kind]:
            values.setdefault(name, default)
    extra = {}
    if kind.per_distance or kind.default_trials:
        if kind.per_distance:
            extra["distances"] = tuple(
                float(v) for v in _values("distances", head.get("distances", list(DISTANCES)), "sweep.distances")
            )
        trials = head.get("trials", kind.default_trials or TRIALS)
        if isinstance(trials, bool) or not isinstance(trials, int) or trials < 1:
            raise InputError("sweep.trials", trials, "must be an integer >= 1")
        extra["trials"] = trials
    cells = math.prod(len(v) for v in values.values())
    if cells > MAX_CELLS:
        raise InputError(
            "axes",
            " x ".join(str(len(v)) for v in values.values()),
            f"give {cells:.3g} cells, more than {MAX_CELLS:.0e}: split the sweep",
        )
    return SweepSpec(
        kind=kind,
        axes=values,
        metrics=list(dict.fromkeys(metrics)),
        text=text,
        random_envs=random_envs,
        ensemble_envs=ensemble_envs,
        **extra,
    )
