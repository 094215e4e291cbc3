"""Panoramas between delvjax and navipy (docs/images.md §9, docs/navipy.md).

delvjax in memory: a panorama (..., H, W, C), row 0 the highest elevation, column j looking along
heading + 360 j / W (counter-clockwise; docs/images.md §2). navipy 0.1.2: a scene (H, W, 4, 1), channels
R, G, B, D (distance), row 0 the lowest elevation and azimuth growing counter-clockwise with the column
from -180° at column 0, so column W // 2 looks along the heading (azimuth 0). Only numpy is used.
"""

from __future__ import annotations

import numpy as np
from jax.typing import ArrayLike


def to_navipy(panorama: ArrayLike, distance: ArrayLike | None = None) -> np.ndarray:
    """A delvjax in-memory panorama (..., H, W, 3) or (..., H, W, 4) (RGB, or RGB and distance) -> a navipy
    scene (..., H, W, 4, 1) (docs/images.md §9).

    Rows are flipped (navipy's row 0 is the lowest elevation) and columns rolled by W // 2 (delvjax's
    column 0, the heading, becomes navipy's azimuth 0). For an RGB panorama, `distance` (broadcast to
    (..., H, W), delvjax order, cast to the panorama's dtype) fills navipy's D channel; zeros when None.
    """
    pano = np.asarray(panorama)
    if pano.ndim < 3 or pano.shape[-1] not in (3, 4) or (pano.shape[-1] == 4 and distance is not None):
        raise ValueError(f"panorama must be (..., H, W, 3), or (..., H, W, 4) without distance, got {pano.shape}")
    if pano.shape[-1] == 3:
        d = np.zeros(pano.shape[:-1], pano.dtype) if distance is None else np.asarray(distance)
        pano = np.concatenate([pano, np.broadcast_to(d, pano.shape[:-1]).astype(pano.dtype)[..., None]], axis=-1)
    width = pano.shape[-2]
    return np.roll(np.flip(pano, axis=-3), width // 2, axis=-2)[..., None]


def from_navipy(scene: ArrayLike, distance: bool = False) -> np.ndarray:
    """A navipy scene (..., H, W, 4, 1) -> a delvjax in-memory panorama (..., H, W, 3) (docs/images.md §9).

    The inverse of `to_navipy`: the columns are rolled back by W // 2 and the rows flipped. With
    `distance`, navipy's D channel is kept as a fourth channel, (..., H, W, 4), which `to_navipy` takes back.
    """
    s = np.asarray(scene)
    if s.ndim < 4 or s.shape[-2:] != (4, 1):
        raise ValueError(f"scene must be navipy's (..., H, W, 4, 1), got {s.shape}")
    rgbd = s[..., 0] if distance else s[..., :3, 0]
    width = s.shape[-3]
    return np.flip(np.roll(rgbd, -(width // 2), axis=-2), axis=-3)
