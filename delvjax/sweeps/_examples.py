"""Documented example sweep files, one per kind (`delvjax sweep --example KIND`; docs/sweeps.md)."""

EXAMPLES = {
    "vector-map": """# delvjax sweep file: every combination of the axes is one cell (docs/sweeps.md).
# Run: delvjax sweep this.toml --out results/sweep ; read: delvjax.load_sweep("results/sweep")
# Other kinds: delvjax sweep --example catchment | success-rate

[sweep]
kind = "vector-map"                  # vector-map metrics of every cell
metrics = ["gt45_pct", "gt90_pct", "mean_error_deg", "mean_error_ci95_deg", "invalid_pct"]

[axes]                               # a list, or an inclusive range {start, stop, step} / {start, stop, num}
env = ["env1", "env2"]               # presets or JSON paths (default ["env1"])
# env = ["env1", {random = 20, landmarks = [3, 6], seed = 0}]  # + 20 seeded random layouts of 3 and of 6
method = ["delv", "delv-compass"]    # registry names (default ["delv"])
d = { start = 10, stop = 100, step = 30 }
bearing_noise_deg = [0.0, 2.0]
seed = { start = 0, stop = 2 }       # integer range, step 1 (default [0])
# spacing = [25]                     # grid spacing, cm (default 25)
# levels, n_heading, background, step_noise, turn_noise_deg, odometry_turn_noise_deg,
# compass_noise_deg: the options of `delvjax vector-map` of the same name
""",
    "catchment": """# delvjax sweep file: a catchment area per cell (docs/sweeps.md "Rollout sweeps").
# Run: delvjax sweep this.toml --out results/catchment

[sweep]
kind = "catchment"                   # a rollout from every grid point of every cell (Tables 5.3/5.4)
metrics = ["catchment_pct", "catchment_min_pct", "gt45_pct", "mean_steps_success"]

[axes]
env = ["env1"]
method = ["delv", "alv"]
occlude = [0, 1, 2]                  # every choice of k hidden landmarks; metrics pool the masks
first_move = ["homing", "release"]   # rollout rules (docs/model.md section 5)
collisions = ["ignore", "fail"]
seed = [0, 1]
# d, levels, the noise sigmas, motion_heading_noise_deg, motion_step_noise, home_radius,
# max_steps and spacing: the options of `delvjax catchment` of the same name
""",
    "success-rate": """# delvjax sweep file: success rate per release distance (docs/sweeps.md "Rollout sweeps").
# Run: delvjax sweep this.toml --out results/success

[sweep]
kind = "success-rate"                # Figs 4.10b, 5.7b: a "distance_cm" dimension is added
metrics = ["success_pct", "success_ci95_lo_pct", "success_ci95_hi_pct"]
distances = [50, 150, 250, 350]      # cm from home (default 50, 100, ..., 450)
trials = 50                          # release points per distance and cell (default 100)

[axes]
method = ["delv", "alv"]
bearing_noise_deg = { start = 0, stop = 4, step = 2 }
motion_heading_noise_deg = [0, 10]
seed = [0, 1]
""",
    "route-following": """# delvjax sweep file: route following by familiarity (docs/sweeps.md "Route-following sweeps").
# Run: delvjax sweep this.toml --out results/following

[sweep]
kind = "route-following"             # trials from the route's start (Ardin et al. 2016; docs/familiarity.md)
metrics = ["route_success_pct", "route_success_ci95_lo_pct", "route_success_ci95_hi_pct", "mean_route_errors"]
trials = 20                          # trials per cell (default 20)

[axes]
env = ["robot"]                      # robot, natural, or an environment as for the other kinds (default robot)
method = ["perfect-memory", "infomax"]  # familiarity models (default perfect-memory)
heading_noise_deg = [30, 60, 90]     # heading noise at every move, deg (default 10)
seed = [0, 1]                        # trial noise, InfoMax's weights, the mushroom body's wiring
# route_spacing, step, view_rows, view_cols, max_steps: as `delvjax familiarity`;
# a model's settings (kind, select, n_best, window_ahead, window_behind, learning_rate, rate_divisor,
# normalise, n_hidden, n_kc, pn_per_kc, n_active) apply to that model's cells only: sweep one model
""",
}
EXAMPLE = EXAMPLES["vector-map"]
