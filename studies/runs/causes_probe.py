"""Causes measured outside the run (docs/reproduce.md "Causes measured outside the run"): the
experiments behind the causes that the claims (`claims._ch4`) name without numbers of their own
study. Not a study of `delvjax reproduce` (they take minutes and
change nothing in the report); run them with

    python -m delvjax.studies.runs.causes_probe [--variants N] [--spacing CM]
    python -m delvjax.studies.runs.causes_probe --gaps [--probe ID ...] [--members N]
    python -m delvjax.studies.runs.causes_probe --tail FAMILY METHOD [--members N]

1. Pixels (claims 4 and 5): DELV's vector map at 360 (the model's ring) and 1440 pixels, d = 20,
   50 and 100 cm on env1 and the 3-landmark layout of Fig 4.8. With noise-free sensing the only
   error of a bearing is its pixel; a short move's parallax magnifies it, and near home the short
   home vector turns most with it.
2. env3's coordinates (two env3 numbers of the built-in world): the thesis describes env3 (four landmarks east
   of home) but gives no coordinates. Moving each landmark of ours up to `jitter` cm (kept east
   of home, non-overlapping) shows how far ACV's error point rate (Table 5.1, k = 0) and
   DELV-compass's catchment with one landmark hidden (Table 5.3, k = 1) depend on them.
3. The ring radius (ALV, ring6, k = 1; the occlusion table's note): ALV's catchment with one of six
   ring landmarks hidden per ring radius, and the distance of its field's sink from home.
4. env2's hull (claim 2): DELV's error points inside a square of landmarks around home at 360 and
   1440 pixels (25 cm grid).
5. `--gaps`: the gap probe (`_gap_probe.PROBES`): the thesis numbers outside our band over the worlds measured
   under alternatives the thesis allows (noise, ACV's pairing, home radius, env3's and the rings' geometry);
   writes `_gap_probes.json`, which `_ensemble_gaps.gap_cause` reads (docs/reproduce.md "What the unexplained
   gaps were"). `--probe` re-measures some probes and keeps the others' rows.
6. `--tail FAMILY METHOD`: every number of many members (200, k = 0) of one family and method, written to
   `_gap_tails.json`, which `_ensemble_gaps.gap_cause` reads: a thesis number outside our band that at least 1 % of
   them reach is a rare world of the family (`_gap_tail`; docs/reproduce.md "The gap probe's third round").
"""

from __future__ import annotations

import argparse
import itertools
import json

import jax
import numpy as np

import delvjax
from delvjax import Grid, Rules
from delvjax.core import rollouts
from delvjax.core.errors import InputError
from delvjax.core.sensor import Sensor
from delvjax.envs import FAMILIES, make_env, member_layouts, random_env
from delvjax.envs._presets import preset_dict
from delvjax.options import method_set

from . import _gap_probe, _gap_tail
from ._common import HOME_RADIUS, METHOD_SET, PAD, RULES, curve, env, inside_hull
from ._occlusion_layouts import stacked_masks

EAST_OF_HOME = 80.0  # cm: every moved env3 landmark keeps its centre at least this far east of home


def pixels(spacing: float = 50.0, ds=(20.0, 50.0, 100.0), widths=(360, 1440)) -> dict:
    """Mean vector-map error of DELV without compass per ring width and d (env1), and the
    3-landmark layout's error curve (nearest bins first) per ring width (d = 50 cm)."""
    e = env("env1").arrays()
    out = {"env1_mean_error_deg": {}, "random3_curve_deg": {}}
    for n_pix in widths:  # a handful of static ring widths: one program each
        row = {}
        for d in ds:
            vm = delvjax.vector_map(e, method="delv", seed=0, d=d, n_pix=n_pix, grid=Grid(spacing=spacing))
            row[f"d={d:g}"] = float(np.asarray(vm.error_deg)[np.asarray(vm.included)].mean())
        out["env1_mean_error_deg"][n_pix] = row
        r3 = random_env(103, 3, pad_to=PAD)
        out["random3_curve_deg"][n_pix] = [
            r["mean_deg"]
            for r in curve(r3, delvjax.vector_map(r3, method="delv", seed=0, n_pix=n_pix, grid=Grid(spacing=spacing)))
        ]
    return out


