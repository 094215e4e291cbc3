"""The thesis's simulation studies, one module per figure set; `delvjax reproduce` runs them.

Each module has `TITLE`, `COST` (rough seconds of a full run, the order in which studies start),
optionally `STEPS` (progress ticks), and `run(ctx)` with a `delvjax.reproduce._study.StudyContext`.
`STUDIES` is the registry, in report order.
"""

STUDIES = [
    "environments",
    "no_compass",
    "step_distance",
    "landmark_number",
    "image_matching",
    "quantization",
    "with_compass",
    "comparators",
    "occlusion",
    "visual_compass",
    "sensitivity",
    "layouts",
    "robot_images",
    "natural_images",
    "image_effects",
    "hybrid",
    "familiarity",
    "ant_world",
    "ensembles",
    "ensemble_ranges",
    "ensemble_maps",
    "ensemble_rollouts",
    "ensemble_settings",
    "ensemble_robot",
    "ensemble_hull",
]

# Studies beyond the thesis's simulations (gradients, layout design, image effects, most ensembles) and the
# two on rendered images: a full run has them, `--quick` (a preview of the thesis's simulation
# experiments) leaves them out unless `--only` names them. Together they were 177 of the 331 s of a
# cold `--quick` on 2 CPU cores, 150 s of it compilation (docs/reproduce.md "Speed").
FULL_RUN_ONLY = (
    "sensitivity",
    "layouts",
    "robot_images",
    "natural_images",
    "image_effects",
    "hybrid",
    "familiarity",
    "ant_world",
    "ensemble_ranges",
    "ensemble_maps",
    "ensemble_rollouts",
    "ensemble_settings",
    "ensemble_robot",
    "ensemble_hull",
)

# Each study declares its own `COST`: rough seconds of it in a full run on 2 CPU cores, two side by side
# (measured 2026-12-04, `benchmarks/bench_reproduce.py`). `delvjax.reproduce` starts the studies side by
# side in that order, the longest first, so that a long one does not start last (`reproduce._run.schedule`).
