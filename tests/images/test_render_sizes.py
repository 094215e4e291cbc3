"""A render's memory is bounded for every image size (docs/reliability.md): large images render fewer at
a time and in smaller chunks, with the same images as the default sizes."""

from __future__ import annotations

import jax
import numpy as np
import pytest

from delvjax.images import _render
from delvjax.images._render import IMAGE_WIDTH, RENDER_BUDGET, ImageSettings, camera, render_sizes, rendered_chunks
from delvjax.images._worlds import image_world


@pytest.mark.parametrize("rows, cols", [(60, 360), (600, 3600), (4096, 16384)])
def test_a_group_and_a_chunk_of_images_stay_under_the_budget(rows, cols):
    width, chunk = render_sizes(rows * cols, 256)
    assert 1 <= width <= IMAGE_WIDTH and 1 <= chunk <= 256
    assert width * rows * cols * _render.RENDER_BYTES_PER_PIXEL <= RENDER_BUDGET or width == 1
    assert chunk * rows * cols * 3 <= RENDER_BUDGET
    if rows * cols == 60 * 360:
        assert (width, chunk) == (IMAGE_WIDTH, 256)  # the default size is untouched
    if rows == 4096:
        assert width == 1 and chunk == 10  # the largest image: 1.6 GB of working memory, one at a time


def test_smaller_groups_and_chunks_render_the_same_images(monkeypatch):
    iw = image_world("robot")
    settings = ImageSettings(camera=camera(12, 72), pixel_noise=0.02, gain_noise=0.05)
    pts = np.array([[40.0, 40.0], [90.0, 60.0], [120.0, 130.0], [60.0, 150.0], [150.0, 100.0]], np.float32)
    heads = np.linspace(0, 3, 5).astype(np.float32)
    key = jax.random.PRNGKey(3)

    def render() -> np.ndarray:
        parts = [
            np.asarray(imgs)[: hi - lo] for lo, hi, imgs in rendered_chunks(iw.world, settings, pts, heads, key, 256)
        ]
        return np.concatenate(parts)

    default = render()
    monkeypatch.setattr(_render, "RENDER_BUDGET", 12 * 72 * 3 * 2)  # two images a chunk, one a group
    assert render_sizes(12 * 72, 256) == (1, 2)
    assert np.array_equal(render(), default)