def ring_radius(radii=(150.0, 250.0, 350.0, 420.0), spacing: float = 50.0) -> dict:
    """ALV's catchment (%) with the north landmark of six equally spaced around home hidden, per ring
    radius (cm), and the sink of its field: where the five visible unit vectors cancel, on the line
    through home away from the hidden landmark (its distance from home, cm)."""
    out = {}
    for radius in radii:  # a handful of layouts: the same program
        angles = np.deg2rad(90.0 + 60.0 * np.arange(6))
        lm = [(500.0 + radius * np.cos(a), 500.0 + radius * np.sin(a), 30.0) for a in angles]
        e = make_env(lm, home=(500.0, 500.0), arena=(0.0, 0.0, 1000.0, 1000.0), pad_to=PAD)
        c = delvjax.catchment(e, "alv", hidden=[0], grid=Grid(spacing=spacing))
        ys = np.linspace(500.0, 500.0 - 0.9 * radius, 2001)  # short of the south landmark
        pts = np.stack([np.full_like(ys, 500.0), ys], 1)
        to = np.asarray(lm)[1:, None, :2] - pts[None]
        pull = (to[..., 1] / np.hypot(to[..., 0], to[..., 1])).sum(0)  # north component of the five unit vectors
        out[f"{radius:g}"] = {
            "catchment_pct": float(c.catchment_pct()[0]),
            "sink_cm": float(500.0 - ys[np.argmin(abs(pull))]),
        }
    return out


def hull_pixels(spacing: float = 25.0, widths=(360, 1440)) -> dict:
    """env2 (a square of landmarks around home): DELV's error points (e > 45°, %) inside and outside the
    landmarks' hull per ring width; on the 25 cm grid the points inside lie within 180 cm of home."""
    e = env("env2")
    out = {}
    for n_pix in widths:
        vm = delvjax.vector_map(e, method="delv", seed=0, n_pix=n_pix, grid=Grid(spacing=spacing))
        inc, err = np.asarray(vm.included), np.asarray(vm.error_deg)
        hull = inside_hull(e, np.asarray(vm.points))
        out[n_pix] = {
            "inside_gt45_pct": 100.0 * float((err[inc & hull] > 45.0).mean()),
            "outside_gt45_pct": 100.0 * float((err[inc & ~hull] > 45.0).mean()),
        }
    return out


def env3_variants(n: int, jitter: float, seed: int = 0) -> list:
    """`n` env3 layouts with every landmark moved uniformly up to `jitter` cm in x and y, kept east of
    home and inside the arena; overlapping draws are skipped (fewer than n may come back)."""
    spec = preset_dict("env3")
    base = np.array([(lm["x"], lm["y"], lm["r"]) for lm in spec["landmarks"]])
    home, arena = np.asarray(spec["home"], float), np.asarray(spec["arena"], float)
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):  # layout construction on the host: a few dozen draws
        lm = base.copy()
        lm[:, :2] += rng.uniform(-jitter, jitter, (len(lm), 2))
        lm[:, 0] = np.clip(lm[:, 0], home[0] + EAST_OF_HOME, arena[2] - lm[:, 2])
        lm[:, 1] = np.clip(lm[:, 1], arena[1] + lm[:, 2], arena[3] - lm[:, 2])
        try:
            out.append(make_env(lm, home=spec["home"], arena=spec["arena"], pad_to=PAD).arrays())
        except InputError:  # overlapping landmarks
            continue
    return out


