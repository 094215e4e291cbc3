"""The thesis's simulation studies, one module per figure set; `delvjax reproduce` runs them.

Each module has `TITLE`, optionally `STEPS` (progress ticks), and `run(ctx)` with a
`delvjax.reproduce._study.StudyContext`. `STUDIES` is the registry, in report order.
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
    "fit",
    "visual_compass",
    "sensitivity",
    "layouts",
    "robot_images",
    "natural_images",
    "image_effects",
    "hybrid",
    "ensembles",
]

# Studies beyond the thesis's simulations (the fit, gradients, layout design, image effects) and the
# two on rendered images: a full run has them, `--quick` (a preview of the thesis's simulation
# experiments) leaves them out unless `--only` names them. Together they were 177 of the 331 s of a
# cold `--quick` on 2 CPU cores, 150 s of it compilation (docs/reproduce.md "Speed").
FULL_RUN_ONLY = ("fit", "sensitivity", "layouts", "robot_images", "natural_images", "image_effects", "hybrid")

# Rough seconds of each study in a full run on 2 CPU cores, two side by side (measured 2026-12-04,
# `benchmarks/bench_reproduce.py`): only the order in which studies side by side are started,
# the longest first, so that a long one does not start last. A study missing here starts last.
FULL_RUN_SECONDS = {
    "ensembles": 300,
    "occlusion": 145,
    "hybrid": 130,
    "image_effects": 95,
    "image_matching": 90,
    "fit": 90,
    "layouts": 85,
    "sensitivity": 60,
    "visual_compass": 50,
    "robot_images": 45,
    "natural_images": 45,
    "quantization": 35,
    "no_compass": 25,
    "landmark_number": 16,
    "comparators": 6,
    "with_compass": 5,
    "step_distance": 4,
    "environments": 1,
}
