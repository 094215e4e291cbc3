"""The route experiments of the familiarity models (docs/familiarity.md §3) through the API and the
command line: route following that can fail, trials that do not depend on chunking, a heading field
that points along the route near it, and bad input refused in one line with nothing written."""

from __future__ import annotations

import json

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.cli._main import main
from delvjax.core.errors import InputError
from delvjax.core.familiarity.fields import heading_field
from delvjax.core.familiarity.following import Following, WorldViews, follow_route
from delvjax.core.familiarity.perfect_memory import PerfectMemory
from delvjax.core.familiarity.views import view_camera, views_at
from delvjax.familiarity import plan_route, ridf, route_in_world, train_model, unfamiliarity_grad
from delvjax.familiarity._setup import render_factor
from delvjax.images import image_world

ROBOT = image_world("robot")


@pytest.fixture(scope="module")
def robot_route():
    return route_in_world(ROBOT, plan_route(ROBOT), view_camera())


def trials_of(model, ri, n, seed=0, noise=10.0):
    rules = Following(heading_noise_deg=noise, max_steps=60)
    starts = jnp.repeat(ri.route.positions[:1], n, 0)
    heads = jnp.repeat(ri.route.headings[:1], n, 0)
    return follow_route(model, WorldViews(ROBOT.world, ri.camera), ri.route, rules, starts, heads, jax.random.key(seed))


def test_a_memory_of_the_route_follows_it_and_a_memory_facing_back_does_not(robot_route):
    """Success is not a given: views of the same places facing the other way lead nowhere."""
    ri = robot_route
    ahead = trials_of(PerfectMemory().train(ri.views), ri, 8)
    render = jax.vmap(lambda p, h: views_at(ROBOT.world, ri.camera, p, h + jnp.pi, jnp.zeros(1))[0])
    back = trials_of(PerfectMemory().train(render(ri.route.positions, ri.route.headings)), ri, 8)
    assert np.mean(np.asarray(ahead.outcome) == 0) >= 0.75
    assert np.mean(np.asarray(back.outcome) == 0) <= 0.25
    assert np.mean(np.asarray(back.errors)) > np.mean(np.asarray(ahead.errors))


def test_trials_are_the_same_however_many_run_together(robot_route):
    model = PerfectMemory().train(robot_route.views)
    few, many = (
        trials_of(model, robot_route, 3, seed=4, noise=30.0),
        trials_of(model, robot_route, 11, seed=4, noise=30.0),
    )
    np.testing.assert_array_equal(np.asarray(few.path), np.asarray(many.path)[:3])
    assert not np.array_equal(np.asarray(many.path)[0], np.asarray(many.path)[1])  # the noise differs by trial


def test_near_the_route_the_heading_field_points_along_it(robot_route):
    ri = robot_route
    model = train_model("perfect-memory", ri.views)
    points = np.asarray(ri.route.positions)[2:-2:3] + np.array([3.0, -3.0], np.float32)
    hf = heading_field(model, WorldViews(ROBOT.world, ri.camera), ri.route, jnp.asarray(points))
    assert np.median(np.asarray(hf.error_deg)) < 20.0
    assert np.all(np.asarray(hf.distance) < 6.0)


@pytest.mark.parametrize("cols", [12, 36, 72, 90, 360])
def test_every_scan_and_field_turn_is_whole_rendered_columns(cols):
    factor = render_factor(cols)
    per_deg = cols * factor / 360.0  # rendered columns a degree
    assert factor >= 4 and float(2.0 * per_deg).is_integer() and float(360.0 / cols * per_deg).is_integer()


BAD_TRAINING = [
    (dict(views=np.zeros((1, 4, 8))), "views: must hold at least 2 images"),
    (dict(views=[np.zeros((4, 8)), np.zeros((4, 9))]), "views: must be 2-D images all of one size"),
    (dict(views=np.ones((3, 4, 8)), masks=np.ones((4, 9), bool)), "masks: must be of the images' size"),
    (dict(views=np.ones((3, 4, 8)), masks=np.zeros((4, 8), bool)), "masks: has an empty mask"),
    (dict(views=np.where(np.arange(96).reshape(3, 4, 8) == 50, np.nan, 1.0)), "views[1]: has a non-finite pixel"),
    (dict(views=np.ones((3, 4, 8)), name="infomax", learning_rate=0.0), "learning_rate: must be > 0"),
    (dict(views=np.ones((3, 4, 8)), name="infomax", learning_rate=-1.0), "learning_rate: must be > 0"),
    (dict(views=np.ones((3, 4, 8)), name="perfect-memory", n_kc=3), "n_kc: is no setting of perfect-memory"),
    (dict(views=np.ones((3, 4, 8)), name="hopfield"), "model: "),
]


@pytest.mark.parametrize("kw,says", BAD_TRAINING)
def test_bad_training_input_is_refused_naming_the_field(kw, says):
    kw = dict(kw)
    name = kw.pop("name", "perfect-memory")
    with pytest.raises(InputError) as e:
        train_model(name, **kw)
    assert str(e.value).startswith(says), str(e.value)


