"""The probe of the causes measured outside the run (`studies/runs/causes_probe.py`, docs/reproduce.md "Causes
measured outside the run"): its env3 variants and a tiny run of it."""

from __future__ import annotations

import numpy as np

from delvjax.studies.runs import causes_probe
from delvjax.studies.runs._common import env


def test_env3_variants_keep_the_description_and_are_reproducible():
    """The layout probe's env3 variants (studies/runs/causes_probe.py): every landmark east of home, inside the
    arena, no overlaps; the same seed gives the same layouts."""
    a, b = causes_probe.env3_variants(8, 150.0, seed=1), causes_probe.env3_variants(8, 150.0, seed=1)
    assert 0 < len(a) <= 8 and len(a) == len(b)
    for e, f in zip(a, b):
        lm = np.asarray(e.landmarks)[np.asarray(e.valid)]
        assert np.array_equal(lm, np.asarray(f.landmarks)[np.asarray(f.valid)]) and lm.shape == (4, 3)
        assert np.all(lm[:, 0] >= np.asarray(e.home)[0] + causes_probe.EAST_OF_HOME)
        assert np.all(lm[:, 0] + lm[:, 2] <= 1000.0) and np.all(lm[:, 1] - lm[:, 2] >= 0.0)
    moved = np.asarray(a[0].landmarks)[np.asarray(a[0].valid)]
    assert not np.allclose(moved, np.asarray(env("env3").landmarks)[:4])


def test_the_cause_probe_runs_and_reports_per_layout_numbers():
    """`python -m delvjax.studies.runs.causes_probe` at a tiny size (the README's promise): numbers per layout and
    per ring width, percentages in range; env3 unmoved (jitter 0) gives our env3's values."""
    lay = causes_probe.env3_layouts(n=2, spacing=250.0, acv_jitter=0.0, delv_jitter=0.0, delv_variants=1)
    assert len(lay["acv_gt45_k0_pct"]) == 2 and len(lay["delv_compass_catchment_k1_pct"]) == 1
    assert lay["acv_gt45_k0_pct"][0] == lay["acv_gt45_k0_pct"][1]  # the same layout twice
    assert all(0.0 <= v <= 100.0 for v in lay["acv_gt45_k0_pct"] + lay["delv_compass_catchment_k1_pct"])
    px = causes_probe.pixels(spacing=250.0, ds=(50.0,), widths=(360,))
    assert set(px["env1_mean_error_deg"][360]) == {"d=50"} and 0.0 <= px["env1_mean_error_deg"][360]["d=50"] < 180.0
    assert px["random3_curve_deg"][360] and all(0.0 <= v <= 180.0 for v in px["random3_curve_deg"][360])
