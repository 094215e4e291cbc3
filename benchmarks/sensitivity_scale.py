"""Does the sensitivity at a stated scale agree with central differences of the smoothed loss? (issue 56;
docs/differentiable.md "Sensitivity at a stated scale")

    python benchmarks/sensitivity_scale.py [--method alv] [--world 2026 5] [--sigma 5] [--samples 8] [--reps 3]
                                           [--kref 256] [--spacing 25] [--landmarks N] [--json PATH]

For one method on `random_env(seed, n)` (seeds 2026 and 2027 are used by no test but one): the reference is the
central difference (h = sigma / 2) of L_sigma, the soft loss smoothed at sigma (with the soft edges set for
that scale, `_smoothing.at_scale`), estimated from `--kref` antithetic draws of an independent key with the same
draws at +h and -h, for every landmark coordinate (x, y, r), with its standard error. Against it, for `--reps`
independent draw sets (the problem's key folded with the rep), the estimate `homing_loss_grad` returns
(`smoothed_value_and_grad`, `--samples` draws): the all-coordinate error |est - ref| / |ref|, how many
coordinates whose reference is resolved (|ref| > 2 SE) lie within 10 %, the norm of the standard errors the
estimate states, and the pathwise gradient of the reference's own draw average against that average's central
differences (0 where the average is smooth over h; large where single draws switch within it).

`--reference hard`: the reference is the same central difference of the *hard* loss (the pixel vector map's
mean 1 - cos(error) over the hard grid rule, `core.maps.vector_map`, as `homing_loss(soft=False)`) smoothed with
the same draws, one map per draw (a loop of maps: slow, so fewer --kref or --landmarks); the issue asks that
the sensitivity agree with the smoothed hard loss as well as the soft one.

`--estimate stein` or `--estimate cv` (with `--reference hard`) replaces the soft estimate by one of the hard
loss's smoothed gradient from Stein's identity, the mean of eps L_hard(theta + sigma eps) / sigma over the same
antithetic draws, plain or with the soft loss as its control variate (the soft pathwise gradient plus eps
(L_hard - L_soft) / sigma; unbiased whatever the soft loss): one hard map per draw (docs/differentiable.md "An
unbiased estimate of the smoothed hard gradient").

`--estimate per-point` keeps the soft loss but gives each grid point its own draws (each point's term, home
record included, in its own perturbed world; docs/differentiable.md "Draws per grid point").

A measurement script, not a test; tests/gradients/test_smoothing.py checks ALV at the default scale. --smoke:
a 200 cm grid, 4 reference draws, landmark 0, one draw set (tests/test_benchmarks_smoke.py runs both references).
"""

from __future__ import annotations

import argparse
import json
import time

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from delvjax.core.geometry import rotate
from delvjax.core.kernel import map_poses
from delvjax.core.maps import stream_keys, vector_map
from delvjax.core.soft.loss import alignment_loss, soft_included
from delvjax.core.soft.methods import soft_direction
from delvjax.core.soft.sensing import soft_home, soft_observe
from delvjax.envs._presets import random_env
from delvjax.gradients._loss import TAU, loss_problem, problem_loss
from delvjax.gradients._smoothing import (
    SMOOTHING_STREAM,
    Smoothing,
    _perturbed,
    _sigmas,
    at_scale,
    smoothed_loss,
    smoothed_value_and_grad,
    smoothing_draws,
)


def hard_loss(params: dict, prob) -> float:
    """The hard (pixel) loss of `prob` with `params` in place of its own: the mean 1 - cos(error) over the
    grid points the hard rule keeps, headings from the problem's key (as `homing_loss(soft=False)`)."""
    e = eqx.tree_at(lambda x: (x.landmarks, x.home), prob.env, (params["landmarks"], params["home"]))
    sensor = eqx.tree_at(lambda x: (x.d, x.noise), prob.sensor, (params["d"], params["noise"]))
    m = eqx.tree_at(lambda x: x.scale, prob.method, params["scale"]) if "scale" in params else prob.method
    vm = vector_map(env=e, method=m, sensor=sensor, key=prob.key, clearance=prob.clearance, points=prob.points)
    err = np.radians(np.asarray(vm.error_deg, np.float64))[np.asarray(vm.included)]
    return float(np.mean(1.0 - np.cos(err)))


