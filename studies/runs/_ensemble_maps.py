"""The per-member numbers of the `ensemble_maps` study (docs/reproduce.md "Ensembles: visual compass, error
curves and the landmark hull"): error curves and hull error rates from a vector-map sweep's per-point errors,
the visual compass's heading errors of many worlds as one program, and the claims' keys of each sweep. Plain
NumPy on the arrays the sweeps return, and one jitted program for the heading errors."""

from __future__ import annotations

import re

import jax
import numpy as np

from delvjax.core.maps import grid_included, random_headings
from delvjax.core.methods.heading import visual_compass_errors
from delvjax.core.scene import Env
from delvjax.envs import env_from_dict, load_env

from .visual_compass import visual_key

BIN_CM = 50.0  # width of an error curve's distance bins (`core.metrics.error_curve`, Fig 4.4)
ERROR_DEG = 45.0  # an error point (Fig 4.3, Tables 5.1/5.2)
WRONG_DEG = 5.0  # a wrong heading of the visual compass (claim 30's reading)
CLEARANCE = 10.0  # cm from a landmark's edge: the grid points a map includes (`maps.grid_included`)


def member_label(label: str) -> str:
    """A sweep's env label as the claims' world label: `env1-s3-m7` -> `env1-m7` (members by index)."""
    return re.sub(r"-s\d+-m(\d+)$", r"-m\1", str(label))


def family_of(label: str) -> str:
    return member_label(label).rsplit("-m", 1)[0]


