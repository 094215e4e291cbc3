"""Catchment and success-rate sweeps (docs/sweeps.md "Rollout sweeps"): every cell equals the
single run of `delvjax.catchment` / `delvjax.success_rate` with the same options, occlusion counts
share one program, and the metrics are computed right."""

from __future__ import annotations

import numpy as np
import pytest

import delvjax
from delvjax import Grid, Rules
from delvjax.core.errors import InputError
from delvjax.core.rollouts import catchment_summary, wilson_interval_pct
from delvjax.core.rollouts.success import wilson_pct
from delvjax.sweeps._examples import EXAMPLES
from delvjax.sweeps._run import run_sweep
from delvjax.sweeps._spec import KINDS, parse_sweep

CATCHMENT = """
[sweep]
kind = "catchment"
[axes]
method = ["delv", "alv"]
occlude = [0, 1]
first_move = ["homing", "release"]
collisions = ["fail"]
bearing_noise_deg = [3.0]
seed = [4]
spacing = [100]
"""
SUCCESS = """
[sweep]
kind = "success-rate"
distances = [100, 250]
trials = 12
[axes]
method = ["alv"]
occlude = [0, 1]
motion_heading_noise_deg = [15.0]
seed = [2]
"""


@pytest.fixture(scope="module")
def catchments():
    return run_sweep(parse_sweep(CATCHMENT))


def test_a_catchment_cell_equals_the_catchment_run_with_its_options(catchments):
    ds = catchments
    assert ds.attrs["programs_compiled"] == 1  # both landmark methods, every occlusion count and rule share it
    for method in ("delv", "alv"):
        for occlude in (0, 1):
            for first_move in ("homing", "release"):
                ref = catchment_summary(
                    delvjax.catchment(
                        "env1",
                        method,
                        seed=4,
                        occlude=occlude or None,
                        bearing_noise_deg=3.0,
                        grid=Grid(spacing=100),
                        rules=Rules(first_move=first_move, collisions="fail"),
                    )
                )
                cell = ds.sel({"homing_method": method, "occlude": occlude, "first_move": first_move}).squeeze()
                where = (method, occlude, first_move)
                assert int(cell.points) == ref["points"], where
                for name in ("catchment", "gt45", "gt90"):
                    assert float(cell[f"{name}_pct"]) == pytest.approx(ref[f"{name}_pct"]["mean"], abs=1e-9), where
                assert float(cell.catchment_min_pct) == pytest.approx(ref["catchment_pct"]["min"], abs=1e-9), where
                assert float(cell.catchment_max_pct) == pytest.approx(ref["catchment_pct"]["max"], abs=1e-9), where
                rows = ref["per_mask"]
                landmark = sum(r["landmark_count"] for r in rows) / (ref["catchment_points"] * len(rows))
                assert int(cell.catchment_points) == ref["catchment_points"], where
                assert float(cell.landmark_pct) == pytest.approx(100 * landmark, abs=1e-9), where
    # the rules reach the cells: DELV's first move along the release heading changes the outcomes
    homing, release = (
        ds.sel({"homing_method": "delv", "first_move": m}).catchment_pct.values for m in ("homing", "release")
    )
    assert not np.array_equal(homing, release)


def test_cells_of_every_max_steps_share_one_program():
    """max_steps is traced (`Rollout.max_steps`): three values run one compiled program, and more moves
    only add successes (a trial home by move 10 is home by move 40)."""
    text = "[sweep]\nkind = 'catchment'\n[axes]\nmax_steps = [10, 20, 40]\nmethod = ['alv']\nspacing = [150]\n"
    ds = run_sweep(parse_sweep(text))
    assert ds.attrs["programs_compiled"] == 1
    pct = [float(ds.catchment_pct.sel(max_steps=m).squeeze()) for m in (10, 20, 40)]
    assert pct[0] <= pct[1] <= pct[2] and pct[0] < pct[2], pct


