"""The gap probe: the thesis numbers that lie outside our band over the worlds with no cause, measured again
under alternatives the thesis's words allow (docs/reproduce.md "What the unexplained gaps were"). Each
`Probe` is one hypothesis: a setting (bearing noise, home radius), a method variant (`_gap_methods`) or a
family variant (env3's sector, its landmarks' distances); its members run as catchment sweeps like the
`ensembles` study's (members in seed slices, `ensembles.sweep_texts`'s layout), and every thesis number of its
families and methods gets its 5-95 % band under the alternative. `python -m delvjax.studies.runs.causes_probe
--gaps` writes them to PROBE_FILE, which `_ensemble_gaps.gap_cause` reads: a thesis number inside a probe's
band has that probe's hypothesis as its cause."""

from __future__ import annotations

import dataclasses
import json
import math
import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from delvjax.envs import FAMILIES, member_layouts
from delvjax.sweeps import parse_sweep, run_sweep

from ._ensemble_stats import BAND, SOURCE_LABEL, thesis_numbers
from ._gap_methods import register_variants, unregister_variants

PROBE_FILE = Path(__file__).with_name("_gap_probes.json")
QUANTITY = {"catchment": "catchment %", "gt45": "e>45 %", "gt90": "e>90 %"}
METRIC = {"catchment": "catchment_pct", "gt45": "gt45_pct", "gt90": "gt90_pct"}
CHOICE = {"catchment_min": "catchment_min_pct", "catchment_max": "catchment_max_pct"}  # a world's worst and best mask
RINGS = ("ring3", "ring5", "ring6")
ENVS = ("env1", "env2", "env3")
COMPASS = (("delv-compass", "delv-compass"), ("acv", "acv"), ("alv", "alv"))


@dataclass(frozen=True)
class Probe:
    """One alternative: `families` (thesis family names) run with `methods` ((thesis method, method run)
    pairs), `axes` (extra sweep axis lines, e.g. 'bearing_noise_deg = [5.0]'), `variant` (Family fields
    replaced: the members are that variant's layouts, same rules otherwise) and up to `k_max` hidden landmarks
    (at most the family's, `k_max`); `cause` names it in a gap's cause. `choice`: a catchment's band is the one
    choice of hidden landmarks' (`CHOICE`), not the mean over every choice's."""

    id: str
    cause: str
    hypothesis: str
    families: tuple[str, ...]
    methods: tuple[tuple[str, str], ...] = COMPASS
    axes: str = ""
    variant: dict = field(default_factory=dict)
    k_max: int = 3
    choice: bool = False


