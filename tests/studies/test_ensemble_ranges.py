"""The ensemble-ranges study (`studies/runs/ensemble_ranges.py`): the lines for the report on synthetic numbers,
each factor's members relabelled under the claims' keys, and the per-claim table across the factors."""

from __future__ import annotations

import numpy as np
import pytest
import xarray

from delvjax.studies import thesis
from delvjax.studies.runs import ensemble_ranges as er
from delvjax.studies.runs._ensemble_stats import claim_rows
from delvjax.studies.runs.ensembles import EVERY_METHOD
from delvjax.sweeps._spec import parse_sweep

CLAIM = "acv_error_grows_faster_than_delv"  # reads occlusion:<env>:<method>:gt45 of env1-3 only
NUMBER = 1 + [c["id"] for c in thesis.CLAIMS].index(CLAIM)
OTHER = "occlusion_increases_errors"


def test_a_verdict_that_changes_gets_one_line_and_one_that_does_not_gets_none():
    flat = {
        f"ensemble_ranges:{CLAIM}": [90.0, 60.0, 10.0],  # holds / depends on the world / fails
        f"ensemble_ranges:{CLAIM}:interval": [72.2, 97.2, 38.7, 78.1, 2.5, 27.8],
        f"ensemble_ranges:{CLAIM}:paired_p": [0.0313, 0.0039],
        f"ensemble_ranges:{OTHER}": [5.0, 0.0, 15.0],  # fails at every factor: no line
        "ensemble_ranges:members": 22,
    }
    lines = er.verdict_change_lines(flat)
    assert lines == [
        f"Claim {NUMBER} ({CLAIM}): depends on the world at the default ranges (60 % of worlds [39-78 %]); "
        "narrowed by a third holds (90 % [72-97 %], paired p = 0.031), widened by a third fails "
        "(10 % [2-28 %], paired p = 0.0039)."
    ]
    # the verdict lines are those of the claims table: 80 % holds, 79.9 % does not
    assert er.verdict_change_lines({f"ensemble_ranges:{CLAIM}": [80.0, 80.0, 80.0]}) == []
    assert len(er.verdict_change_lines({f"ensemble_ranges:{CLAIM}": [80.0, 79.9, 80.0]})) == 1
    assert er.verdict_change_lines({}) == []  # the study was not run


def test_a_ceiling_decides_the_verdict_in_the_lines():
    """Most members at a ceiling: 'cannot tell' at that factor, whatever the share."""
    flat = {f"ensemble_ranges:{CLAIM}": [0.0, 0.0, 0.0], f"ensemble_ranges:{CLAIM}:cannot_tell": [60.0, 0.0, 0.0]}
    (line,) = er.verdict_change_lines(flat)
    assert "narrowed by a third cannot tell" in line and "widened by a third fails (0 %)" in line


def sweep_of(labels: list[str]) -> xarray.Dataset:
    """A catchment sweep's Dataset over `labels` whose every number is the label's index (+ k and method offsets)."""
    n, m, k = len(labels), len(EVERY_METHOD), 3
    base = np.arange(n)[:, None, None] * 10.0 + np.arange(m)[None, :, None] + np.arange(k)[None, None, :] * 0.1
    dims = ("env", "homing_method", "occlude")
    data = {v: (dims, base) for v in ("catchment_pct", "gt45_pct", "gt90_pct", "mean_error_deg")}
    coords = {"env": labels, "homing_method": list(EVERY_METHOD), "occlude": list(range(k)), "seed": 3}
    return xarray.Dataset(data, coords=coords)


def test_each_factors_members_are_read_under_the_default_familys_keys():
    labels = ["env1x0.666667-s3-m0", "env1-s3-m0", "env1x1.33333-s3-m0", "env2x0.666667-s3-m1", "env2-s3-m1"]
    found = er.numbers_by_factor(sweep_of(labels), er.GROUP)
    assert sorted(found) == sorted(er.FACTORS)
    assert sorted(found[2 / 3]) == ["env1-m0", "env2-m1"] and sorted(found[1.0]) == ["env1-m0", "env2-m1"]
    assert sorted(found[4 / 3]) == ["env1-m0"]
    delv = EVERY_METHOD.index("delv-compass")
    assert found[2 / 3]["env1-m0"]["occlusion:env1:delv-compass:gt45"] == pytest.approx([delv, delv + 0.1, delv + 0.2])
    assert found[1.0]["env1-m0"]["catchment:env1:delv-compass"] == pytest.approx(10.0 + delv)
    assert found[4 / 3]["env1-m0"]["map:env1:delv-compass:mean_error_deg"] == pytest.approx(20.0 + delv)
    assert found[1.0]["env2-m1"]["occlusion:env2:acv:catchment"][0] == pytest.approx(40.0 + EVERY_METHOD.index("acv"))


