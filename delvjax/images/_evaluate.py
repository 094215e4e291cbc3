"""Evaluating homing methods on an image database (docs/images.md §6-7): load a BoB database or a
plain folder (`_load.py`), then vector maps and nearest-snapshot rollouts of any method.
Validation first (`InputError` naming the field, or the file, and the value)."""

from __future__ import annotations

import math
from collections.abc import Callable

import jax
import jax.numpy as jnp
import numpy as np

from ..core.checks import non_negative, positive, positive_int, seed_value
from ..core.deprecation import keywords_after
from ..core.errors import InputError
from ..core.images.database import (
    RingDatabase,
    database_directions,
    home_plan,
    move_plan,
    perceived_landmarks,
    route_home_plan,
    route_plan,
)
from ..core.images.rollouts import OUTCOMES, Field, Paths, nearest_snapshot_rollouts
from ..core.maps import VectorMap
from ..core.rollouts import MAX_STEPS, TRIALS_PER_DISTANCE
from ..core.rollouts.success import wilson_pct
from ..options._setup import make_setup
from ._conventions import mismatch
from ._load import LoadedDatabase, _warn, with_channel


def plans(db: LoadedDatabase):
    """(the unit move ending at every point, the home record's move) of a database (docs/images.md §6)."""
    pos, head = np.asarray(db.rings.positions), np.asarray(db.rings.headings)
    if db.kind == "route":
        plan = route_plan(pos, head, db.camera.cols)
        home = route_home_plan(pos, head, db.home_index, db.camera.cols)
    else:
        plan = move_plan(pos, head, db.spacing, db.camera.cols)
        home = home_plan(pos, head, db.home_index, db.spacing, db.camera.cols)
    return jax.tree.map(jnp.asarray, plan), jax.tree.map(jnp.asarray, home)


def perceived(db: LoadedDatabase, delv) -> np.ndarray:
    """World positions of the landmarks in the reference map of `delv` (a `DELV` module; Fig 4.20)."""
    xy, valid = perceived_landmarks(db.rings, plans(db)[1], delv)
    return np.asarray(xy)[np.asarray(valid)]


def database_vector_map(
    db: LoadedDatabase,
    method="delv",
    home_rings: RingDatabase | None = None,
    method_set=None,
    warn: Callable[[str], None] = _warn,
    **options,
) -> VectorMap:
    """The homing direction of `method` at every database point (docs/images.md §6). `options`: method
    settings and `channel` as in `evaluate.vector_map`; `home_rings`: take the home record from another
    rendering of the same positions (e.g. other lighting); `method_set`: registry names compiled into one
    program with `method` (`options.method_set`). The home point itself is not included."""
    module, sensor = make_setup(method, method_set, n_pix=db.camera.cols, panorama_cols=db.camera.cols, **options)
    if module.reads_panorama():
        check_panorama_field(db, method)
    rings = with_channel(db.rings, sensor.channel)
    home_db = rings if home_rings is None else with_channel(home_rings, sensor.channel)
    plan, home = plans(db)
    pos = np.asarray(db.rings.positions)
    direction, valid, error = database_directions(rings, plan, home_db, home, module, jnp.asarray(db.home, jnp.float32))
    included = np.arange(len(pos)) != db.home_index
    if db.conventions is not None and db.heading_deg is not None:  # views turned by a misread heading: say so
        end = np.asarray(plan.end)
        to_home = np.arctan2(*(db.home - pos[end]).T[::-1])
        signed = np.degrees(np.angle(np.exp(1j * (np.asarray(direction, np.float64) - to_home))))
        hint = mismatch(np.where(included, signed, np.nan), db.heading_deg[end], db.camera.cols, db.conventions)
        if hint:
            warn(f"{db.name}: {hint}")
    return VectorMap(
        points=jnp.asarray(pos),
        included=jnp.asarray(included),
        heading=jnp.asarray(
            np.arctan2(*(pos[np.asarray(plan.end)] - pos[np.asarray(plan.start)]).T[::-1]), jnp.float32
        ),
        direction=direction,
        valid=valid,
        error_deg=error,
    )


def check_panorama_field(db: LoadedDatabase, method) -> None:
    """`InputError` unless the database holds panoramas a panorama method can read (docs/model.md §4.7):
    kept at loading (`panoramas=True`), with a vertical field that contains the horizon (the scale
    planes magnify about it) and stays within +-90 deg."""
    if db.rings.snapshots.panorama is None:
        raise InputError("method", method, "reads panoramas: load or render the database with panoramas=True")
    top, bottom = float(db.camera.elev_top_deg), float(db.camera.elev_bottom_deg)
    if not 90.0 > top > 0.0 > bottom > -90.0:
        raise InputError(
            "elevation",
            [top, bottom],
            "must contain the horizon, within (-90, 90) deg: the scale planes magnify the panorama about it",
        )