DEFAULT = "default"  # the reference probe: our families and settings on the probes' members, seeds and grid
PROBES = (
    Probe(
        DEFAULT,
        "our defaults",
        "the reference: no alternative, the same members, seeds and grid",
        RINGS + ENVS,
        k_max=2,
    ),
    Probe(
        "bearing5",
        "5° of bearing noise",
        "Tables 5.2/5.4 come from Yu and Kim 2011a, Tables 5.1/5.3 from 2011b (thesis lines 900, 915): the "
        "noise of the two papers need not be the same",
        RINGS,
        axes="bearing_noise_deg = [5.0]",
        k_max=1,
    ),
    Probe(
        "bearing5-env",
        "5° of bearing noise",
        "the same noise on env1-3 (Table 5.1/5.3)",
        ENVS,
        axes="bearing_noise_deg = [5.0]",
    ),
    Probe(
        "acv-nearest",
        "ACV pairing by the nearest bearing",
        "ACV pairs each landmark with the nearest home bearing (Weber et al. 1999's non-distinctive "
        "landmarks) instead of the best cyclic shift of the sorted lists (docs/model.md §4.2)",
        ("ring5", "ring6", "env1"),
        methods=(("acv", "acv-nearest"),),
        k_max=2,
    ),
    Probe(
        "acv-agent",
        "ACV's current list in the agent frame",
        "ACV keeps the current landmarks in the order the camera reads them (agent frame, as DELV's earlier "
        "order, docs/model.md §3.3) instead of sorting them by home-frame bearing (§4.2): the thesis does not say "
        "in which frame ACV's rotational matching lists them (Tables 5.2/5.4, Yu and Kim 2011a)",
        RINGS,
        methods=(("acv", "acv-agent"),),
    ),
    Probe(
        "acv-agent-env",
        "ACV's current list in the agent frame",
        "the same ACV on env1-3 (Tables 5.1/5.3, Yu and Kim 2011b)",
        ENVS,
        methods=(("acv", "acv-agent"),),
    ),
    Probe(
        "agent-lists",
        "current lists in the agent frame (DELV and ACV)",
        "DELV (compass) and ACV both keep the current list in the agent frame (`delv-compass-agent`, "
        "`acv-agent`; docs/model.md §3.3): the rings' tables come from Yu and Kim 2011a, whose matching need "
        "not list the landmarks as Fig 3.4 draws them",
        RINGS,
        methods=(("delv-compass", "delv-compass-agent"), ("acv", "acv-agent")),
    ),
    Probe(
        "alv-mean",
        "ALV averaging its unit vectors",
        "ALV as the average of the unit landmark vectors (thesis lines 209, 234, 408, 'the average landmark "
        "vector'; Lambrinos et al. 2000) instead of Eq 3.11's sum: the same direction with every landmark seen as "
        "its own blob, different where a landmark is hidden or two blobs merge",
        RINGS + ENVS,
        methods=(("alv", "alv-mean"),),
        k_max=2,
    ),
    Probe(
        "home75",
        "a 75 cm home radius",
        "a trial succeeds within 75 cm of home (ours 50 cm; the thesis states no radius)",
        ("ring5", "ring6", "env1", "env2"),
        methods=(("acv", "acv"), ("alv", "alv")),
        axes="home_radius = [75.0]",
        k_max=2,
    ),
    Probe(
        "ring-small",
        "rings 80-150 cm from home",
        "the rings' landmarks 80-150 cm from home (ours 150-350 cm; Tables 5.2/5.4 give no radius)",
        RINGS,
        variant={"distance": (80.0, 150.0)},
        k_max=2,
    ),
    Probe(
        "ring-large",
        "rings 350-440 cm from home",
        "the rings' landmarks 350-440 cm from home, near the arena's walls (ours 150-350 cm)",
        RINGS,
        variant={"distance": (350.0, 440.0)},
        k_max=2,
    ),
    Probe(
        "env3-wide",
        "env3's landmarks within 180°",
        "'on one side' as a half plane: every bearing within 180° (ours 150°)",
        ("env3",),
        variant={"sector_deg": 180.0},
    ),
    Probe(
        "env3-near",
        "env3's landmarks 80-200 cm from home",
        "env3's landmarks nearer home, 80-200 cm (ours 150-350 cm)",
        ("env3",),
        variant={"distance": (80.0, 200.0)},
    ),
    Probe(
        "env3-far",
        "env3's landmarks 300-440 cm from home",
        "env3's landmarks farther, 300-440 cm (ours 150-350 cm)",
        ("env3",),
        variant={"distance": (300.0, 440.0)},
    ),
    Probe(
        "one-choice",
        "one choice of hidden landmarks",
        "the thesis does not say which landmarks it hid nor that it averaged over the choices (docs/model.md §5): "
        "a table's catchment may be one choice's, which lies between its world's worst and best choice; the band "
        "runs from the 5th percentile of the members' worst choice to the 95th of their best",
        RINGS + ENVS,
        choice=True,
    ),
)


def family_k_max(family: str) -> int:
    """The most hidden landmarks of a family's thesis numbers: 3 for the five- and six-landmark rings, else 2."""
    return 3 if family in ("ring5", "ring6") else 2


