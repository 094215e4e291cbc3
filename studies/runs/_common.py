"""What the thesis studies share: padded environments, cached runs, hull error rates, figures.

Every environment is padded to `PAD` landmark slots and stripped of its name, and vector
maps are read from catchment runs, so one compiled rollout program (all methods) serves every
environment, occlusion, layout, quantization level, background and noise setting (the
numbers do not change: padding slots are masked out). Rollouts run under the default
rules (thesis Algorithm 2, docs/model.md §5), the earlier "homing" first move and the physical
rules (landmark hits fail), reported side by side (`RULES`, `RULES_NOTE`).
"""

from __future__ import annotations

import jax
import numpy as np
from scipy.spatial import Delaunay

import delvjax
from delvjax import Grid, Rules
from delvjax.core import rollouts
from delvjax.core.maps import VectorMap
from delvjax.core.metrics import error_curve, summarize_map
from delvjax.core.scene import Env
from delvjax.core.sensor import Sensor
from delvjax.core.tables import concat_columns, success_rows, trajectory_columns
from delvjax.envs import load_env
from delvjax.options import get_method
from delvjax.plots import catchment_handles, catchment_panel, draw_env, draw_vector_map, subplots, vector_map_handles
from delvjax.plots import has_uncounted as not_counted

PAD = 6
# the default rules (thesis Algorithm 2), the earlier default ("homing": every first move follows the
# direction computed at the release point) and the physical rules (landmarks are obstacles); docs/model.md §5
RULES = {"default": rollouts.DEFAULT_RULES, "homing": rollouts.HOMING_RULES, "physical": rollouts.PHYSICAL_RULES}
RULES_NOTE = (
    "default rules (thesis Algorithm 2, docs/model.md §5): a method that needs a unit movement (DELV) first "
    "moves d along the release heading and only then matches, the others turn to their first direction at "
    "once; the catchment counts the grid points at least d from every wall (the blind first move must stay "
    "in the arena); landmarks are no obstacles. homing: every first move follows the direction computed at "
    "the release point (the earlier default; every grid point counts). physical: Algorithm 2, and a move "
    "ending inside a landmark fails."
)
LABEL = {
    "delv": "DELV",
    "delv-compass": "DELV (compass)",
    "delv-visual": "DELV (visual compass)",
    "acv": "ACV",
    "alv": "ALV",
    "acv-visual": "ACV (visual compass)",
    "alv-visual": "ALV (visual compass)",
    "warping": "image matching",
    "minwarping": "MinWarping",
}
HOME_RADIUS = rollouts.HOME_RADIUS
# Every method of the reproduction is compiled into one rollout program (`options.method_set`: a
# `MethodSet` module whose traced index picks the method): compiling a rollout program costs about 6 CPU-seconds, so the
# reproduction compiles one, not eight. Rendering a method does not need (the start snapshot, the gray
# channel) is skipped at run time, so no method runs slower for sharing (docs/reproduce.md).
METHOD_SET = (
    "delv",
    "delv-compass",
    "alv",
    "acv",
    "delv-visual",
    "alv-visual",
    "acv-visual",
    "warping",
    "delv-gap-compass",
    "delv-compass-agent",
)


def env(name: str) -> Env:
    """A built-in environment padded to PAD landmarks (one compiled program for all)."""
    return load_env(name, pad_to=PAD)


def vector_map(ctx, e: Env, method: str, **options) -> VectorMap:
    """The vector map of `method`, read from a catchment run: the rollouts' first directions are the
    vector map of the same seed (the same numbers as `delvjax.vector_map`, tested), and every study
    then needs one compiled program (`METHOD_SET`)."""
    return as_vector_map(catchment(ctx, e, method, **options))


def catchment(
    ctx, e: Env, method: str, rules: str = "default", home_radius: float = HOME_RADIUS, **options
) -> rollouts.Catchment:
    return delvjax.catchment(
        e,
        method=method,
        seed=ctx.config.seed,
        method_set=METHOD_SET,
        grid=Grid(spacing=ctx.config.spacing),
        rules=Rules(home_radius=home_radius, lanes=ctx.config.lanes, **RULES[rules]),
        **options,
    )