def test_a_success_rate_cell_equals_the_runs_under_each_hidden_landmark():
    from delvjax.plots._sweep import sweep_figure

    ds = run_sweep(parse_sweep(SUCCESS))
    assert ds.sizes["distance_cm"] == 2 and ds.attrs["trials_per_distance"] == 12
    kw = dict(distances=[100, 250], trials=12, seed=2, motion_heading_noise_deg=15.0)
    full = delvjax.success_rate("env1", "alv", **kw).table()
    cell = ds.sel({"occlude": 0}).squeeze()
    assert cell.placed.values.tolist() == [r["placed"] for r in full]
    assert np.allclose(cell.success_pct.values, [r["success_pct"] for r in full])
    # occlude = 1: the same release points under each of the 4 masks, pooled
    hidden = [delvjax.success_rate("env1", "alv", hidden=[i], **kw).table() for i in range(4)]
    successes = np.sum([[r["successes"] for r in t] for t in hidden], axis=0)
    placed = np.sum([[r["placed"] for r in t] for t in hidden], axis=0)
    cell = ds.sel({"occlude": 1}).squeeze()
    assert cell.placed.values.tolist() == placed.tolist()
    assert np.allclose(cell.success_pct.values, 100 * successes / placed)
    lo, hi = wilson_pct(successes, placed)
    assert np.allclose(cell.success_ci95_lo_pct.values, lo) and np.allclose(cell.success_ci95_hi_pct.values, hi)
    # one seed: the figure's band is the Wilson interval of each distance
    _, rows = sweep_figure(ds, "distance_cm", None, "success_pct")
    drawn = [r for r in rows if r["panel"] == "occlude=1"]
    assert [r["interval"] for r in drawn] == ["95 % Wilson interval"] * 2
    assert np.allclose([r["ci95_lo"] for r in drawn], lo) and np.allclose([r["ci95_hi"] for r in drawn], hi)


@pytest.mark.parametrize("confidence", [0.9, 0.95, 0.99])
def test_the_vectorised_wilson_interval_is_scipys_to_the_bit(confidence):
    """`wilson_pct` writes Newcombe's formula as scipy's binomtest does, without importing scipy.stats: the
    same float64 for every count up to 60 trials, NaN without trials; and the t quantile is scipy's t.ppf."""
    from scipy import stats

    from delvjax.core.metrics import t_quantile

    n = np.repeat(np.arange(61), np.arange(61) + 1)
    k = np.concatenate([np.arange(m + 1) for m in range(61)])
    lo, hi = wilson_pct(k, n, confidence)
    cis = [stats.binomtest(int(a), int(b)).proportion_ci(confidence, "wilson") for a, b in zip(k[1:], n[1:])]
    assert np.isnan(lo[0]) and np.isnan(hi[0])  # no trials
    assert np.array_equal(lo[1:], [100.0 * c.low for c in cis]) and np.array_equal(
        hi[1:], [100.0 * c.high for c in cis]
    )
    assert (
        wilson_interval_pct(3, 10, confidence)["ci_lo_pct"]
        == 100.0 * stats.binomtest(3, 10).proportion_ci(confidence, "wilson").low
    )
    counts = np.arange(500)
    t = t_quantile(counts, confidence)
    ref = stats.t.ppf(0.5 + confidence / 2, np.maximum(counts - 1, 1))
    assert np.all(np.isnan(t[:2])) and np.array_equal(t[2:], ref[2:])
    with pytest.raises(ValueError, match="successes"):  # as binomtest: more successes than trials
        wilson_pct(np.array([11]), np.array([10]))


@pytest.mark.parametrize("kind", KINDS)
def test_every_example_file_is_a_valid_sweep_of_its_kind(kind):
    spec = parse_sweep(EXAMPLES[kind])
    assert spec.kind == kind and spec.n_cells >= 8


@pytest.mark.parametrize(
    "text, field",
    [
        (
            "[sweep]\nkind = 'catchment'\n[axes]\nocclude = [9]",
            "cell (occlude=9, env=env1, method=delv, spacing=25.0, seed=0)",
        ),
        (
            "[sweep]\nkind = 'catchment'\n[axes]\nfirst_move = ['walk']",
            "cell (first_move=walk, env=env1, method=delv, spacing=25.0, seed=0)",
        ),
        ("[sweep]\nkind = 'success-rate'\ndistances = [5000]", "cell (env=env1, method=delv, seed=0)"),
        (
            "[sweep]\nkind = 'catchment'\n[axes]\nmax_steps = [0]",
            "cell (max_steps=0, env=env1, method=delv, spacing=25.0, seed=0)",
        ),
    ],
)
def test_an_impossible_rollout_cell_is_refused_before_any_work(text, field):
    with pytest.raises(InputError) as exc:
        run_sweep(parse_sweep(text))
    assert exc.value.field == field