def member_envs(probe: Probe, family: str, members: int, seed: int, folder: Path) -> list[str]:
    """The env axis entries (TOML) of a probe's members of one family: one ensemble table per member, or for a
    family variant the paths of its members' JSON files (docs/model.md §7) written to `folder`."""
    if not probe.variant:
        return [f'{{ensemble = "{family}", members = 1, first = {i}, seed = {seed}}}' for i in range(members)]
    fam = dataclasses.replace(FAMILIES[family], name=f"{family}-{probe.id}", **probe.variant)
    paths = []
    for i, lay in enumerate(member_layouts(fam, members, seed)):  # writing the members' files: input preparation
        env = {"name": f"{fam.name}-m{i}", "arena": list(fam.arena), "home": list(fam.home)}
        env["landmarks"] = [{"x": float(x), "y": float(y), "r": float(r)} for x, y, r in lay]
        path = folder / f"{fam.name}-m{i}.json"
        path.write_text(json.dumps(env))
        paths.append(f'"{path}"')
    return paths


def k_groups(probe: Probe) -> dict[int, tuple[str, ...]]:
    """The probe's families by the most hidden landmarks they are run with (min of the probe's `k_max` and the
    family's): one sweep per group and seed slice, so ring5/ring6 reach k = 3 beside ring3's k = 2."""
    groups: dict[int, tuple[str, ...]] = {}
    for f in probe.families:
        k = min(probe.k_max, family_k_max(f))
        groups[k] = groups.get(k, ()) + (f,)
    return groups


def sweep_text(probe: Probe, envs: list[str], spacing: float, seed: int, k: int | None = None) -> str:
    """The catchment sweep of some of a probe's members (the families of one k group: one program) under one
    seed, up to `k` hidden landmarks (default: the smallest of the probe's families')."""
    methods = ", ".join(f'"{run}"' for _, run in probe.methods)
    k = min([probe.k_max] + [family_k_max(f) for f in probe.families]) if k is None else k
    metrics = ", ".join(f'"{m}"' for m in [*METRIC.values(), *(CHOICE.values() if probe.choice else ())])
    return (
        f'[sweep]\nkind = "catchment"\nmetrics = [{metrics}]\n'
        f"[axes]\nenv = [{', '.join(envs)}]\nmethod = [{methods}]\nocclude = {list(range(k + 1))}\n"
        f"spacing = [{spacing}]\nseed = [{seed}]\n{probe.axes}\n"
    )


def measure(probe: Probe, members: int = 16, slices: int = 2, spacing: float = 100.0, seed: int = 0) -> dict:
    """{(family, run method, quantity): (members, k + 1) array} of one probe: members in `slices` seed slices
    (slice j's noise and release headings under seed + j; layouts from `seed`, as in the `ensembles` study), every
    family of a slice in one sweep. The probe's method variants are registered for it and removed after."""
    register_variants()
    size = -(-members // slices)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            envs = {f: member_envs(probe, f, members, seed, Path(tmp)) for f in probe.families}
            groups, parts = k_groups(probe), []
            width = max(groups) + 1
            for j in range(slices):  # a few seed slices x k groups: input preparation, one sweep each
                part: dict = {}
                for k, fams in groups.items():
                    chunk = [e for f in fams for e in envs[f][j * size : (j + 1) * size]]
                    part |= _sweep(probe, chunk, fams, spacing, seed + j, k, width)
                parts.append(part)
            return _stack(parts)
    finally:
        unregister_variants()


def _sweep(probe: Probe, envs: list[str], fams: tuple, spacing: float, seed: int, k: int, width: int) -> dict:
    """One seed slice's sweep of the families `fams` up to k hidden: {(family, run method, quantity): (members,
    `width`) array}, NaN beyond k."""
    ds = run_sweep(parse_sweep(sweep_text(probe, envs, spacing, seed, k), f"gap-{probe.id}"), lanes=128)
    family = np.array([re.search(r"(env\d|ring\d)", str(e).rsplit("/", 1)[-1]).group(1) for e in ds.env.values])
    out = {}
    for _, run in probe.methods:
        dim = next((d for d in ("homing_method", "method") if d in ds.dims), None)  # the name before issue 53: method
        cell = ds.sel({dim: run}) if dim else ds
        for q, metric in (METRIC | CHOICE if probe.choice else METRIC).items():
            values = np.asarray(cell[metric].transpose("env", "occlude").values, float)
            values = np.pad(values, ((0, 0), (0, width - values.shape[1])), constant_values=np.nan)
            out |= {(f, run, q): values[family == f] for f in fams}
    return out


def _stack(parts: list[dict]) -> dict:
    """The slices' arrays, members stacked."""
    return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}


