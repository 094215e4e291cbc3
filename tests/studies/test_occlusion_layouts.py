"""The occlusion study's grids: --quick puts the rings on a coarser grid, a full run keeps its own."""

from __future__ import annotations

from delvjax.reproduce._study import RunConfig
from delvjax.studies.runs._occlusion_layouts import ENVS, QUICK_RING_SPACING, RING_SPACING, layout_spacing


def test_quick_puts_the_rings_on_the_preview_grid_and_a_full_run_keeps_its_own():
    quick, full, tiny = RunConfig.make(quick=True), RunConfig.make(), RunConfig(spacing=200.0, trials=10)
    rings = [n for n in ENVS if not n.startswith("env")]
    assert rings == ["ring3", "ring5", "ring6"]
    for name in rings:
        assert layout_spacing(name, quick) == QUICK_RING_SPACING == 200.0
        assert layout_spacing(name, full) == max(full.spacing, RING_SPACING) == 50.0  # the full run unchanged
        assert layout_spacing(name, tiny) == 200.0
    for name in ("env1", "env2", "env3"):  # env1-3 on the run's grid, quick or not
        assert layout_spacing(name, quick) == quick.spacing == 100.0
        assert layout_spacing(name, full) == full.spacing