def env3_layouts(
    n: int = 60, spacing: float = 50.0, acv_jitter: float = 150.0, delv_jitter: float = 70.0, delv_variants: int = 12
) -> dict:
    """ACV's e > 45° % (k = 0) over env3 variants moved up to `acv_jitter` cm, and DELV-compass's mean
    catchment over the four single hidden landmarks (k = 1, default rules) over `delv_variants`
    variants moved up to `delv_jitter` cm."""
    acv = []
    for e in env3_variants(n, acv_jitter, seed=1):
        vm = delvjax.vector_map(e, method="acv", seed=0, grid=Grid(spacing=spacing))
        acv.append(100.0 * float((np.asarray(vm.error_deg)[np.asarray(vm.included)] > 45.0).mean()))
    delv = []
    method = method_set("delv-compass", METHOD_SET)[0]
    for e in env3_variants(delv_variants, delv_jitter, seed=0):
        masks, hidden, ks = stacked_masks(e, 1)
        c = rollouts.catchment_area(
            e,
            method,
            Sensor(),
            key=jax.random.PRNGKey(0),
            masks=masks[ks == 1],
            hidden=[h for h, k in zip(hidden, ks) if k == 1],
            grid=Grid(spacing=spacing),
            rules=Rules(home_radius=HOME_RADIUS, lanes=128, **RULES["default"]),
        )
        delv.append(float(np.mean([r["catchment_pct"] for r in rollouts.catchment_summary(c)["per_mask"]])))
    return {
        "acv_gt45_k0_pct": acv,
        "delv_compass_catchment_k1_pct": delv,
        "acv_jitter_cm": acv_jitter,
        "delv_jitter_cm": delv_jitter,
        "spacing_cm": spacing,
    }


