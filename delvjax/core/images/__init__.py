"""Colour worlds, the panoramic and catadioptric renderer, and the omnidirectional image pipeline
(docs/images.md): from a camera image to the ring images and blobs every homing method reads."""

from .pipeline import Extractor, camera_noise, gray_bytes, rgb_to_hsv, ring_snapshot, segment, to_uint8, unwrap
from .render import donut, panorama, panoramas
from .scene_panorama import ScenePanorama
from .world import Camera, Catadioptric, World

__all__ = [
    "Camera",
    "Catadioptric",
    "World",
    "donut",
    "panorama",
    "panoramas",
    "Extractor",
    "camera_noise",
    "gray_bytes",
    "ScenePanorama",
    "rgb_to_hsv",
    "ring_snapshot",
    "segment",
    "to_uint8",
    "unwrap",
]