def every_rule(run, method: str, arena, d=None) -> dict:
    """{rules: result} of `run(rules)` for every rule set of RULES, from as few rollouts as give the
    same trials (docs/model.md §5): a method that reads only the current view makes the same trials
    under "homing" and "default" (`rollouts.under_release`), and the trials under the physical rules
    are the default ones ended at their first landmark contact (`rollouts.under_collisions`). Each
    restated result equals its own run bit for bit (tests/core/rollouts/test_restated_rules.py).
    `d`: the step distance if not the sensor's default."""
    d = Sensor().d if d is None else d
    view_only = not bool(np.asarray(get_method(method).reads_start_view()))
    homing = run("homing")
    default = rollouts.under_release(homing, arena, d) if view_only else run("default")
    return {"default": default, "homing": homing, "physical": rollouts.under_collisions(default)}


def catchments(ctx, e: Env, method: str, **options) -> dict[str, rollouts.Catchment]:
    """`catchment` of `method` under every rule set of RULES (`every_rule`)."""
    return every_rule(lambda rules: catchment(ctx, e, method, rules, **options), method, e.arena, options.get("d"))


def success_tables(ctx, e: Env, method: str, **options) -> dict[str, list[dict]]:
    """Success rate per release distance 50..450 cm (`config.trials` per bin, Figs 4.10b, 5.7b) of
    `method` under every rule set of RULES (`every_rule`): {rules: the rows of `tables.success_rows`
    (the CLI's success-rate CSV)}."""
    runs = every_rule(lambda rules: success_rate(ctx, e, method, rules, **options), method, e.arena, options.get("d"))
    return {rules: success_rows(res, method) for rules, res in runs.items()}


def success_rate(ctx, e: Env, method: str, rules: str = "default", **options) -> rollouts.SuccessRate:
    """The success-rate trials of `method` under one rule set (`success_tables`)."""
    return delvjax.success_rate(
        e,
        method=method,
        trials=ctx.config.trials,
        seed=ctx.config.seed,
        method_set=METHOD_SET,
        rules=Rules(home_radius=HOME_RADIUS, lanes=ctx.config.lanes, **RULES[rules]),
        **options,
    )


def inside_hull(e: Env, points: np.ndarray) -> np.ndarray:
    """True where a point lies inside the convex hull of the landmark centres."""
    lms = np.asarray(e.landmarks)[np.asarray(e.valid), :2]
    return Delaunay(lms).find_simplex(np.asarray(points)) >= 0


def hull_failures(c, hull: np.ndarray, m: int = 0) -> dict:
    """Failed rollouts (%) among the counted grid points of a `Catchment` c (`c.counted`, the points
    `catchment_pct` is over) inside and outside the landmarks' hull (`hull`, per cell), and how many
    counted points each region holds; NaN where a region holds none. Over `included` instead, the
    near-wall points a blind first move may not be released from would count as failures."""
    counted = np.asarray(c.counted)
    failed = ~np.asarray(c.success)[m]
    out = {}
    for name, region in (("inside", counted & hull), ("outside", counted & ~hull)):
        n = int(region.sum())
        out[name] = 100.0 * float(failed[region].mean()) if n else float("nan")
        out[f"n_{name}"] = n
    return out


def map_numbers(e: Env, vm: VectorMap) -> dict:
    """summarize_map plus e > 45 % inside and outside the landmarks' convex hull (Fig 4.3's reading)."""
    s = summarize_map(vm.error_deg, vm.valid, vm.included)
    inc = np.asarray(vm.included)
    hull = inside_hull(e, np.asarray(vm.points)) & inc
    out = ~hull & inc
    err = np.asarray(vm.error_deg)
    s["gt45_inside_hull_pct"] = 100.0 * float((err[hull] > 45).mean()) if hull.any() else float("nan")
    s["gt45_outside_hull_pct"] = 100.0 * float((err[out] > 45).mean()) if out.any() else float("nan")
    s["n_inside_hull"], s["n_outside_hull"] = int(hull.sum()), int(out.sum())  # the points behind each share
    return s


def curve(e: Env, vm: VectorMap) -> list[dict]:
    return error_curve(vm.error_deg, vm.points, e.home, vm.included)


def curve_means(rows: list[dict]) -> list[float]:
    return [r["mean_deg"] for r in rows]


def curve_number(ctx, key: str, rows: list[dict]) -> None:
    """An error curve as headline numbers: its bin means under `key` and the points behind each bin
    under `n:key` (the claims table reports the smallest sample behind a verdict)."""
    ctx.number(key, curve_means(rows))
    ctx.number(f"n:{key}", [int(r["n"]) for r in rows])


