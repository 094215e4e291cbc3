"""The model as array programs (docs/architecture.md): methods as equinox modules, the sensor and its
noise, sensing, distance estimation, the per-point kernel, vector maps, rollouts, metrics.

The core never reads files, prints, parses options or looks a method up by name; the rest of
`delvjax` (the edge) does that and depends on the core, never the reverse.
"""