def probe_rows(probe: Probe, measured: dict) -> list[dict]:
    """One row per thesis number of the probe's families and methods: its band under the alternative."""
    rows = []
    run_of = dict(probe.methods)
    for source, fam, m, k, q, value in thesis_numbers():
        key = (fam, run_of.get(m), q)
        if key not in measured or k >= measured[key].shape[1] or source in ("fig4_5", "fig5_5", "fig5_10"):
            continue
        if probe.choice and (fam, key[1], f"{q}_min") not in measured:  # no choice's rates: the default's band
            continue
        sample = measured[key][:, k]
        sample = sample[~np.isnan(sample)]
        if not len(sample):  # k beyond the family's (ring3 beside ring5's k = 3)
            continue
        lo, med, hi = np.percentile(sample, [BAND[0], 50.0, BAND[1]])
        if probe.choice:  # one choice lies in [worst, best] of its world: the ends of those
            lo = np.nanpercentile(measured[(fam, key[1], f"{q}_min")][:, k], BAND[0])
            hi = np.nanpercentile(measured[(fam, key[1], f"{q}_max")][:, k], BAND[1])
        rows.append(
            {
                "probe": probe.id,
                "cause": probe.cause,
                "source": SOURCE_LABEL[source],
                "world": fam,
                "method": m,
                "k": k,
                "quantity": QUANTITY[q],
                "thesis": value,
                "lo": round(float(lo), 2),
                "median": round(float(med), 2),
                "hi": round(float(hi), 2),
                "members": int(len(sample)),
                "inside": bool(lo <= value <= hi),
            }
        )
    return rows


def load_probes(path: Path = PROBE_FILE) -> list[dict]:
    """The committed probe rows (empty when the file is missing)."""
    return json.loads(path.read_text())["rows"] if path.exists() else []


NUMBER = ("source", "world", "method", "k", "quantity")  # what names a thesis number


def with_net(rows: list[dict]) -> list[dict]:
    """The rows with each probe's net gain: of the thesis numbers both it and the DEFAULT probe measured, how many
    more lie inside its bands than inside the default's (`net`), and those counts (`keeps`: inside, default, of)."""
    default = {tuple(r[f] for f in NUMBER): r["inside"] for r in rows if r["probe"] == DEFAULT}
    out = []
    for pid in dict.fromkeys(r["probe"] for r in rows):
        mine = [r for r in rows if r["probe"] == pid]
        common = [r for r in mine if tuple(r[f] for f in NUMBER) in default]
        inside = sum(r["inside"] for r in common)
        before = sum(default[tuple(r[f] for f in NUMBER)] for r in common)
        out += [r | {"net": inside - before, "keeps": [inside, before, len(common)]} for r in mine]
    return out


def matching(row: dict, probes: list[dict], step: float = 0.0) -> list[dict]:
    """The probe rows of the same thesis number as `row` (a `distribution_rows` row) whose band holds it, or comes
    within `step` points of it (one grid point of the probes' grid, as `_ensemble_gaps.gap_cause` allows for our
    own band), of probes that are not the DEFAULT and put at least as many of the thesis's numbers inside their
    bands as the default (`net` >= 0): an alternative that moves this number inside and more others out is not its
    cause. Rows whose band holds it come first."""
    found = [
        p
        for p in probes
        if p["lo"] - step <= p["thesis"] <= p["hi"] + step
        and p["probe"] != DEFAULT
        and p.get("net", 0) >= 0
        and all(str(p[f]) == str(row[f]) for f in NUMBER)
        and math.isclose(p["thesis"], row["thesis"])
    ]
    return sorted(found, key=lambda p: not p["inside"])