def choice_maps(probe: _gap_probe.Probe, members: int, spacing: float, seed: int = 0, slices: int = 2) -> dict:
    """The error-point rates of one choice of hidden landmarks (Table 5.1's first row "corresponds to the error
    graphs in Figure 5.9", one map per k): {(family, run method, gt45|gt90[_min|_max]): (members, k + 1)}, the
    mean over the choices and a member's worst and best choice, from every member's vector map under every choice
    (slice j's members under seed + j, as `_gap_probe.measure`). Catchment sweeps pool the rates over the masks, so
    these come from vector maps, a loop on the host (~10 ms a map once compiled; a few thousand maps)."""
    size, width = -(-members // slices), max(_gap_probe.k_groups(probe)) + 1
    out: dict = {}
    for fam in probe.families:  # families x members x methods x choices: a loop of small programs
        family, k_max = FAMILIES[fam], min(probe.k_max, _gap_probe.family_k_max(fam))
        for i, lay in enumerate(member_layouts(family, members, seed)):
            e = make_env([tuple(map(float, lm)) for lm in lay], home=family.home, arena=family.arena, pad_to=PAD)
            for _, run in probe.methods:
                for k in range(k_max + 1):
                    rates = []
                    for hidden in itertools.combinations(range(family.n), k):
                        vm = delvjax.vector_map(
                            e,
                            method=run,
                            seed=seed + i // size,
                            hidden=list(hidden) or None,
                            grid=Grid(spacing=spacing),
                        )
                        err = np.asarray(vm.error_deg)[np.asarray(vm.included)]
                        rates.append((100.0 * np.mean(err > 45.0), 100.0 * np.mean(err > 90.0)))
                    for q, col in (("gt45", 0), ("gt90", 1)):
                        vals = [r[col] for r in rates]
                        for stat, v in (("", np.mean(vals)), ("_min", min(vals)), ("_max", max(vals))):
                            arr = out.setdefault((fam, run, q + stat), np.full((members, width), np.nan))
                            arr[i, k] = v
    return out


def probe_json(doc: dict) -> str:
    """The probe file's text: its header keys indented, one row a line (small diffs when a probe is re-measured)."""
    head = json.dumps({k: v for k, v in doc.items() if k != "rows"}, indent=1, ensure_ascii=False)[:-2]
    rows = ",\n  ".join(json.dumps(r, ensure_ascii=False) for r in doc["rows"])
    return f'{head},\n "rows": [\n  {rows}\n ]\n}}\n'


def gap_probes(ids: list[str] | None, members: int, spacing: float, path=_gap_probe.PROBE_FILE) -> dict:
    """Measure the gap probes `ids` (all when None) and write their rows to `path`, keeping other probes' rows."""
    chosen = [pr for pr in _gap_probe.PROBES if ids is None or pr.id in ids]
    kept = [r for r in _gap_probe.load_probes(path) if r["probe"] not in {pr.id for pr in chosen}]
    for pr in chosen:  # a handful of probes, each a few sweeps
        measured = _gap_probe.measure(pr, members=members, spacing=spacing)
        if pr.choice:  # the rates of one choice: vector maps (the sweeps pool them over the masks)
            measured |= choice_maps(pr, members, spacing)
        rows = _gap_probe.probe_rows(pr, measured)
        kept += rows
        inside = [f"{r['world']} {r['method']} k={r['k']} {r['quantity']}" for r in rows if r["inside"]]
        print(f"{pr.id}: {len(inside)} of {len(rows)} thesis numbers inside its band", flush=True)
    order = {pr.id: i for i, pr in enumerate(_gap_probe.PROBES)}
    kept.sort(key=lambda r: order.get(r["probe"], len(order)))
    doc = {"members": members, "slices": 2, "spacing_cm": spacing, "seed": 0}
    doc["probes"] = {pr.id: pr.hypothesis for pr in _gap_probe.PROBES}
    doc["rows"] = _gap_probe.with_net([{k: v for k, v in r.items() if k not in ("net", "keeps")} for r in kept])
    doc["command"] = (
        "python -m delvjax.studies.runs.causes_probe --gaps --members {members} --spacing {spacing:g}".format(
            members=members, spacing=spacing
        )
    )
    path.write_text(probe_json(doc))
    return doc


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--variants", type=int, default=60, help="env3 variants for ACV (default 60)")
    p.add_argument("--spacing", type=float, default=None, help="grid spacing cm (default 50; 100 with --gaps)")
    p.add_argument("--gaps", action="store_true", help="run the gap probe and write _gap_probes.json")
    p.add_argument("--probe", nargs="*", default=None, help="with --gaps: only these probes (ids of PROBES)")
    p.add_argument("--members", type=int, default=16, help="with --gaps: members per family (default 16)")
    p.add_argument("--tail", nargs=2, metavar=("FAMILY", "METHOD"), help="how rare a world with few error points is")
    a = p.parse_args()
    if a.tail:
        row = _gap_tail.measure(*a.tail, members=200 if a.members == 16 else a.members, spacing=a.spacing or 100.0)
        _gap_tail.write_tails([row])
        for q in _gap_tail.QUANTITIES:
            v = np.asarray(row[q])
            print(
                f"{a.tail[0]} {a.tail[1]} k = 0, {q} over {len(v)} members: 5-95 % {np.percentile(v, 5):.2f}-"
                f"{np.percentile(v, 95):.2f}, min {v.min():.2f}, max {v.max():.2f}"
            )
        print(f"written to {_gap_tail.TAIL_FILE}")
        return
    if a.gaps:
        gap_probes(a.probe, a.members, a.spacing or 100.0)
        return
    a.spacing = a.spacing or 50.0
    px = pixels(a.spacing)
    lay = env3_layouts(a.variants, a.spacing)
    for name, v in (
        ("ACV e>45 % (k = 0)", lay["acv_gt45_k0_pct"]),
        ("DELV-compass catchment % (k = 1)", lay["delv_compass_catchment_k1_pct"]),
    ):
        print(f"env3 variants, {name}: n {len(v)}, min {min(v):.1f}, median {np.median(v):.1f}, max {max(v):.1f}")
    rings, hull = ring_radius(), hull_pixels()
    print(json.dumps({"pixels": px, "env3": lay, "ring_radius": rings, "env2_hull_pixels": hull}, indent=1))


if __name__ == "__main__":
    main()