def test_the_readme_sweep_file_is_valid():
    import re
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    blocks = re.findall(r"```toml\n(.*?)```", readme, re.S)
    assert blocks
    for text in blocks:
        spec = parse_sweep(text)
        assert spec.kind == "catchment" and spec.n_cells == 2 * 3 * 2 * 2 * 5


def test_random_layouts_on_the_env_axis_are_the_seeded_random_envs():
    from delvjax.envs._presets import random_env

    spec = parse_sweep("[axes]\nenv = ['env1', {random = 2, landmarks = [3, 5], seed = 7}]\nspacing = [150]\n")
    assert spec.axes["env"] == ["env1", "random7-3", "random8-3", "random7-5", "random8-5"]
    ds = run_sweep(spec)
    assert ds.attrs["programs_compiled"] <= 1  # 4 and 3 or 5 landmarks padded to one shape
    for label, (seed, n) in spec.random_envs.items():
        ref = delvjax.summarize_map(
            *(lambda v: (v.error_deg, v.valid, v.included))(
                delvjax.vector_map(random_env(seed, n, pad_to=5), grid=Grid(spacing=150))
            )
        )  # padded: one program for both counts
        assert float(ds.gt45_pct.sel({"env": label}).squeeze()) == pytest.approx(ref["gt45_pct"], abs=1e-9), label


def test_ensemble_members_on_the_env_axis_are_the_family_members():
    """issue 52: a sweep names a world ensemble as an axis (docs/sweeps.md); the members are those of
    `envs.ensemble_envs`, padded with the other worlds to one program."""
    from delvjax.envs import ensemble_envs
    from delvjax.envs._presets import env_from_dict

    spec = parse_sweep(
        "[axes]\nenv = ['env1', {ensemble = 'env1', members = 2, seed = 4}, {ensemble = 'ring5', members = 1}]\n"
        "spacing = [150]\n"
    )
    assert spec.axes["env"] == ["env1", "env1-s4-m0", "env1-s4-m1", "ring5-m0"]
    worlds = {w["name"]: w for w in [*ensemble_envs("env1", 2, seed=4), *ensemble_envs("ring5", 1)]}
    assert spec.ensemble_envs == worlds
    ds = run_sweep(spec)
    assert ds.attrs["programs_compiled"] <= 1  # 4 and 5 landmarks padded to one shape
    for label, world in worlds.items():
        vm = delvjax.vector_map(env_from_dict(world, pad_to=5), grid=Grid(spacing=150))
        ref = delvjax.summarize_map(vm.error_deg, vm.valid, vm.included)
        assert float(ds.gt45_pct.sel({"env": label}).squeeze()) == pytest.approx(ref["gt45_pct"], abs=1e-9), label


@pytest.mark.parametrize(
    "raw, field",
    [
        ("{ensemble = 'env9', members = 2}", "axes.env.ensemble"),
        ("{ensemble = 3, members = 2}", "axes.env.ensemble"),
        ("{ensemble = 'env1'}", "axes.env"),
        ("{ensemble = 'env1', members = 0}", "axes.env.members"),
        ("{ensemble = 'env1', members = 2.5}", "axes.env.members"),
        ("{ensemble = 'env1', members = 2, seed = -1}", "axes.env.seed"),
        ("{ensemble = 'env1', members = 2, factor = 0}", "axes.env.factor"),
        ("{ensemble = 'env1', members = 2, factor = 'wide'}", "axes.env.factor"),
        ("{ensemble = 'env1', members = 2, colour = 1}", "axes.env"),
        ("{ensemble = 'env1', members = 2, first = -1}", "axes.env.first"),
        ("{ensemble = 'env1', members = 100000}", "axes.env"),
    ],
)
def test_a_bad_ensemble_table_names_its_field(raw, field):
    with pytest.raises(InputError) as exc:
        parse_sweep(f"[axes]\nenv = [{raw}]\n")
    assert exc.value.field == field