def test_the_sweep_files_hold_every_factor_in_seed_slices():
    texts = er.range_texts(er.GROUP, 3, 200.0, 5, 2)
    assert len(texts) == 2
    first, second = (parse_sweep(t, "t") for t in texts)
    envs = first.axes["env"]
    assert "env1x0.666667-s5-m0" in envs and "env3-s5-m1" in envs and "env2x1.33333-s5-m1" in envs
    assert len(envs) == 2 * 3 * 3 and len(second.axes["env"]) == 1 * 3 * 3
    assert "env1x1.33333-s5-m2" in second.axes["env"]
    assert first.axes["seed"] == [5] and second.axes["seed"] == [6]  # slice j under the seed + j
    # member i at factor 1 is the ensembles study's member i (the same layouts)
    assert first.ensemble_envs["env1-s5-m0"]["landmarks"] != first.ensemble_envs["env1x0.666667-s5-m0"]["landmarks"]


def claim_world(acv_rise: float) -> dict:
    """One member's numbers for CLAIM: ACV's e > 45 rate rises by acv_rise over k, DELV (compass)'s by 4."""
    return {
        **{f"occlusion:{e}:delv-compass:gt45": [5.0, 7.0, 9.0] for e in ("env1", "env2", "env3")},
        **{f"occlusion:{e}:acv:gt45": [5.0, 5.0 + acv_rise / 2, 5.0 + acv_rise] for e in ("env1", "env2", "env3")},
    }


def test_the_table_gives_each_factors_share_the_paired_test_and_whether_the_verdict_changes():
    """CLAIM holds in members 0-5 at 2/3, in all 10 at 1, in 1-9 at 4/3: 6, 10 and 9 of 10."""
    holds = {2 / 3: range(6), 1.0: range(10), 4 / 3: range(1, 10)}
    by_factor, held = {}, {}
    for factor, where in holds.items():
        worlds = {
            f"{e}-m{i}": {k: v for k, v in claim_world(40.0 if i in where else 1.0).items() if f":{e}:" in k}
            for i in range(10)
            for e in ("env1", "env2", "env3")
        }
        by_factor[factor] = {r["id"]: r for r in claim_rows(worlds, 10, {}, ids={CLAIM, OTHER})}
        held[factor] = er.member_holds(worlds, 10, ids=(CLAIM, OTHER))
    assert held[2 / 3][CLAIM].tolist() == [True] * 6 + [False] * 4
    (row,) = [r for r in er.claim_table(by_factor, held) if r["id"] == CLAIM]
    assert row["#"] == NUMBER and row["members"] == 10
    assert [row[f"{er.FACTOR_NAMES[f]}: holds %"] for f in er.FACTORS] == pytest.approx([60.0, 100.0, 90.0])
    assert row["narrowed ×2/3: verdict"] == "depends on the world" and row["widened ×4/3: verdict"] == "holds"
    assert row["narrowed ×2/3 vs ×1: members gained / lost"] == "0 / 4"
    assert row["narrowed ×2/3 vs ×1: sign test p"] == pytest.approx(0.125)  # 4 of 4 one way: 2 / 2**4
    assert row["widened ×4/3 vs ×1: members gained / lost"] == "0 / 1"
    assert row["verdict changes"] == "yes: narrowed: depends on the world (paired p = 0.12)"
    same = er.claim_table({f: by_factor[1.0] for f in er.FACTORS}, {f: held[1.0] for f in er.FACTORS})
    assert [r["verdict changes"] for r in same if r["id"] == CLAIM] == ["no"]


def test_member_holds_agrees_with_claim_rows_and_leaves_out_claims_without_numbers():
    worlds = {f"{e}-m{i}": claim_world(40.0 if i % 3 else 1.0) for e in ("env1", "env2", "env3") for i in range(9)}
    held = er.member_holds(worlds, 9)
    (row,) = claim_rows(worlds, 9, {}, ids={CLAIM})
    assert 100.0 * held[CLAIM].mean() == pytest.approx(row["holds %"]) and held[CLAIM].sum() == 6
    assert "delv_nocompass_catchment_all_envs" not in held  # reads catchment:<env>:delv, absent


def test_the_sign_test_is_the_exact_binomial():
    assert er.sign_test(0, 0) == 1.0 and er.sign_test(3, 3) == 1.0
    assert er.sign_test(0, 5) == pytest.approx(2 / 32) and er.sign_test(6, 0) == pytest.approx(2 / 64)
    assert er.sign_test(1, 7) == pytest.approx(2 * 9 / 256)