# --- geometry over many worlds at once ----------------------------------------------------------------


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def hull_inside(centres: np.ndarray, valid: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(W, P): True where grid point p lies inside (or on) the convex hull of world w's landmark centres
    (`centres` (W, L, 2), `valid` (W, L); points (P, 2)). An edge i -> j bounds the hull when every landmark
    lies on its left; a point is inside when it lies on the left of every such edge (the hull of
    `scipy.spatial.Delaunay`, `_common.inside_hull`, tested)."""
    a = centres[:, :, None, None, :]  # edge start i
    ab = (centres[:, None, :, :] - centres[:, :, None, :])[:, :, :, None, :]  # (W, L, L, 1, 2)
    eps = 1e-6 * float(np.abs(centres[valid]).max(initial=1.0)) ** 2
    side = _cross(ab, centres[:, None, None, :, :] - a)  # (W, L, L, L): landmark k against edge i -> j
    left = (side >= -eps) | ~valid[:, None, None, :]
    pair = valid[:, :, None] & valid[:, None, :] & ~np.eye(centres.shape[1], dtype=bool)
    edge = pair & left.all(axis=-1)  # (W, L, L)
    on_left = _cross(ab, points[None, None, None, :, :] - a) >= -eps  # (W, L, L, P)
    return np.all(~edge[..., None] | on_left, axis=(1, 2))


def binned_curves(errors: np.ndarray, points: np.ndarray, homes: np.ndarray, width: float = BIN_CM):
    """Error curves of W worlds at once: (means (W, B), counts (W, B)), bin b holding the included points
    (errors not NaN) at b * width <= |x - home| < (b + 1) * width, as `core.metrics.error_curve` bins
    them (tested); a bin without a point NaN."""
    dist = np.linalg.norm(points[None, :, :] - homes[:, None, :], axis=-1)  # (W, P)
    inc = ~np.isnan(errors)
    b = np.floor(dist / width).astype(int)
    n_bins = int(b[inc].max()) + 1 if inc.any() else 0
    onehot = (b[..., None] == np.arange(n_bins)) & inc[..., None]  # (W, P, B)
    counts = onehot.sum(axis=1)
    sums = np.einsum("wp,wpb->wb", np.nan_to_num(errors), onehot.astype(float))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(counts > 0, sums / np.maximum(counts, 1), np.nan), counts


def rate_in(errors: np.ndarray, region: np.ndarray, above: float = ERROR_DEG) -> np.ndarray:
    """(W,) % of the included points of `region` (W, P) whose error exceeds `above`; NaN where none."""
    inc = region & ~np.isnan(errors)
    n = inc.sum(axis=-1)
    hits = (np.nan_to_num(errors) > above) & inc
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(n > 0, 100.0 * hits.sum(axis=-1) / np.maximum(n, 1), np.nan)


# --- the visual compass's heading errors of many worlds ----------------------------------------------


def stacked_env(worlds: list[dict | str], pad: int) -> Env:
    """Worlds (docs/model.md §7 dictionaries or built-in names) stacked along a leading axis, padded to `pad`
    landmark slots (one scene pytree for a vmapped program)."""
    envs = [load_env(w, pad_to=pad) if isinstance(w, str) else env_from_dict(w, pad_to=pad) for w in worlds]
    stack = lambda field: jax.device_put(np.stack([np.asarray(getattr(e, field)) for e in envs]))  # noqa: E731
    return Env(stack("landmarks"), stack("valid"), stack("home"), stack("arena"))


@jax.jit
def heading_errors(envs: Env, points: jax.Array, key: jax.Array, sensors) -> tuple[jax.Array, jax.Array]:
    """The visual compass's heading error (degrees, (W, S, P)) of W stacked worlds under S stacked sensors
    (the background a traced leaf) at the grid `points`, release headings random per point from `key`
    (as `visual_compass` draws them), and the points each world includes (W, P)."""
    headings = random_headings(key, points.shape[0])
    per_sensor = lambda env: jax.vmap(lambda s: visual_compass_errors(env, points, headings, s))(sensors)  # noqa: E731
    err = jax.vmap(per_sensor)(envs)
    included = jax.vmap(lambda env: grid_included(env, points, CLEARANCE))(envs)
    return jax.numpy.degrees(err), included


def heading_stats(err_deg: np.ndarray, included: np.ndarray) -> dict[str, np.ndarray]:
    """(W, S) mean |error| and % of included points with |error| > WRONG_DEG (`visual_compass.heading_error_stats`)."""
    a = np.where(included[:, None, :], np.abs(err_deg), np.nan)
    n = included.sum(axis=-1)[:, None]
    return {
        "heading_error_mean_deg": np.nanmean(a, axis=-1),
        "heading_error_gt5_pct": 100.0 * np.sum(np.nan_to_num(a) > WRONG_DEG, axis=-1) / np.maximum(n, 1),
    }


# --- the claims' keys of each sweep ----------------------------------------------------------------------


def curve_keys(res: dict, methods, labels, mean_of=("delv", "warping")) -> dict[str, dict]:
    """{world: {key: value}} from `sweeps.point_errors` (env x method x one spacing and seed): per method its
    error curve `error_curve:<family>:<m>` (bins with a point; `n:` the points behind each), the e > 45
    rates inside and outside the landmarks' hull (`map:<family>:<m>:gt45_inside_hull_pct`, `..._outside_...`)
    and, for `mean_of`, the mean error `map:<family>:<m>:mean_error_deg` (the other methods' means come from
    the grid of their visual-compass companions)."""
    err = res["errors"].reshape(len(labels), len(methods), -1)  # one spacing, one seed
    lms = [res["landmarks"][label] for label in labels]
    slots = max(len(x) for x in lms)
    centres = np.zeros((len(labels), slots, 2))
    valid = np.zeros((len(labels), slots), bool)
    for w, x in enumerate(lms):  # input preparation: a few landmarks per world
        centres[w, : len(x)], valid[w, : len(x)] = x[:, :2], True
    inside = hull_inside(centres, valid, res["points"])  # (W, P)
    homes = np.stack([res["homes"][label] for label in labels])
    out: dict[str, dict] = {}
    for j, m in enumerate(methods):  # a handful of methods; each step is one array program over worlds
        means, counts = binned_curves(err[:, j], res["points"], homes)
        rin, rout = rate_in(err[:, j], inside), rate_in(err[:, j], ~inside)
        overall = np.nanmean(err[:, j], axis=-1)
        for w, label in enumerate(labels):  # the claims' dictionaries, one per world
            fam, keep = family_of(label), counts[w] > 0
            nums = out.setdefault(member_label(label), {})
            nums[f"error_curve:{fam}:{m}"] = means[w][keep].tolist()
            nums[f"n:error_curve:{fam}:{m}"] = counts[w][keep].astype(int).tolist()
            nums[f"map:{fam}:{m}:gt45_inside_hull_pct"] = None if np.isnan(rin[w]) else float(rin[w])
            nums[f"map:{fam}:{m}:gt45_outside_hull_pct"] = None if np.isnan(rout[w]) else float(rout[w])
            if m in mean_of:
                nums[f"map:{fam}:{m}:mean_error_deg"] = float(overall[w])
    return out


def compass_keys(ds, methods, sigmas) -> dict[str, dict]:
    """{world: {key: value}} of the true compass's catchment sweep (env x method x compass_noise_deg):
    `catchment:<family>:<m>` and `map:<family>:<m>:mean_error_deg` without noise, and the catchment per
    compass noise `compass_noise:<family>:<m>:catchment` (`visual_compass`'s keys)."""
    out: dict[str, dict] = {}
    for label in ds.env.values:
        fam, nums = family_of(label), out.setdefault(member_label(label), {})
        for m in methods:
            cell = ds.sel({"env": label, "homing_method": m})  # the axis `method` (docs/sweeps.md)
            by_sigma = [float(cell.sel({"compass_noise_deg": s}).catchment_pct) for s in sigmas]
            nums[f"catchment:{fam}:{m}"] = by_sigma[0]
            nums[f"map:{fam}:{m}:mean_error_deg"] = float(cell.sel({"compass_noise_deg": sigmas[0]}).mean_error_deg)
            nums[f"compass_noise:{fam}:{m}:catchment"] = by_sigma
    return out


def visual_keys(ds, pairs, background: str, catchment: bool) -> dict[str, dict]:
    """{world: {key: value}} of a visual-compass sweep of one background (env x method): with `catchment`
    the catchment under the default rules and restated under the physical ones
    (`visual:[<env>:]<bg>:<m>:catchment[:physical]`), else the vector map's mean error
    (`...:mean_error_deg`); `pairs`: (true-compass method, visual method), keys under the former."""
    pairs, out = list(pairs), {}
    for label in ds.env.values:
        fam, nums = family_of(label), out.setdefault(member_label(label), {})
        for true, visual in pairs:
            cell = ds.sel({"env": label, "homing_method": visual})
            prefix = f"{visual_key(fam, background)}:{true}"
            if catchment:
                nums[f"{prefix}:catchment"] = float(cell.catchment_pct)
                nums[f"{prefix}:catchment:physical"] = float(cell.catchment_physical_pct)
            else:
                nums[f"{prefix}:mean_error_deg"] = float(cell.mean_error_deg)
    return out


def level_keys(res: dict, labels, levels) -> dict[str, dict]:
    """{world: {key: value}} of DELV's per-point sweep over the quantization levels (env x delv x one spacing and
    seed x levels): the error curve per level `error_curve:<family>:delv:Q<q>` (bins with a point; `n:` the
    points behind each), the keys of the `quantization` study (claim 11)."""
    out = curve_keys(res, [f"delv:Q{q}" for q in levels], labels, mean_of=())
    return {w: {k: v for k, v in nums.items() if k.startswith(("error_curve:", "n:"))} for w, nums in out.items()}


def with_continuous(worlds: dict[str, dict]) -> None:
    """Every world with DELV's quantized curves gets `error_curve:env1:delv:continuous`: its continuous curve of
    the same sweep seed and grid (the per-point maps' `error_curve:env1:delv`; a sweep's levels are >= 1)."""
    for nums in worlds.values():
        if "error_curve:env1:delv:Q1" in nums and "error_curve:env1:delv" in nums:
            nums["error_curve:env1:delv:continuous"] = nums["error_curve:env1:delv"]
            nums["n:error_curve:env1:delv:continuous"] = nums["n:error_curve:env1:delv"]


RANDOM_LABEL = re.compile(r"random(\d+)-(\d+)$")  # a sweep's seeded random layout `random<seed>-<landmarks>`


def random_worlds(numbers: dict[str, dict], landmarks: dict, base: int) -> dict[str, dict]:
    """The per-point numbers of a sweep over seeded random layouts (`curve_keys`, labels `random<s>-<n>`) as
    worlds: layout seed s >= `base` is member `random-m<s - base>`, a smaller seed the built-in `random` (the
    `landmark_number` study's layouts); keys `...:random<n>:...` (`error_curve:random<n>:<m>`, that study's).
    `landmark_number:nested` (claim 6): 1.0 where each world's fewer landmarks are the first of its more (one
    seed's draws, `envs._presets.random_env`, drawn in order: checked here on the layouts the sweep ran), else 0.0."""
    out: dict[str, dict] = {}
    layouts: dict[str, dict[int, np.ndarray]] = {}
    for label, nums in numbers.items():
        s, n = (int(g) for g in RANDOM_LABEL.match(label).groups())
        world = f"random-m{s - base}" if s >= base else "random"
        out.setdefault(world, {}).update({k.replace(f":{label}:", f":random{n}:"): v for k, v in nums.items()})
        layouts.setdefault(world, {})[n] = np.asarray(landmarks[label], float)
    for world, by_n in layouts.items():
        lays = [by_n[n] for n in sorted(by_n)]
        nested = all(len(a) <= len(b) and np.array_equal(b[: len(a)], a) for a, b in zip(lays, lays[1:]))
        out[world]["landmark_number:nested"] = float(nested and len(lays) > 1)
    return out


def merge(worlds: dict[str, dict], more: dict[str, dict], suffix: str = "") -> None:
    """Add `more`'s numbers to `worlds` (labels with `suffix`, e.g. a built-in world's seed offset)."""
    for label, nums in more.items():
        worlds.setdefault(label + suffix, {}).update(nums)
