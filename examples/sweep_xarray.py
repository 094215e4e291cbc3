"""A small parameter sweep (DELV and ALV, two step distances, bearing noise, three seeds) read as xarray.

    python examples/sweep_xarray.py        # writes examples_out/sweep/ (sweep.nc, sweep.csv, sweep.toml)

Every combination of the axes is one cell; cells of one shape share one compiled program
(docs/sweeps.md). The result is an `xarray.Dataset` with one dimension per axis of more than one
value (the axis `method` as `homing_method`), CF `units` and `long_name` on every variable.
"""

from pathlib import Path

from delvjax.sweeps import load_sweep, run_sweep, save_sweep
from delvjax.sweeps._spec import parse_sweep

SWEEP = """
[sweep]
kind = "vector-map"
metrics = ["gt45_pct", "mean_error_deg"]

[axes]
env = ["env1"]
method = ["delv", "alv"]
d = [30, 60]
bearing_noise_deg = [0.0, 3.0]
seed = [0, 1, 2]
spacing = [100]
"""

out = Path("examples_out") / "sweep"
out.mkdir(parents=True, exist_ok=True)
ds = run_sweep(parse_sweep(SWEEP), out=out)  # finished chunks are kept: a rerun resumes
save_sweep(ds, out)

# mean over seeds, one number per method, d and noise level
mean = ds.mean_error_deg.mean("seed")
print(mean.to_dataframe().reset_index().to_string(index=False))
print("units:", ds.mean_error_deg.attrs["units"], "| environment:", ds.env_name.item(), "| spacing:", float(ds.spacing))
cost = mean.sel(bearing_noise_deg=3.0) - mean.sel(bearing_noise_deg=0.0)
print("what 3° of bearing noise costs, degrees of mean error:")
print(cost.to_pandas())  # methods x d
# the axis `method` is the dimension `homing_method` (`method` is a keyword of xarray's `sel`: docs/sweeps.md)
delv = ds.mean_error_deg.sel(homing_method="delv", d=60).mean("seed")
print("DELV at d = 60 cm, mean error by noise:", delv.values.round(2).tolist())
assert load_sweep(out).mean_error_deg.identical(ds.mean_error_deg)  # the netCDF file holds the same
