"""A DELV vector map of the thesis's first environment, its headline numbers, a figure and a table.

    python examples/vector_map.py          # writes examples_out/vector_map.png and .csv

`delvjax.vector_map` computes every grid point as one JAX program (docs/model.md §5); the result is
a `VectorMap` of arrays, with `.to_dataframe()` (pandas) and `.to_xarray()` (a labelled grid) views.
"""

from pathlib import Path

import delvjax
from delvjax import Grid
from delvjax.plots import vector_map_figure

out = Path("examples_out")
out.mkdir(exist_ok=True)

vm = delvjax.vector_map("env1", method="delv", seed=0, grid=Grid(spacing=50.0))  # thesis defaults: d = 50 cm
numbers = delvjax.summarize_map(vm.error_deg, vm.valid, vm.included)
print(
    f"{numbers['points']} points: e > 45° at {numbers['gt45_pct']:.1f} %, mean error {numbers['mean_error_deg']:.1f}°"
)

table = vm.to_dataframe()  # one row per grid point: x, y, heading_deg, direction_deg, error_deg, valid, ...
table.to_csv(out / "vector_map.csv", index=False)
grid = vm.to_xarray()  # error_deg etc. over (y, x), in cm
print("worst row (y):", float(grid.error_deg.mean("x").idxmax()))

fig = vector_map_figure(delvjax.load_env("env1"), vm, spacing=50.0, title="DELV, env1", classes=True)
fig.savefig(out / "vector_map.png", dpi=120)