@keywords_after(
    3,
    (
        "step",
        "home_radius",
        "max_steps",
        "motion_heading_noise_deg",
        "motion_step_noise",
        "seed",
        "collisions",
    ),
)
def database_rollouts(
    db: LoadedDatabase,
    vm: VectorMap,
    starts,
    *,
    step: float | None = None,
    home_radius: float | None = None,
    max_steps: int = MAX_STEPS,
    motion_heading_noise_deg: float = 0.0,
    motion_step_noise: float = 0.0,
    seed: int = 0,
    collisions: bool = True,
) -> Paths:
    """Nearest-snapshot rollouts (docs/images.md §7) from `starts` (T, 2) cm on the directions of `vm`.
    step and home_radius default to the spacing; the database's obstacles (rendered databases list
    them) end a trial where `collisions`."""
    step = db.spacing if step is None else positive(step, "step")
    home_radius = db.spacing if home_radius is None else non_negative(home_radius, "home_radius")
    max_steps = positive_int(max_steps, "max_steps")
    noise = jnp.asarray(
        [
            math.radians(non_negative(motion_heading_noise_deg, "motion_heading_noise_deg")),
            non_negative(motion_step_noise, "motion_step_noise"),
        ],
        jnp.float32,
    )
    key = jax.random.fold_in(jax.random.PRNGKey(seed_value(seed)), 3)
    obs = db.obstacles if collisions else {}
    cyl = np.asarray(obs.get("cylinders") or np.zeros((0, 3)), np.float32).reshape(-1, 3)
    box = np.asarray(obs.get("boxes") or np.zeros((0, 4)), np.float32).reshape(-1, 4)
    f = Field(
        db.rings.positions,
        vm.direction,
        vm.valid,
        jnp.asarray(db.home, jnp.float32),
        jnp.asarray(db.arena, jnp.float32),
        jnp.asarray(cyl),
        jnp.asarray(box),
    )
    return nearest_snapshot_rollouts(
        f,
        jnp.asarray(starts, jnp.float32).reshape(-1, 2),
        key,
        jnp.float32(step),
        jnp.float32(home_radius),
        noise,
        max_steps,
    )


def database_catchment(
    db: LoadedDatabase, vm: VectorMap, home_radius: float | None = None, **options
) -> tuple[np.ndarray, Paths]:
    """Catchment (docs/images.md §7): `database_rollouts` from every database point farther than
    `home_radius` (default: the spacing) from home: (release points (T, 2), Paths)."""
    radius = db.spacing if home_radius is None else non_negative(home_radius, "home_radius")
    pos = np.asarray(db.rings.positions)
    starts = pos[np.linalg.norm(pos - db.home, axis=-1) > radius]
    return starts, database_rollouts(db, vm, starts, home_radius=radius, **options)


def database_success_rate(
    db: LoadedDatabase, vm: VectorMap, distances, trials: int = TRIALS_PER_DISTANCE, seed: int = 0, **options
) -> list[dict]:
    """Success rate against release distance on a database (docs/images.md §7; thesis Figs 4.10b,
    5.8): `trials` releases at each distance from home in seeded uniform directions, nearest-snapshot
    rollouts (`database_rollouts` options). A release outside the arena or within `db.spacing / 2` of
    an obstacle is not placed. A distance's directions come from its own key (the seed and the distance),
    so they do not change with the other distances asked for. Per distance: trials placed, successes,
    the rate and its 95 % Wilson interval (%, NaN where none was placed)."""
    distances = [positive(d, "distances") for d in np.atleast_1d(np.asarray(distances, np.float64)).tolist()]
    trials = positive_int(trials, "trials")
    key = jax.random.PRNGKey(seed_value(seed))
    keys = [jax.random.fold_in(jax.random.fold_in(key, 11), round(100 * d)) for d in distances]  # per distance
    phi = np.stack([np.asarray(jax.random.uniform(k, (trials,), maxval=2 * math.pi, dtype=jnp.float32)) for k in keys])
    d = np.asarray(distances)[:, None]
    starts = np.stack([db.home[0] + d * np.cos(phi), db.home[1] + d * np.sin(phi)], -1).reshape(-1, 2)
    lo, hi = np.asarray(db.arena[:2]), np.asarray(db.arena[2:])
    placed = np.all((starts >= lo) & (starts <= hi), -1)
    for x, y, r in db.obstacles.get("cylinders") or []:
        placed &= np.hypot(starts[:, 0] - x, starts[:, 1] - y) > r + db.spacing / 2
    for x0, y0, x1, y1 in db.obstacles.get("boxes") or []:
        m = db.spacing / 2
        placed &= ~(
            (starts[:, 0] > x0 - m) & (starts[:, 0] < x1 + m) & (starts[:, 1] > y0 - m) & (starts[:, 1] < y1 + m)
        )
    ok = np.zeros(len(starts), bool)
    if placed.any():
        paths = database_rollouts(db, vm, starts[placed], seed=seed, **options)
        ok[placed] = np.asarray(paths.outcome) == 0
    rows = []
    for i, dist in enumerate(distances):
        sel = slice(i * trials, (i + 1) * trials)
        n, k = int(placed[sel].sum()), int(ok[sel].sum())
        lo_pct, hi_pct = wilson_pct(k, n)
        rate = 100.0 * k / n if n else float("nan")
        rows.append(
            {
                "distance_cm": dist,
                "placed": n,
                "successes": k,
                "success_pct": rate,
                "ci_lo_pct": float(lo_pct),
                "ci_hi_pct": float(hi_pct),
            }
        )
    return rows


def catchment_numbers(paths: Paths) -> dict:
    """Catchment (%) and the share of every other outcome (%), mean steps of the successes."""
    code = np.asarray(paths.outcome)
    n = max(len(code), 1)
    out = {"releases": int(len(code)), "catchment_pct": 100.0 * float(np.sum(code == 0)) / n}
    out.update({f"{name}_pct": 100.0 * float(np.sum(code == i)) / n for i, name in enumerate(OUTCOMES) if i})
    steps = np.asarray(paths.steps)[code == 0]
    out["mean_steps_success"] = float(steps.mean()) if steps.size else float("nan")
    return out