def curves_rows(curves: dict[str, list[dict]]) -> list[dict]:
    return [{"label": label, **row} for label, rows in curves.items() for row in rows]


def as_vector_map(c: rollouts.Catchment, m: int = 0) -> VectorMap:
    """The vector map inside a `Catchment` (mask m): same headings and home record as `vector_map`."""
    return VectorMap(
        points=c.points,
        included=c.included,
        heading=c.heading,
        direction=np.asarray(c.direction)[m],
        valid=np.asarray(c.valid)[m],
        error_deg=np.asarray(c.error_deg)[m],
        grid=c.grid,  # the catchment's grid: a figure of it needs no spacing=
    )


def index(tree, i: int):
    """Result i of a swept (vmapped) result, on the host (an eager device op would compile per shape)."""
    return jax.tree.map(lambda a: np.asarray(a)[i], tree)


def outcome_counts(c: rollouts.Catchment, m: int = 0) -> dict[str, int]:
    inc = np.asarray(c.counted)
    out = np.asarray(c.outcome)[m][inc]
    return {f"{name}": int((out == code).sum()) for code, name in enumerate(rollouts.OUTCOMES)}


FAILURES = ("timeout", "landmark", "arena")  # the failure outcomes of a rollout (docs/model.md §5)
FAR_BINS = 3  # the far third of the nine release distances (50..450 cm): the claims' "far from home"


def failure_counts(rows: list[dict], last: int | None = None) -> dict[str, int]:
    """Failed trials of a success table (`success_tables` rows) by outcome: timeout, landmark (a move
    ending inside a landmark), arena; over the `last` release distances only when given."""
    rows = rows if last is None else rows[-last:]
    return {o: int(sum(r[f"{o}_count"] for r in rows)) for o in FAILURES}


def failures_text(counts: dict[str, int]) -> str:
    """Failure counts as a table cell "timeout/landmark/arena"."""
    return "/".join(str(counts[o]) for o in FAILURES)


def record_failures(ctx, key: str, counts: dict[str, int]) -> None:
    """Failure counts by outcome as numbers `<key>:timeout`, `<key>:landmark`, `<key>:arena` (read back by
    `claims._common._failures`)."""
    for outcome in FAILURES:
        ctx.number(f"{key}:{outcome}", int(counts[outcome]))


def success_summary(rows: list[dict]) -> dict:
    placed = sum(r["placed"] for r in rows)
    return {
        "by_distance": [r["success_pct"] for r in rows],
        "overall": 100.0 * sum(r["successes"] for r in rows) / max(placed, 1),
    }


# --- figures ---------------------------------------------------------------------------------


