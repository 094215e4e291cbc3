"""Render an image database of the robot arena (BoB layout: PNG panoramas, database_entries.csv,
database_metadata.yaml), read it back and compare DELV with ALV on its images (docs/images.md).

    python examples/image_database.py      # writes examples_out/robot_db/ and examples_out/robot_db.png
"""

from pathlib import Path

import delvjax
from delvjax.plots import database_map_figure

out = Path("examples_out")
out.mkdir(exist_ok=True)
db_path = out / "robot_db"
if not db_path.exists():  # render once: 4 red cylinders, 1.8 m arena, one panorama every 40 cm
    delvjax.render_database("robot", db_path, spacing=40.0)
db = delvjax.load_database(db_path)  # any BoB database (or a folder of images with positions.csv)
print(f"{len(db.rings.positions)} images of {db.camera.cols} columns")
for method in ("delv-compass", "alv"):
    vm = delvjax.database_vector_map(db, method)
    numbers = delvjax.summarize_map(vm.error_deg, vm.valid, vm.included)
    print(f"{method:13s} mean error {numbers['mean_error_deg']:5.1f}°, e > 45° at {numbers['gt45_pct']:.1f} %")
fig = database_map_figure(db, vm, "ALV on the rendered robot arena")
fig.savefig(out / "robot_db.png", dpi=120)