def test_ridf_refuses_masks_that_keep_nothing_in_common():
    view = np.arange(32.0).reshape(4, 8)
    left = np.zeros((4, 8), bool)
    left[:, :1] = True
    with pytest.raises(InputError, match="keep no common pixel"):
        ridf(view, view[None], view_mask=left, snapshot_masks=np.roll(left, 4, axis=1)[None])


def test_the_command_writes_every_output_with_its_numbers(tmp_path, capsys):
    out = {
        k: tmp_path / f"{k}.{ext}"
        for k, ext in (("f", "csv"), ("t", "csv"), ("c", "csv"), ("r", "csv"), ("s", "json"), ("p", "png"))
    }
    argv = ["familiarity", "robot", "--model", "infomax", "--trials", "4", "--max-steps", "40", "--grid-spacing", "40",
            "--out", str(out["f"]), "--trials-out", str(out["t"]), "--catchments-out", str(out["c"]),
            "--ridf-out", str(out["r"]), "--summary", str(out["s"]), "--plot", str(out["p"])]  # fmt: skip
    assert main(argv) == 0
    assert all(p.is_file() for p in out.values())
    s = json.loads(out["s"].read_text())
    assert s["model"] == "infomax" and s["trials"] == 4 and s["settings"]["learning_rate"] == 0.97
    assert 0.0 <= s["success_pct"] <= 100.0 and s["route_images"] == len(out["c"].read_text().splitlines()) - 1
    head = out["f"].read_text().splitlines()[0]
    assert head.startswith("x_cm,y_cm,heading_deg,unfamiliarity,best_image")
    assert "success" in capsys.readouterr().out
    field = np.genfromtxt(out["f"], delimiter=",", names=True)
    ridf = np.genfromtxt(out["r"], delimiter=",", names=True)
    assert len(ridf) == 90 * len(field)  # every heading of a 90-column view at every field point
    curves = ridf["unfamiliarity"].reshape(len(field), 90)
    best = ridf["heading_deg"].reshape(len(field), 90)[np.arange(len(field)), np.argmin(curves, 1)]
    np.testing.assert_allclose(np.mod(field["heading_deg"], 360.0), best, atol=1e-3)  # the field is the RIDF's minimum
    np.testing.assert_allclose(curves.min(1), field["unfamiliarity"], rtol=1e-5)


@pytest.mark.parametrize(
    "extra,says",
    [
        (["--model", "hopfield"], "--model: must be one of"),
        (["--model", "infomax", "--learning-rate", "0"], "--learning-rate: must be > 0"),
        (["--kind", "rms", "--model", "infomax"], "--kind: is no setting of infomax"),
        (["--route", "10,10"], "--route: needs at least two waypoints"),
        (["--route", "10,10 170,170"], "--route: passes through an obstacle"),
        (["--route", "a,b c,d"], "--route: must be waypoints"),
        (["--route-spacing", "0"], "--route-spacing: must be > 0"),
        (["--view-cols", "7"], "--view-cols: must divide 360"),
        (["--trials", "0"], "--trials: must be >= 1"),
        (["--window-ahead", "-1"], "--window-ahead: must be >= 0"),
        (["--n-active", "30000", "--model", "mushroom-body"], "--n-active: must be at most n_kc"),
    ],
)
def test_bad_options_are_refused_in_one_line_and_nothing_is_written(tmp_path, capsys, extra, says):
    out = tmp_path / "f.csv"
    assert main(["familiarity", "robot", *extra, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"delvjax: error: {says}"), err
    assert not out.exists()


@pytest.mark.parametrize("name,settings", [("perfect-memory", {"kind": "rms"}), ("perfect-memory", {"kind": "corr"}),
                                           ("infomax", {"learning_rate": 0.5})])  # fmt: skip
def test_the_unfamiliarity_gradient_is_central_differences(name, settings):
    rng = np.random.default_rng(3)
    route = rng.integers(0, 256, (4, 4, 8)).astype(np.float32)
    model = train_model(name, route, **settings)
    view = route[1] + rng.normal(0, 30, route[1].shape).astype(np.float32)
    value, d_view, d_model = unfamiliarity_grad(model, view)
    f = lambda v: float(model.unfamiliarity(jnp.asarray(v)[None])[0])  # noqa: E731
    for r, c in [(0, 0), (2, 5), (3, 7)]:
        e = np.zeros_like(view)
        e[r, c] = 0.5
        fd = (f(view + e) - f(view - e)) / 1.0
        assert d_view[r, c] == pytest.approx(fd, rel=2e-2, abs=1e-5 * max(1.0, abs(value)))
    memory = d_model.images if name == "perfect-memory" else d_model.weights
    assert memory is not None and np.isfinite(memory).all() and np.abs(memory).max() > 0


def test_the_mushroom_bodys_view_gradient_is_zero_and_its_weights_are_not():
    route = np.random.default_rng(4).integers(0, 256, (3, 4, 8)).astype(np.float32)
    model = train_model("mushroom-body", route, n_kc=200, pn_per_kc=4, n_active=10)
    _, d_view, d_model = unfamiliarity_grad(model, route[0] + 3.0)
    assert np.all(d_view == 0.0) and np.abs(d_model.kc_weights).sum() == pytest.approx(1.0)
