"""Trap points (docs/differentiable.md "Trap points"): the soft field's zeros near failed rollouts,
found with optimistix and classified from the Jacobian."""

from __future__ import annotations

from types import SimpleNamespace

import jax.numpy as jnp
import numpy as np
import pytest

from delvjax.cli._main import main
from delvjax.core.soft.traps import KINDS, classify, field_zeros
from delvjax.gradients._loss import loss_problem
from delvjax.gradients._traps import failed_rollouts, find_traps


@pytest.mark.parametrize(
    "jac, kind",
    [
        ([[-1, 0], [0, -2]], "sink"),
        ([[-1, 3], [-3, -1]], "sink"),
        ([[1, 0], [0, 2]], "source"),
        ([[1, 0], [0, -1]], "saddle"),
    ],
)
def test_a_zero_is_classified_from_its_jacobian(jac, kind):
    assert KINDS[int(classify(jnp.asarray(jac, jnp.float32)))] == kind


def test_the_alv_field_flows_to_home_only():
    """§3.3.2: the ALV field is minus the gradient of a convex potential, so home is its one zero, a sink."""
    p = loss_problem("env1", "alv", spacing=100)
    starts = jnp.asarray([[450.0, 450.0], [560.0, 530.0], [520.0, 440.0], [470.0, 560.0]])
    z, _, kind, _, residual = (
        np.asarray(a) for a in field_zeros(p.env, starts, p.sensor, p.method, p.key, p.tau, p.sharpness)
    )
    assert np.all(residual < 1e-3)
    assert np.all(np.hypot(*(z - np.asarray(p.env.home)).T) < 5.0) and all(KINDS[k] == "sink" for k in kind)


def test_quantized_delv_on_env1_has_a_trap_where_its_rollouts_fail():
    """DELV with Q = 2 on env1 loses 22 of 99 rollouts; a false home (sink) lies west of home at about
    (402, 437), a saddle between it and home, and every timed-out rollout ends near the sink or near a
    discontinuity of the field it oscillates across, on period-2 orbits of the rollout step."""
    r = find_traps("env1", "delv", spacing=100, levels=2)
    s = r.summary
    assert s["failed_rollouts"] == round(s["counted_points"] * (1 - s["catchment_pct"] / 100))
    assert s["timed_out"] > 0 and s["sinks"] >= 1 and s["home_sinks"] == 1 and s["saddles"] >= 1
    sinks = [(p["x"], p["y"]) for p in r.points if p["kind"] == "sink" and not p["home"]]
    assert min(np.hypot(x - 402.3, y - 436.6) for x, y in sinks) < 5.0
    assert s["timed_out_within_near_of_a_sink"] >= 1
    assert s["timed_out_within_near_of_a_sink"] + s["timed_out_within_near_of_a_discontinuity"] == s["timed_out"]
    cycles = [p for p in r.points if p["kind"] == "2-cycle"]  # period-2 orbits of the rollout step
    assert cycles and s["timed_out_on_a_2_cycle"] >= s["timed_out"] // 2
    for p in cycles:  # each end is a step d = 50 cm from the other
        assert abs(np.hypot(p["x"] - p["partner_x"], p["y"] - p["partner_y"]) - 50.0) < 1.0


def test_failed_rollouts_are_counted_over_the_catchments_points():
    """Issue 52: the failures are over the points the catchment counts (`Catchment.counted`), as
    `catchment_pct` is; over `included`, a near-wall point (not released under the default first move,
    never a success) counted as a failed rollout."""
    c = SimpleNamespace(
        included=np.array([True, True, True, True]),
        counted=np.array([True, True, True, False]),  # the last point lies within d of a wall
        success=np.array([[True, False, True, False]]),
    )
    assert failed_rollouts(c) == 1


def test_delvjax_traps_writes_and_refuses(tmp_path, capsys):
    out = tmp_path / "t"
    assert main(["traps", "env1", "--levels", "2", "--spacing", "100", "--out", str(out)]) == 0  # the programs above
    assert sorted(p.name for p in out.iterdir()) == ["traps.csv", "traps.json", "traps.png"]
    for args, field in [(["--method", "warping"], "method"), (["--tau", "-1"], "tau"), (["--near", "0"], "near")]:
        bad = tmp_path / field
        assert main(["traps", "env1", "--spacing", "200", "--out", str(bad)] + args) == 2
        assert (
            capsys.readouterr()
            .err.splitlines()[-1]
            .startswith((f"delvjax: error: {field}:", f"delvjax: error: --{field.replace('_', '-')}:"))
        )
        assert not bad.exists()
