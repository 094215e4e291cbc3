"""The thesis's simulation studies, one module per figure set; `delvjax reproduce` runs them.

Each module has `TITLE`, optionally `STEPS` (progress ticks), and `run(ctx)` with a
`delvjax.study.StudyContext`. `STUDIES` is the registry, in report order.
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
]