@pytest.mark.parametrize(
    "raw",
    [
        "{random = 0, landmarks = 3}",
        "{random = 2}",
        "{random = 2, landmarks = 99}",
        "{random = 2, landmarks = 3, seed = -1}",
        "{random = 2, landmarks = 3, colour = 1}",
        "{random = 100000, landmarks = 3}",
    ],
)
def test_a_bad_random_layout_table_names_the_env_axis(raw):
    with pytest.raises(InputError) as exc:
        parse_sweep(f"[axes]\nenv = [{raw}]\n")
    assert exc.value.field == "axes.env"


@pytest.mark.parametrize("kind", KINDS)
def test_sweep_example_prints_the_example_of_a_kind(kind, capsys):
    from delvjax.cli._main import main

    assert main(["sweep", "--example", kind]) == 0
    assert parse_sweep(capsys.readouterr().out).kind == kind


@pytest.mark.parametrize(
    "text, field",
    [
        ("[axes]\nd = {start = 1, stop = 1e12, step = 1}", "axes.d"),
        ("[axes]\nd = {start = 1, stop = 2, num = 1000000000}", "axes.d"),
        ("[axes]\nd = {start = 1, stop = 1000, num = 1000}\nseed = {start = 0, stop = 99999}", "axes"),
    ],
)
def test_a_huge_sweep_is_refused_at_once(text, field):
    import time

    t = time.perf_counter()
    with pytest.raises(InputError) as exc:
        parse_sweep(text)
    assert exc.value.field == field and time.perf_counter() - t < 1.0


def test_an_output_folder_on_a_file_system_that_refuses_writes_is_refused_before_any_work(tmp_path, capsys):
    from pathlib import Path

    from delvjax.cli._main import main

    if not Path("/proc/self").is_dir():
        pytest.skip("no /proc")
    sweep = tmp_path / "s.toml"
    sweep.write_text("[axes]\nspacing = [200]\n")
    assert main(["sweep", str(sweep), "--out", "/proc/delvjax-out"]) == 2
    assert capsys.readouterr().err.startswith("delvjax: error: --out: is not writable (folder /proc")


def test_padding_runs_no_trials_and_moves_no_number():
    """A chunk padded to its program's size (`evaluate`'s `real`): the padding's cells run no trials
    (`idle_padding`: no masks) and every real cell's numbers are those of the chunk padded with running copies."""
    from delvjax.sweeps._kinds import cell_setup, evaluate, mask_rows
    from delvjax.sweeps._run import _envs

    spec = parse_sweep(SUCCESS, "padded")
    envs = _envs(spec)
    setups = [cell_setup(spec, envs, spec.cell(i), 10_000) for i in range(spec.n_cells)]
    chunk, rows = setups + [setups[0]] * 2, max(mask_rows(s) for s in setups)
    idle = evaluate(spec.kind, chunk, None, rows, lanes=16, real=len(setups))
    running = evaluate(spec.kind, chunk, None, rows, lanes=16)
    assert running["placed"][len(setups) :].sum() > 0 and idle["placed"][len(setups) :].sum() == 0
    for name, values in idle.items():
        np.testing.assert_array_equal(values[: len(setups)], running[name][: len(setups)])


def test_sweeps_of_other_methods_and_occlusions_share_one_program():
    """`run_sweep(method_set=..., mask_rows=...)`: a sweep compiled as a MethodSet of more methods and with more mask
    rows than its own runs in the program of the sweep that needs them (nothing compiled) with the same numbers."""
    wide = parse_sweep(SUCCESS.replace('method = ["alv"]', 'method = ["alv", "acv"]').replace("[0, 1]", "[0, 2]"), "w")
    narrow = parse_sweep(SUCCESS.replace("occlude = [0, 1]", "occlude = [0]"), "n")
    run_sweep(wide, lanes=16)
    shared = run_sweep(narrow, lanes=16, method_set=("alv", "acv"), mask_rows=6)
    assert shared.attrs["programs_compiled"] == 0
    own = run_sweep(narrow, lanes=16)
    np.testing.assert_array_equal(shared["success_pct"].values, own["success_pct"].values)