def stein_estimate(p, smoothing: Smoothing, base, n: int, control: bool) -> tuple[np.ndarray, dict]:
    """The hard loss's smoothed gradient for landmarks (n, 3) by Stein's identity over `p`'s own draws (those
    `smoothed_value_and_grad` takes), with the soft loss as control variate when `control`; and its standard
    error from the antithetic pairs."""
    scaled, sig, eps = smoothing_draws(p, smoothing)  # the sigmas and draws `smoothed_value_and_grad` takes
    k = smoothing.samples
    hard = np.asarray(
        [hard_loss(_perturbed(scaled.params, sig, jax.tree.map(lambda x, i=i: x[i], eps)), base) for i in range(k)]
    )
    e = np.asarray(eps["landmarks"], np.float64)[:, :n]
    s = np.asarray(sig["landmarks"], np.float64)[:n]
    per = e * hard[:, None, None] / s
    if control:
        grad = jax.jit(
            jax.vmap(jax.value_and_grad(lambda q, x: problem_loss(_perturbed(q, sig, x), scaled)), (None, 0))
        )
        soft, g = grad(scaled.params, eps)
        per = (
            np.asarray(g["landmarks"], np.float64)[:, :n] + e * (hard - np.asarray(soft, np.float64))[:, None, None] / s
        )
    pairs = (per[: k // 2] + per[k // 2 :]) / 2
    return per.mean(0), {"landmarks": pairs.std(0, ddof=1) / np.sqrt(k // 2)}


def per_point_terms(moved: dict, prob) -> tuple[jax.Array, jax.Array]:
    """Per grid point its weight and weighted loss, each point with its own parameters (`moved`, leading axis P):
    `core.soft.loss.soft_loss`'s terms with the home record seen in each point's own world."""
    k_home, k_views, _ = stream_keys(prob.key)

    def one(par, point, heading, index):
        e = eqx.tree_at(lambda x: (x.landmarks, x.home), prob.env, (par["landmarks"], par["home"]))
        s = eqx.tree_at(lambda x: (x.d, x.noise), prob.sensor, (par["d"], par["noise"]))
        m = eqx.tree_at(lambda x: x.scale, prob.method, par["scale"]) if "scale" in par else prob.method
        poses = map_poses(point, heading, k_views, index, s)
        view = soft_observe(e, jnp.ones(e.landmarks.shape[0], bool), poses, s, prob.sharpness)
        vec, _, valid = soft_direction(m, soft_home(e, k_home, s, prob.sharpness), view, prob.tau)
        loss = alignment_loss(rotate(vec, poses.heading_end)[None], valid[None], point[None], e.home)[0]
        w = soft_included(e, point[None], prob.clearance, prob.edge)[0]
        return w, w * loss

    points, headings = jnp.asarray(prob.points), jnp.asarray(prob.headings)
    return jax.vmap(one)(moved, points, headings, jnp.arange(points.shape[0]))


@jax.jit
def _per_point_value_and_grad(prob, sig: dict, eps: dict):
    def loss(q, e):
        w, wl = per_point_terms(jax.vmap(lambda x: _perturbed(q, sig, x))(e), prob)
        return jnp.sum(wl) / jnp.maximum(jnp.sum(w), 1e-6)

    _, grads = jax.lax.map(lambda e: jax.value_and_grad(loss)(prob.params, e), eps)
    half = grads["landmarks"].shape[0] // 2
    pairs = (grads["landmarks"][:half] + grads["landmarks"][half:]) / 2
    return jnp.mean(grads["landmarks"], 0), jnp.std(pairs, 0, ddof=1) / jnp.sqrt(half)


def per_point_estimate(p, smoothing: Smoothing, n: int) -> tuple[np.ndarray, dict]:
    """The smoothed soft gradient for landmarks (n, 3) with independent draws per grid point: the loss is a
    weighted mean of per-point terms, so each point may take its own eps (`smoothing.samples` antithetic draws of
    (P, ...) per leaf; the same expectation up to the mean's normaliser); and its standard error."""
    scaled, sig, _ = smoothing_draws(p, smoothing)
    size = scaled.points.shape[0]
    leaves, tree = jax.tree.flatten(scaled.params)
    keys = jax.random.split(jax.random.fold_in(scaled.key, SMOOTHING_STREAM), len(leaves))
    half = [jax.random.normal(k, (smoothing.samples // 2, size, *jnp.shape(x))) for k, x in zip(keys, leaves)]
    eps = jax.tree.unflatten(tree, [jnp.concatenate([e, -e]) for e in half])
    grad, se = _per_point_value_and_grad(scaled, sig, eps)
    return np.asarray(grad, np.float64)[:n], {"landmarks": np.asarray(se)[:n]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--method", default="alv")
    ap.add_argument("--world", nargs=2, type=int, default=[2026, 5])
    ap.add_argument("--sigma", type=float, default=5.0)
    ap.add_argument("--samples", type=int, default=8)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--kref", type=int, default=256)
    ap.add_argument("--spacing", type=float, default=25.0)
    ap.add_argument("--landmarks", type=int, default=99, help="how many landmarks to check (the first N)")
    ap.add_argument("--reference", choices=["soft", "hard"], default="soft", help="the loss the reference smooths")
    ap.add_argument(
        "--estimate",
        choices=["soft", "stein", "cv", "per-point"],
        default="soft",
        help="what is checked (stein, cv: the hard loss's; per-point: the soft one with draws per grid point)",
    )
    ap.add_argument(
        "--smoke", action="store_true", help="that it runs: 200 cm grid, 4 reference draws, landmark 0, 1 set"
    )
    ap.add_argument("--tau", type=float, default=TAU, help=f"the softmins' temperature (default: the loss's, {TAU:g})")
    ap.add_argument("--json")
    a = ap.parse_args()
    if a.smoke:
        a.spacing, a.kref, a.landmarks, a.reps = 200.0, 4, 1, 1
    smoothing = Smoothing(a.sigma, 1.0, 0.01, a.samples)
    base = loss_problem(random_env(*a.world), a.method, spacing=a.spacing, seed=0, tau=a.tau)
    prob = at_scale(base, smoothing)
    sig = _sigmas(prob, smoothing)
    n = min(a.landmarks, prob.n_landmarks)
    leaves, tree = jax.tree.flatten(prob.params)
    keys = jax.random.split(jax.random.PRNGKey(9999), len(leaves))
    half = [jax.random.normal(k, (a.kref // 2, *jnp.shape(x)), jnp.float32) for k, x in zip(keys, leaves)]
    eps = jax.tree.unflatten(tree, [jnp.concatenate([e, -e]) for e in half])
    soft_draws = jax.jit(lambda q, p: jax.lax.map(lambda e: problem_loss(_perturbed(q, sig, e), p), eps, batch_size=16))
    draws = [jax.tree.map(lambda x, k=k: x[k], eps) for k in range(a.kref)] if a.reference == "hard" else None

    def per_draw(q, p):
        if draws is None:
            return soft_draws(q, p)
        return np.asarray([hard_loss(_perturbed(q, sig, e), base) for e in draws])

    t0 = time.perf_counter()
    ref, se = np.zeros((n, 3)), np.zeros((n, 3))
    h = a.sigma / 2
    for i in range(n):
        for j in range(3):
            hi = dict(prob.params, landmarks=prob.params["landmarks"].at[i, j].add(h))
            lo = dict(prob.params, landmarks=prob.params["landmarks"].at[i, j].add(-h))
            d = (np.asarray(per_draw(hi, prob), np.float64) - np.asarray(per_draw(lo, prob), np.float64)) / (2 * h)
            pairs = (d[: a.kref // 2] + d[a.kref // 2 :]) / 2
            ref[i, j], se[i, j] = pairs.mean(), pairs.std(ddof=1) / np.sqrt(len(pairs))
    t_ref = time.perf_counter() - t0
    resolved = np.abs(ref) > 2 * se
    norm = np.linalg.norm(ref)
    print(
        f"{a.method} on random_env{tuple(a.world)}, sigma {a.sigma:g} cm, {a.samples} draws, grid {a.spacing:g} cm; "
        f"{a.reference} reference: {a.kref} draws, |SE| / |ref| = {np.linalg.norm(se) / norm:.3f} ({t_ref:.0f} s)"
    )
    reps = []
    for rep in range(a.reps):
        p = base._replace(key=jax.random.fold_in(base.key, 1000 + rep)) if rep else base
        if a.estimate == "soft":
            _, grads, errors = smoothed_value_and_grad(p, smoothing)
            est = np.asarray(grads["landmarks"], np.float64)[:n]
        elif a.estimate == "per-point":
            est, errors = per_point_estimate(p, smoothing, n)
        else:
            est, errors = stein_estimate(p, smoothing, base, n, a.estimate == "cv")
        rel = np.abs(est - ref) / np.maximum(np.abs(ref), 1e-30)
        row = {
            "rep": rep,
            "error": float(np.linalg.norm(est - ref) / norm),
            "resolved": int(resolved.sum()),
            "resolved_within_10pct": int((rel[resolved] <= 0.10).sum()),
            "stated_se_over_norm": float(np.linalg.norm(np.asarray(errors["landmarks"])[:n]) / norm),
        }
        reps.append(row)
        print(
            f"  draw set {rep}: |est - ref| / |ref| = {row['error']:.3f}; resolved coordinates within 10 %: "
            f"{row['resolved_within_10pct']} / {row['resolved']}; stated |SE| / |ref| = {row['stated_se_over_norm']:.3f}"
        )
    bias = None
    if a.reference == "soft":  # the hard loss has no pathwise gradient
        g_ref = jax.jit(jax.grad(lambda q, p: smoothed_loss(q, p, sig, eps)))(prob.params, prob)
        bias = float(np.linalg.norm(np.asarray(g_ref["landmarks"])[:n] - ref) / norm)
        print(
            f"  pathwise with the reference's draws against their central differences: {bias:.3f} (0 when smooth over h)"
        )
    if a.json:
        out = {"args": vars(a), "reference": ref.tolist(), "se": se.tolist(), "reps": reps, "bias": bias}
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
