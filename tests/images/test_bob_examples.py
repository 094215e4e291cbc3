"""BoB robotics' own example databases (its docs' example_image_databases), entries and metadata copied
verbatim, images rendered at their poses: they load with their poses, camera and home (docs/images.md §4)."""

from __future__ import annotations

import warnings

import jax
import numpy as np
import pytest

from delvjax.images import load_database
from delvjax.images._evaluate import database_vector_map
from delvjax.images._render import camera, lit, render_images
from delvjax.images._worlds import image_world
from tests.cases.bob import bob_file_image, bob_read

pytest.importorskip("cv2")  # OpenCV's own parser (opencv-python-headless, a test dependency)

EXAMPLE_GRID = """X [mm], Y [mm], Z [mm], Heading [degrees], Filename, Grid X, Grid Y, Grid Z
0, 0, 10, 0, image_+000000_+000000_+000010.png, 0, 0, 0
1000, 0, 10, 0, image_+001000_+000000_+000010.png, 1, 0, 0
0, 1000, 10, 0, image_+000000_+001000_+000010.png, 0, 1, 0
1000, 1000, 10, 0, image_+001000_+001000_+000010.png, 1, 1, 0
"""
EXAMPLE_ROUTE = """X [mm], Y [mm], Z [mm], Heading [degrees], Filename
6300, 8450, 10, 219.962, image_00000.png
6293.58, 8442.34, 10, 219.962, image_00001.png
6287.26, 8434.58, 10, 219.159, image_00002.png
"""
EXAMPLE_META = """%YAML:1.0
---
metadata:
   time: "2019-01-29 13:0{m}:1{s}"
   type: {kind}
{grid}   camera:
      name: opengl
      resolution: [ 720, 150 ]
      isPanoramic: 0
   needsUnwrapping: 0
   isGreyscale: 0
"""
EXAMPLE_GRID_BLOCK = """   grid:
      beginAtMM: [ 0., 0., 10. ]
      separationMM: [ 1000., 1000., 0. ]
      size: [ 2, 2, 1 ]
"""


@pytest.mark.parametrize("kind", ["grid", "route"])
def test_bobs_example_databases_load_with_their_poses(tmp_path, kind):
    """BoB's docs/example_image_databases, entries and metadata copied verbatim (720 x 150 images, here
    rendered in env1 at those poses, as BoB's ant world would have shown them there)."""
    import cv2

    folder = tmp_path / kind
    folder.mkdir()
    text = EXAMPLE_GRID if kind == "grid" else EXAMPLE_ROUTE
    (folder / "database_entries.csv").write_text(text)
    meta = EXAMPLE_META.format(
        m=5 if kind == "grid" else 7,
        s=4 if kind == "grid" else 5,
        kind=kind,
        grid=EXAMPLE_GRID_BLOCK if kind == "grid" else "",
    )
    (folder / "database_metadata.yaml").write_text(meta)
    rows = [ln.split(", ") for ln in text.splitlines()[1:]]
    mm = np.array([[float(r[0]), float(r[1])] for r in rows])
    compass = np.array([float(r[3]) for r in rows])
    iw = image_world("env1")
    cam = camera(150, 720, 60.0, -15.0, 1.0)
    column0 = np.mod(270.0 - compass, 360.0)
    mem = np.asarray(
        render_images(
            lit(iw.world, None),
            cam,
            None,
            (mm / 10).astype(np.float32),
            np.radians(column0).astype(np.float32),
            np.arange(len(rows)),
            jax.random.PRNGKey(0),
            0.0,
            0.0,
        )
    )
    for m, c, b, r in zip(mem, column0, compass, rows):
        assert cv2.imwrite(str(folder / r[4]), np.ascontiguousarray(bob_file_image(m, c, b)[..., ::-1]))
    assert bob_read(folder)["type"] == kind
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the camera and its height come from the files: nothing assumed
        db = load_database(folder)
    assert db.spacing == (100.0 if kind == "grid" else pytest.approx(1.0, abs=0.01))  # the grid block's 1000 mm
    assert db.kind == kind and (db.camera.rows, db.camera.cols) == (150, 720)
    assert (db.camera.elev_top_deg, db.camera.elev_bottom_deg, db.camera.height) == (60.0, -15.0, 1.0)
    np.testing.assert_allclose(db.absolute(np.asarray(db.rings.positions, np.float64)), mm / 10, atol=1e-4)
    np.testing.assert_allclose(np.degrees(np.asarray(db.rings.headings)) % 360, column0, atol=1e-4)
    assert db.home_index == (
        len(rows) - 1 if kind == "route" else 0
    )  # the route's end; the grid's first nearest the centre
    vm = database_vector_map(db, "alv")
    assert np.asarray(vm.valid)[np.asarray(vm.included)].all()
