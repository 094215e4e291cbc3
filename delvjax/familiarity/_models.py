"""The familiarity models by name, built and checked before any work (docs/familiarity.md §2):
`perfect-memory`, `infomax`, `mushroom-body`, each with its settings (`InputError` naming the field)."""

from __future__ import annotations

import jax
import numpy as np

from ..core.checks import choice, is_integer, positive, positive_int
from ..core.errors import InputError
from ..core.familiarity.base import FamiliarityModel
from ..core.familiarity.infomax import infomax
from ..core.familiarity.mushroom_body import mushroom_body
from ..core.familiarity.perfect_memory import PerfectMemory
from ..core.familiarity.ridf import KINDS, ridf_table

MODELS = {
    "perfect-memory": "every route image kept; the best match (or the n best, weighted) sets the heading (BoB)",
    "infomax": "one network trained over the route by the infomax rule (Baddeley et al. 2012; BoB)",
    "mushroom-body": "sparse Kenyon-cell code, one output neuron, one-shot depression (Ardin et al. 2016)",
}
SETTINGS = {  # model -> its settings and defaults
    "perfect-memory": {"kind": "abs", "select": "best", "n_best": 3, "window_ahead": 0, "window_behind": 0},
    "infomax": {"learning_rate": 0.97, "rate_divisor": "inputs_hidden", "normalise": "none", "n_hidden": None},
    "mushroom-body": {"n_kc": 20000, "pn_per_kc": 10, "n_active": 200},
}


def non_negative_int(value, field: str) -> int:
    """An integer >= 0."""
    if is_integer(value) and value <= 0:
        if value < 0:
            raise InputError(field, value, "must be >= 0")
        return 0
    return positive_int(value, field)


def model_settings(name: str, **settings) -> dict:
    """The settings of model `name` with the defaults filled in, checked; unknown settings are refused."""
    name = choice(name, "model", tuple(MODELS))
    unknown = sorted(set(settings) - set(SETTINGS[name]))
    if unknown:
        raise InputError(unknown[0], settings[unknown[0]], f"is no setting of {name} ({', '.join(SETTINGS[name])})")
    s = {**SETTINGS[name], **{k: v for k, v in settings.items() if v is not None}}
    if name == "perfect-memory":
        choice(s["kind"], "kind", KINDS)
        choice(s["select"], "select", ("best", "weighted"))
        positive_int(s["n_best"], "n_best")
        for k in ("window_ahead", "window_behind"):
            non_negative_int(s[k], k)
    elif name == "infomax":
        positive(s["learning_rate"], "learning_rate")
        choice(s["rate_divisor"], "rate_divisor", ("inputs_hidden", "hidden"))
        choice(s["normalise"], "normalise", ("none", "zscore"))
        if s["n_hidden"] is not None:
            positive_int(s["n_hidden"], "n_hidden")
    else:
        for k in ("n_kc", "pn_per_kc", "n_active"):
            positive_int(s[k], k)
        if s["n_active"] > s["n_kc"]:
            raise InputError("n_active", s["n_active"], f"must be at most n_kc ({s['n_kc']})")
    return s


def make_model(name: str, shape: tuple[int, int], seed: int = 0, **settings) -> FamiliarityModel:
    """An untrained model `name` for views of `shape` (H, W); `seed` draws InfoMax's initial weights and the
    mushroom body's wiring."""
    s = model_settings(name, **settings)
    key = jax.random.fold_in(jax.random.key(seed), list(MODELS).index(name))
    n_pixels = int(np.prod(shape))
    if name == "perfect-memory":
        return PerfectMemory(**s)
    if name == "infomax":
        return infomax(shape, key, **s)
    if s["pn_per_kc"] > n_pixels:
        raise InputError("pn_per_kc", s["pn_per_kc"], f"must be at most the view's {n_pixels} pixels")
    return mushroom_body(shape, key, **s)


def checked_images(images, field: str = "views", least: int = 1) -> np.ndarray:
    """(N, H, W) float32 from a stack or a list of 2-D images: one size, finite, at least `least`."""
    try:
        stack = [np.asarray(v) for v in (images if isinstance(images, (list, tuple)) else list(np.asarray(images)))]
    except (TypeError, ValueError):
        raise InputError(field, type(images).__name__, "must be a stack of 2-D images") from None
    if len(stack) < least:
        raise InputError(
            field,
            len(stack),
            f"must hold at least {least} image{'s' if least > 1 else ''} (a route of fewer than two images)",
        )
    shapes = sorted({v.shape for v in stack}, key=str)
    if len(shapes) > 1 or len(shapes[0]) != 2:
        raise InputError(field, [list(s) for s in shapes[:3]], "must be 2-D images all of one size")
    a = np.stack(stack).astype(np.float32)
    bad = ~np.isfinite(a)
    if bad.any():
        i = np.argwhere(bad)[0].tolist()
        raise InputError(f"{field}[{i[0]}]", float(a[tuple(i)]), f"has a non-finite pixel at row {i[1]}, column {i[2]}")
    return a


def checked_masks(masks, shape: tuple[int, ...], field: str = "masks") -> np.ndarray | None:
    """Boolean masks of `shape` ((H, W) or (N, H, W); one (H, W) mask is used for every image), none empty."""
    if masks is None:
        return None
    m = np.asarray(masks)
    if m.shape not in (tuple(shape), tuple(shape[-2:])):
        raise InputError(field, list(m.shape), f"must be of the images' size {list(shape[-2:])}")
    m = np.broadcast_to(m.astype(bool), shape)
    empty = ~m.reshape(-1, shape[-2] * shape[-1]).any(-1) if m.ndim == 3 else np.array([not m.any()])
    if empty.any():
        raise InputError(field, int(np.argmax(empty)), "has an empty mask (no pixel kept): nothing to compare")
    return m


def train_model(name: str, views, masks=None, seed: int = 0, **settings) -> FamiliarityModel:
    """Model `name` trained on route images `views` ((N, H, W) or a list, N >= 2, in route order; 8-bit
    scale), with perfect memory's `masks`, checked before any work (docs/familiarity.md §2)."""
    model_settings(name, **settings)
    v = checked_images(views, "views", least=2)
    m = checked_masks(masks, v.shape)
    if name == "mushroom-body" and np.any(v.max((1, 2)) == v.min((1, 2))):
        raise InputError(
            "views",
            int(np.argmax(v.max((1, 2)) == v.min((1, 2)))),
            "is a constant image (the mushroom body normalises by its range)",
        )
    return make_model(name, v.shape[1:], seed, **settings).train(v, m)


def ridf(view, snapshots, kind: str = "abs", view_mask=None, snapshot_masks=None) -> np.ndarray:
    """(S, W) rotational image differences (`core/familiarity/ridf.py`, BoB's table and scale) of a view
    (H, W) against snapshots (S, H, W), with masks (None: every pixel), checked first."""
    choice(kind, "kind", KINDS)
    v = checked_images([view], "view")[0]
    s = checked_images(snapshots, "snapshots")
    if s.shape[1:] != v.shape:
        raise InputError("snapshots", list(s.shape[1:]), f"must be of the view's size {list(v.shape)}")
    vm = checked_masks(view_mask, v.shape, "view_mask")
    sm = checked_masks(snapshot_masks, s.shape, "snapshot_masks")
    table = np.asarray(ridf_table(v, s, kind, vm, sm))
    if np.isnan(table).any():
        raise InputError(
            "view_mask and snapshot_masks", "", "keep no common pixel (or an image is constant) at some rotation"
        )
    return table