def panel_figure(items, spacing: float | None = None, classes: bool = False, title: str = ""):
    """Vector-map panels, at most 3 a row (readable fonts at page width): items = [(panel title, env,
    VectorMap)]; every marker in a legend. `spacing`: each map's own grid (`VectorMap.grid`) unless given."""
    cols = min(len(items), 3)
    rows = -(-len(items) // cols)
    fig, axes = subplots(rows, cols, figsize=(4.6 * cols, 4.6 * rows + 0.5), squeeze=False)
    for ax in axes.ravel()[len(items) :]:
        ax.set_visible(False)
    for ax, (label, e, vm) in zip(axes.ravel(), items):
        errors, side = vm.error_deg if classes else None, vm.spacing if spacing is None else spacing
        draw_vector_map(ax, e, vm.points, vm.direction, vm.valid, vm.included, side, error_deg=errors)
        draw_env(ax, e)
        ax.set_title(label, fontsize=9)
    handles = vector_map_handles(classes)
    fig.legend(handles=handles, loc="lower center", ncol=min(len(handles), 4), fontsize=8, frameon=False)
    if title:
        fig.suptitle(title)
    fig.set_layout_engine("tight", rect=(0, 0.1 / rows, 1, 1))  # applied when drawn (in the figure thread)
    return fig


def catchment_figure(items, title: str):
    """1 x n catchment panels (Figs 4.5 / 5.5): items = [(panel title, env, Catchment)], each on its grid."""
    fig, axes = subplots(1, len(items), figsize=(4.8 * len(items), 5.4), squeeze=False)
    for ax, (label, e, c) in zip(axes[0], items):
        catchment_panel(ax, e, c, 0, title=label)
    handles = catchment_handles(any(not_counted(c) for _, _, c in items))
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle(title)
    fig.set_layout_engine("tight", rect=(0, 0.05, 1, 1))  # applied when drawn (in the figure thread)
    return fig


def thesis_value(table: dict, env_name: str, method: str, k: int = 0):
    """A thesis number or None (`table[env][method][k]`)."""
    values = table.get(env_name, {}).get(method)
    if values is None:
        return None
    if isinstance(values, dict):
        values = values.get("gt45")
    return values[k] if values is not None and k < len(values) else None


def rule_suffix(rules: str) -> str:
    """The numbers-key suffix of a rule set: "" for the default rules, ":<name>" otherwise (":homing", ":physical")."""
    return "" if rules == "default" else f":{rules}"


def catchment_columns(ctx, key: str, results: dict, row: dict) -> None:
    """Record the catchment of each rule set (`results`: {rules: Catchment}) as number `key` (+ suffix)
    and as table columns "ours <rules> %" and "<rules> failures (timeout/landmark/arena)" of `row`."""
    for rules, c in results.items():
        pct = float(c.catchment_pct()[0])
        ctx.number(key + rule_suffix(rules), pct)
        counts = outcome_counts(c)
        row[f"ours {rules} %"] = pct
        row[f"{rules} failures (timeout/landmark/arena)"] = failures_text(counts)


def success_set(ctx, e: Env, methods, fig_file: str, title: str, caption: str, source: str, note: str) -> dict:
    """Success rate vs release distance of `methods` under both rule sets: numbers
    `success:env1:<method>[:physical]` and `success_overall:...`, a table, a figure and the counts CSV."""
    from delvjax.plots import success_rate_figure  # matplotlib: loaded only when a figure is drawn

    tables = {}
    for m in methods:  # a few methods x three rule sets; one compiled program
        for rules, t in success_tables(ctx, e, m).items():
            tables[f"{LABEL[m]} ({rules})"] = t
            summ = success_summary(t)
            ctx.number(f"success:env1:{m}{rule_suffix(rules)}", summ["by_distance"])
            ctx.number(f"success_overall:env1:{m}{rule_suffix(rules)}", summ["overall"])
            record_failures(ctx, f"success_failures:env1:{m}{rule_suffix(rules)}", failure_counts(t))
            record_failures(ctx, f"success_failures_far:env1:{m}{rule_suffix(rules)}", failure_counts(t, last=FAR_BINS))
            ctx.step(f"success {m} {rules}")
    ctx.table(
        "success_rate",
        f"Success rate (%) by release distance, {title}",
        [
            {
                "method (rules)": k,
                **{f"{r['distance_cm']:g} cm": r["success_pct"] for r in v},
                "failures timeout/landmark/arena": failures_text(failure_counts(v)),
            }
            for k, v in tables.items()
        ],
        source=source,
        note=note,
    )
    ctx.figure(
        f"{fig_file}.png",
        success_rate_figure(tables, f"Success rate, {title} ({ctx.config.trials} trials per distance; {source})"),
        caption,
    )
    ctx.csv(f"{fig_file}_counts.csv", rows=[{"label": k, **r} for k, v in tables.items() for r in v])
    return tables


def trajectory_set(
    ctx, e: Env, methods, fig_file: str, title: str, caption: str, n_starts: int = 8, own: dict | None = None
) -> None:
    """Homing paths of `methods` from the same `n_starts` seeded release points (Figs 4.11, 5.8):
    numbers `trajectories:env1:<method>:reach_home`, the figure and the CSV of every position. A method
    in `own` runs in a program of its own with those options (one outside the shared METHOD_SET)."""
    from delvjax.plots import trajectories_figure  # matplotlib: loaded only when a figure is drawn

    results, tables = {}, []
    for m in methods:
        tr = delvjax.trajectories(
            e,
            method=m,
            n_starts=n_starts,
            seed=ctx.config.seed,
            method_set=None if m in (own or {}) else METHOD_SET,
            rules=Rules(home_radius=HOME_RADIUS, lanes=ctx.config.lanes),
            **(own or {}).get(m, {}),
        )
        results[LABEL[m]] = tr
        tables.append(trajectory_columns(tr, m))
        ctx.number(f"trajectories:env1:{m}:reach_home", int(np.asarray(tr.success).sum()))
    ctx.figure(f"{fig_file}.png", trajectories_figure(e, results, HOME_RADIUS, title), caption)
    ctx.csv(f"{fig_file}.csv", columns=concat_columns(tables))
