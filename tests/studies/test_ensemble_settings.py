"""The joint estimate of the unstated settings (`studies/runs/ensemble_settings.py`): the orthogonal array, the
score, and the estimator on synthetic member numbers, where it must recover a planted setting and say "not
identified" of settings the numbers do not depend on."""

from __future__ import annotations

import numpy as np
import pytest

from delvjax.studies.runs import _settings_design as design_
from delvjax.studies.runs import _settings_estimate as est
from delvjax.studies.runs import ensemble_settings

SETTINGS = list(design_.SETTINGS)


def test_the_design_is_the_full_factorial_under_both_rule_sets_and_starts_at_the_defaults():
    d = design_.design()
    assert d.shape == (48, 4) and not d[0].any() and len({tuple(r) for r in d}) == 48
    assert design_.combination(d[0]) == {n: v[1][0] for n, v in design_.SETTINGS.items()}
    assert list(d[:, -1]) == [0, 1] * 24  # each run under the default rules, then its physical twin
    assert design_.sweep_settings(d[0]) == {
        "bearing_noise_deg": 0.0,
        "home_radius": 50.0,
        "step_noise": 0.0,
        "odometry_turn_noise_deg": 0.0,
        "collisions": "ignore",
    }
    noisy = design_.sweep_settings(d[3])  # run 1: the default bearing noise and radius, odometry noise
    assert noisy["step_noise"] == 0.1 and noisy["odometry_turn_noise_deg"] == 3.0 and noisy["collisions"] == "fail"
    preview = design_.design(ensemble_settings.PREVIEW["runs"])  # every value of every setting at least once
    for j, name in enumerate(SETTINGS):
        assert set(preview[:, j]) == set(range(len(design_.SETTINGS[name][1]))), name


def test_the_score_is_the_crps_and_a_single_world_gives_the_absolute_gap():
    rng = np.random.default_rng(0)
    x, t = rng.uniform(0, 100, (3, 5, 4)), rng.uniform(0, 100, 5)
    s = est.scores(x, t, np.ones((1, 4)))
    assert s[0] == pytest.approx(est.crps(x, t[None, :]).mean(axis=1))
    one = est.scores(x[:, :, :1], t, np.ones((1, 1)))[0]  # one member: mean |ours - thesis|
    assert one == pytest.approx(np.abs(x[:, :, 0] - t).mean(axis=1))
    w = np.array([2.0, 0.0, 1.0, 1.0])  # a resample: member 0 twice, member 1 left out
    again = x[:, :, [0, 0, 2, 3]]
    near = np.abs(again - t[None, :, None]).mean(axis=-1)
    pairs = [(i, j) for i in range(4) for j in range(4) if i != j]  # pairs of different members, by their counts
    spread = sum(w[i] * w[j] * np.abs(x[:, :, i] - x[:, :, j]) for i, j in pairs) / (16 - (w**2).sum())
    assert est.scores(x, t, w[None])[0] == pytest.approx((near - 0.5 * spread).mean(axis=1))
    # a resample's score is not biased upwards by its copies: over many resamples it averages near the sample's
    many = est.scores(x, t, est.resample_weights(4, 4000, seed=0))
    assert np.abs(many[1:].mean(axis=0) - many[0]).max() < 0.05 * np.abs(many[0]).max()
    # a narrow distribution at the thesis's number beats a wide one around it and a narrow one beside it
    narrow, wide, beside = (np.full((1, 1, 8), 50.0) + d for d in (0.0, np.linspace(-30, 30, 8), 20.0))
    t50 = np.array([50.0])
    assert est.crps(narrow, t50[None]) < est.crps(wide, t50[None]) < est.crps(beside, t50[None])


def test_resamples_draw_members_with_replacement():
    w = est.resample_weights(12, 500, seed=3)
    assert w.shape == (501, 12) and np.all(w[0] == 1.0) and np.all(w.sum(axis=1) == 12)
    assert (w[1:] == 0).any(axis=1).mean() > 0.9  # almost every resample leaves a member out
    assert np.array_equal(w, est.resample_weights(12, 500, seed=3))


def synthetic(slope: dict[str, float], planted: dict[str, int], members: int = 12, seed: int = 0):
    """Member numbers over the design that move by about slope[name] points per value index of a setting (each
    number by its own share, 0-2 times: settings move different numbers), the thesis's numbers those of the
    planted value indices; every member its own offset per number (its world and seed), shared by every
    combination, and a little noise of each combination's own."""
    rng = np.random.default_rng(seed)
    d = design_.design()
    n = 40
    base = rng.uniform(20, 80, n)
    load = rng.uniform(0.0, 2.0, (len(SETTINGS), n))
    world = rng.normal(0, 6.0, (n, members))
    shift = sum(slope.get(name, 0.0) * d[:, [j]] * load[j] for j, name in enumerate(SETTINGS))  # (C, N)
    shift = shift + np.zeros((len(d), n))
    x = base[None, :, None] + shift[:, :, None] + world[None] + rng.normal(0, 0.5, (len(d), n, members))
    t = base + sum(slope.get(name, 0.0) * planted.get(name, 0) * load[j] for j, name in enumerate(SETTINGS))
    return d, x, t


