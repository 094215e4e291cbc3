"""The layouts and hidden-landmark choices of the occlusion study (Tables 5.1-5.4), and spreads
(mean, min, max) over those choices; shared by `occlusion` and its gap-aware section."""

from __future__ import annotations

import numpy as np

from delvjax.core import rollouts

ENVS = {"env1": 2, "env2": 3, "env3": 2, "ring3": 2, "ring5": 3, "ring6": 3}  # env -> largest k
RING_SPACING = 50.0
# cm: the rings' grid under --quick (5 x 5; the tiny test run's too): their 75 masks are two thirds of the study's
# trials, and --quick stays under a minute cold on 2 CPU cores (the full run keeps RING_SPACING)
QUICK_RING_SPACING = 200.0


def layout_spacing(name: str, config) -> float:
    """The grid spacing (cm) of layout `name`: env1-3 the run's, the rings at least RING_SPACING (a full run) or
    QUICK_RING_SPACING (`--quick`)."""
    if name.startswith("env"):
        return config.spacing
    return max(config.spacing, QUICK_RING_SPACING if config.quick else RING_SPACING)


def stacked_masks(e, k_max: int):
    """Masks of every k = 0..k_max stacked: (masks (M, L), hidden tuples, k of each mask)."""
    masks, hidden, ks = [], [], []
    for k in range(k_max + 1):  # input preparation: a handful of k
        m, h = rollouts.occlusion_masks(e, k)
        masks.append(m)
        hidden += h
        ks += [k] * len(h)
    return np.concatenate(masks), hidden, np.array(ks)


def spread(values) -> dict:
    v = np.asarray(values, float)
    return {"mean": float(v.mean()), "min": float(v.min()), "max": float(v.max())}


def fmt_spread(s: dict) -> str:
    return f"{s['mean']:.2f} [{s['min']:.2f}-{s['max']:.2f}]" if s["min"] != s["max"] else f"{s['mean']:.2f}"