def estimate(d, x, t, members: int = 12):
    s = est.scores(x, t, est.resample_weights(members, 1000, seed=1))
    found = {name: est.identify(s, d[:, j], len(design_.SETTINGS[name][1]), members) for j, name in enumerate(SETTINGS)}
    return found, s


def test_a_planted_bearing_noise_is_recovered_and_the_settings_without_effect_are_not_identified():
    # bearing noise moves every number by 6 points per value (0, 1, 2, 3°); the thesis's numbers are those of 2°
    d, x, t = synthetic({"bearing_noise_deg": 6.0}, {"bearing_noise_deg": 2})
    found, s = estimate(d, x, t)
    bearing = found["bearing_noise_deg"]
    assert bearing["identified"] and bearing["best"] == 2 and bearing["kept"] == [2]
    assert bearing["share_best"][2] >= est.SHARE
    for name in ("home_radius", "odometry", "rules"):
        assert not found[name]["identified"], name
        assert len(found[name]["kept"]) > 1, name  # no value excluded
    comb = est.combinations(s)
    assert design_.combination(d[comb["best"]])["bearing_noise_deg"] == 2.0
    assert comb["indistinct"][comb["best"]] and comb["indistinct"].sum() <= len(d) // 4  # only 2° ones remain
    text = est.sentence(
        found, {n: n for n in SETTINGS}, {n: [str(v) for v in design_.SETTINGS[n][1]] for n in SETTINGS}, 12
    )
    assert text.startswith("The thesis's numbers identify the bearing_noise_deg (2.0, best in ")
    assert "They do not identify the home_radius (not excluded: " in text and text.count(". ") == 1


def test_two_planted_settings_are_recovered_together():
    d, x, t = synthetic({"bearing_noise_deg": 5.0, "rules": 12.0}, {"bearing_noise_deg": 1, "rules": 1})
    found, _ = estimate(d, x, t)
    assert found["bearing_noise_deg"]["identified"] and found["bearing_noise_deg"]["best"] == 1
    assert found["rules"]["identified"] and found["rules"]["best"] == 1
    # a mean over the combinations with each bearing noise would pick another value: the score is V-shaped, and
    # the combinations under the wrong rules favour the noise that makes up for them (why profiles)
    s = est.scores(x, t, np.ones((1, 12)))[0]
    bearing = d[:, SETTINGS.index("bearing_noise_deg")]
    assert np.argmin([s[bearing == v].mean() for v in range(4)]) != 1
    assert not found["odometry"]["identified"] and not found["home_radius"]["identified"]


def test_nothing_is_identified_when_the_numbers_do_not_depend_on_the_settings_in_one_sentence():
    d, x, t = synthetic({}, {})
    found, s = estimate(d, x, t)
    assert not any(f["identified"] for f in found.values())
    same, _ = estimate(d, np.repeat(x[:1], len(d), axis=0), t)  # every combination the same numbers: ties
    for f in same.values():
        assert not f["identified"] and len(f["kept"]) == len(f["score"])
        assert f["share_best"] == pytest.approx(100.0 / len(f["score"]))  # a tie is shared
    text = est.sentence(found, {n: n for n in SETTINGS}, {n: [] for n in SETTINGS}, 12)
    assert text.startswith("The thesis's numbers identify none") and text.count(". ") == 0 and text.endswith(".")


def test_a_setting_whose_values_are_not_told_apart_keeps_them_all():
    """A small effect (0.3 points per value) under members spread by 6 points: the best value is not best in
    80 % of the resamples, so the setting is not identified even though one value is best on the sample."""
    d, x, t = synthetic({"home_radius": 0.3}, {"home_radius": 1})
    found, _ = estimate(d, x, t)
    assert not found["home_radius"]["identified"]


def test_thesis_numbers_are_read_from_their_cell_and_rule_set():
    items = design_.targets()
    assert len(items) == 90 and {r[1] for r in items} == set(design_.FAMILIES)  # Figs 4.5, 5.5, 5.10, Tables 5.1, 5.3
    runs, members = 2, 3
    shape = (runs, len(design_.FAMILIES), members, len(design_.PAIRS))
    code = np.arange(np.prod(shape), dtype=float).reshape(shape)
    values = {"catchment": code, "catchment_physical": -code, "gt45": code + 0.25, "gt90": code + 0.5}
    x = design_.numbers(values, items)
    assert x.shape == (runs * 2, 90, members)
    for n, (_, fam, method, k, q, _) in enumerate(items):
        f, p = design_.FAMILIES.index(fam), design_.PAIRS.index((method, k))
        for r in range(runs):
            ours = values[q][r, f, :, p]
            assert np.array_equal(x[2 * r, n], ours)  # the default rules
            physical = values["catchment_physical"][r, f, :, p] if q == "catchment" else ours
            assert np.array_equal(x[2 * r + 1, n], physical)  # the physical rules: the restated catchment


def test_a_preview_identifies_nothing():
    d, x, t = synthetic({"bearing_noise_deg": 6.0}, {"bearing_noise_deg": 2}, members=2)
    found, _ = estimate(d, x, t, members=2)
    assert not any(f["identified"] for f in found.values())
    assert est.sentence(found, {}, {}, 2).startswith("With 2 members per world (a preview)")
