"""How rough the soft homing loss is at the centimetre scale (issue 56; docs/differentiable.md "Homing loss").

    python benchmarks/roughness.py [--spacing 25] [--json PATH]      # float32 and float64, one child each
    python benchmarks/roughness.py --dtype float64 [--json PATH]     # one precision, in this process
    python benchmarks/roughness.py --smoke                           # spacing 200, profile +-0.4 cm, h = 0.5
    python benchmarks/roughness.py --method alv                      # another method (default delv-compass)

`delvjax.homing_loss(env, "delv-compass", soft=True, tau=TAU, sharpness=VISIBILITY_WIDTH)` (0.01, 0.01: the
defaults) on a 25 cm grid, seed 0, in a five-landmark world no test uses (`random_env(2026, 5)`), as a
function of landmark 0 (the loss through the public API only: landmarks replaced with `equinox.tree_at`, `jax.grad`):

1. profile: the loss along landmark 0's x over +-3 cm in 0.2 cm steps (31 values); the largest jump between
   neighbouring steps against the trend (least-squares slope, per cm), and whether the grid points clear of
   the landmarks (`VectorMap.included`, r + clearance) changed across the step of that jump;
2. central differences (L(x + h) - L(x - h)) / 2h at h = 2, 0.5 and 0.02 cm of landmark 0's x, y and r
   against `jax.grad` at the point, and whether their signs agree;
3. `jax.grad` of landmark 0's x in float32 against float64 (x64 is a process-wide switch, so each precision
   runs in its own child process; float64 takes the same world's numbers as float64 arrays), with
   `homing_loss_grad(..., smoothing_cm=None)` (the gradient at the point) beside it in float32, and a control with every heading fixed (`heading_deg=0`): under
   x64 `jax.random.uniform` draws float64 headings, other numbers than float32's, so with random headings the
   two precisions evaluate different grid samples, not only different roundings.

Prints a table; `--json PATH` writes the same numbers. A measurement script, not a test.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import jax
import numpy as np

DTYPES = ("float32", "float64")
METHOD = "delv-compass"  # the issue's; --method picks another (alv shows the continuous loss of issue 56)
WORLD = (2026, 5)  # random_env(seed, n): no test uses seed 2026
COORDS = ("x", "y", "r")
TAU = None  # the softmins' temperature; None: the loss's default (gradients._loss.TAU); --tau sets it


def settings(smoke: bool, spacing: float | None) -> dict:
    """The measured sizes: the issue's, or the --smoke ones."""
    if smoke:
        return {"spacing": spacing or 200.0, "extent": 0.4, "step": 0.2, "hs": [0.5]}
    return {"spacing": spacing or 25.0, "extent": 3.0, "step": 0.2, "hs": [2.0, 0.5, 0.02]}


def measure(dtype: str, spacing: float, extent: float, step: float, hs: list[float]) -> dict:
    """Every measurement in one precision; call only in a process whose x64 switch matches `dtype`."""
    import equinox as eqx
    import jax.numpy as jnp

    import delvjax
    from delvjax.core.soft.sensing import VISIBILITY_WIDTH
    from delvjax.envs._presets import random_env
    from delvjax.gradients._loss import TAU as DEFAULT_TAU

    tau = DEFAULT_TAU if TAU is None else TAU
    world = random_env(*WORLD)
    float_type = jnp.float64 if dtype == "float64" else jnp.float32
    lm0 = jnp.asarray(np.asarray(world.landmarks, np.float64), float_type)
    env = eqx.tree_at(lambda e: e.home, world, jnp.asarray(np.asarray(world.home, np.float64), float_type))
    kw = {"spacing": spacing, "seed": 0, "soft": True, "tau": tau, "sharpness": VISIBILITY_WIDTH}

    def loss(lm: jax.Array, **extra) -> jax.Array:
        """The soft loss with landmarks `lm`."""
        return delvjax.homing_loss(eqx.tree_at(lambda e: e.landmarks, env, lm), METHOD, **kw, **extra)

    def moved(coord: int, by: float) -> jax.Array:
        """The landmarks with landmark 0's `coord` moved `by` cm."""
        return lm0.at[0, coord].add(by)

    value = loss(lm0)
    grad = np.asarray(jax.grad(loss)(lm0)[0], np.float64)
    # 1. profile along x; which grid points are clear of the landmarks, per offset (a hard ALV map's mask)
    offsets = np.arange(-round(extent / step), round(extent / step) + 1) * step
    profile = np.array([float(loss(moved(0, float(o)))) for o in offsets])
    grid = delvjax.Grid(spacing=spacing)
    masks = [
        np.asarray(
            delvjax.vector_map(eqx.tree_at(lambda e: e.landmarks, env, moved(0, float(o))), "alv", grid=grid).included
        )
        for o in offsets
    ]
    jumps = np.abs(np.diff(profile))
    mask_changed = np.array([bool(np.any(a != b)) for a, b in zip(masks[:-1], masks[1:])])
    at = int(np.argmax(jumps))
    steady = jumps[~mask_changed]
    # 2. central differences of x, y, r
    central = {
        c: [(float(loss(moved(i, h))) - float(loss(moved(i, -h)))) / (2 * h) for h in hs] for i, c in enumerate(COORDS)
    }
    # 3. the x gradient with every heading fixed (same headings in both precisions)
    fixed = jax.grad(lambda lm: loss(lm, heading_deg=0.0))(lm0)
    out = {
        "dtype": dtype,
        "value_dtype": str(value.dtype),
        "grad_dtype": str(fixed.dtype),
        "value": float(value),
        "grad": dict(zip(COORDS, grad.tolist())),
        "profile": {
            "offsets_cm": offsets.tolist(),
            "loss": profile.tolist(),
            "included": [int(m.sum()) for m in masks],
            "max_jump": float(jumps[at]),
            "max_jump_between_cm": [float(offsets[at]), float(offsets[at + 1])],
            "max_jump_included_changed": bool(mask_changed[at]),
            "steps_included_changed": int(mask_changed.sum()),
            "max_jump_included_same": float(steady.max()) if steady.size else None,
            "slope_per_cm": float(np.polyfit(offsets, profile, 1)[0]),
        },
        "central": {"h_cm": hs, **central},
        "fixed_heading": {"value": float(loss(lm0, heading_deg=0.0)), "grad_x": float(fixed[0, 0])},
    }
    out["smoothed"] = smoothed(env, spacing, float_type, tau)
    if dtype == "float32":  # the one-program gradient (it takes the landmarks as float32 in any mode)
        _, grads = delvjax.homing_loss_grad(
            env, METHOD, spacing=spacing, seed=0, tau=tau, sharpness=VISIBILITY_WIDTH, smoothing_cm=None
        )
        out["homing_loss_grad"] = dict(zip(COORDS, np.asarray(grads["landmarks"][0], np.float64).tolist()))
    out["tau"] = tau
    out["world"] = {"name": world.name, "landmarks": np.asarray(world.landmarks, np.float64).tolist()}
    return out


def smoothed(env, spacing: float, float_type, tau: float) -> dict:
    """The sensitivity at the default stated scale (`homing_loss_grad`'s 5 cm, 8 draws) computed in `float_type`:
    the API's problem with every float leaf cast (the draws stay float32 numbers, so both precisions smooth
    with the same sample); every landmark's x, y, r and their standard errors."""
    import jax.numpy as jnp

    from delvjax.core.maps import CLEARANCE
    from delvjax.core.soft.sensing import VISIBILITY_WIDTH
    from delvjax.gradients._loss import loss_problem
    from delvjax.gradients._smoothing import check_smoothing, smoothed_value_and_grad
    from delvjax.options._limits import MAX_POINTS

    problem = loss_problem(env, METHOD, spacing, 0, tau, VISIBILITY_WIDTH, None, CLEARANCE, MAX_POINTS)
    cast = jax.tree.map(
        lambda x: x.astype(float_type) if jnp.issubdtype(jnp.result_type(x), jnp.floating) else x, problem
    )
    value, grads, se = smoothed_value_and_grad(cast, check_smoothing(5.0, 1.0, 0.01, 8, problem.env.arena))
    n = problem.n_landmarks
    return {
        "value": float(value),
        "landmarks": np.asarray(grads["landmarks"][:n], np.float64).tolist(),
        "se": np.asarray(se["landmarks"][:n], np.float64).tolist(),
        "dtype": str(grads["landmarks"].dtype),
    }


def child(dtype: str, argv: list[str]) -> dict:
    """`measure` in a fresh process with x64 set for `dtype` (its JSON output, read back)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{dtype}.json"
        cmd = [sys.executable, __file__, "--dtype", dtype, "--json", str(path), "--quiet", *argv]
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode != 0:
            raise SystemExit(f"{dtype} child failed ({run.returncode}):\n{run.stderr[-3000:]}")
        return json.loads(path.read_text())[dtype]


def table(results: dict[str, dict], s: dict) -> str:
    """The readable report of one or both precisions."""
    ds = list(results)
    first = results[ds[0]]
    lines = [
        f"world {first['world']['name']} (random_env{WORLD}), landmark 0 at "
        + ", ".join(f"{c} {v:.3f}" for c, v in zip(COORDS, first["world"]["landmarks"][0]))
        + f" cm; {METHOD}, soft, tau {first['tau']:g}, sharpness 0.01, spacing {s['spacing']:g} cm, seed 0",
        f"{'':44s}" + "".join(f"{d:>16s}" for d in ds),
        f"{'loss dtype / value':44s}"
        + "".join(f"{r['value_dtype'] + ' ' + format(r['value'], '.6f'):>17s}" for r in results.values()),
    ]

    def row(label: str, values: list, fmt: str = "{:+16.3e}") -> None:
        lines.append(f"{label:44s}" + "".join(fmt.format(v) if v is not None else f"{'-':>16s}" for v in values))

    n = len(first["profile"]["offsets_cm"])
    lines.append(f"1. profile of x over +-{s['extent']:g} cm, {s['step']:g} cm steps ({n} values)")
    p = [r["profile"] for r in results.values()]
    row("   largest |jump| between neighbours", [q["max_jump"] for q in p])
    lines.append(
        f"{'     between offsets (cm)':44s}"
        + "".join(f"{'{:+.1f} {:+.1f}'.format(*q['max_jump_between_cm']):>16s}" for q in p)
    )
    row("     included grid points changed there", [str(q["max_jump_included_changed"]) for q in p], "{:>16s}")
    row("   steps where included points change", [q["steps_included_changed"] for q in p], "{:16d}")
    row("   largest |jump| where they do not", [q["max_jump_included_same"] for q in p])
    row("   trend (least-squares slope), per cm", [q["slope_per_cm"] for q in p])
    row("   largest jump / (trend x step)", [q["max_jump"] / abs(q["slope_per_cm"] * s["step"]) for q in p], "{:16.1f}")
    lines.append("2. central differences (L(+h) - L(-h)) / 2h against jax.grad, landmark 0")
    for c in COORDS:
        row(f"   d/d{c}  jax.grad", [r["grad"][c] for r in results.values()])
        for k, h in enumerate(s["hs"]):
            cells = [
                f"{r['central'][c][k]:+.3e} {'ok' if np.sign(r['central'][c][k]) == np.sign(r['grad'][c]) else 'NO'}"
                for r in results.values()
            ]
            row(f"         h = {h:g} cm (sign agrees)", cells, "{:>16s}")
    lines.append("3. d/dx of landmark 0 by precision")
    row("   jax.grad(homing_loss), random headings", [r["grad"]["x"] for r in results.values()])
    row("   homing_loss_grad (float32)", [r.get("homing_loss_grad", {}).get("x") for r in results.values()])
    row("   jax.grad, heading_deg = 0 (control)", [r["fixed_heading"]["grad_x"] for r in results.values()])
    row("   loss, heading_deg = 0 (control)", [r["fixed_heading"]["value"] for r in results.values()], "{:16.8f}")
    sm = [r["smoothed"] for r in results.values()]
    lines.append("   at the stated scale (homing_loss_grad, 5 cm, 8 draws), computed in each precision")
    row("   d/dx of landmark 0", [q["landmarks"][0][0] for q in sm])
    row("   its standard error", [q["se"][0][0] for q in sm])
    if len(sm) == 2:
        a, b = (np.asarray(q["landmarks"]) for q in sm)
        rel = np.abs(a - b) / np.maximum(np.abs(b), 1e-12)
        lines.append(
            f"   float32 vs float64 over every landmark's x, y, r: largest |difference| / |float64| "
            f"{100 * rel.max():.2g} %, median {100 * np.median(rel):.2g} %"
        )
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dtype", choices=DTYPES, help="run one precision in this process (default: both, as children)")
    ap.add_argument("--spacing", type=float, help="grid spacing, cm (default 25; 200 with --smoke)")
    ap.add_argument("--smoke", action="store_true", help="tiny size: spacing 200, profile +-0.4 cm, h = 0.5")
    ap.add_argument("--json", type=Path, help="write the numbers here")
    ap.add_argument("--quiet", action="store_true", help="no table (a child of the two-precision run)")
    ap.add_argument("--method", default=METHOD, help=f"delv, delv-compass, alv or acv (default {METHOD})")
    ap.add_argument("--tau", type=float, help="the softmins' temperature (default: the loss's, 0.01)")
    a = ap.parse_args()
    globals()["METHOD"] = a.method  # one setting read by measure() and table() in this process and its children
    globals()["TAU"] = a.tau  # read by measure(), passed on to the children
    s = settings(a.smoke, a.spacing)
    t = time.perf_counter()
    if a.dtype:
        jax.config.update("jax_enable_x64", a.dtype == "float64")  # before delvjax makes any array
        results = {a.dtype: measure(a.dtype, s["spacing"], s["extent"], s["step"], s["hs"])}
    else:
        passed = (["--smoke"] if a.smoke else []) + ([] if a.spacing is None else ["--spacing", str(a.spacing)])
        passed += ["--method", a.method] + ([] if a.tau is None else ["--tau", str(a.tau)])
        results = {d: child(d, passed) for d in DTYPES}
    if not a.quiet:
        print(table(results, s))
        print(f"{time.perf_counter() - t:.1f} s")
    if a.json:
        a.json.write_text(json.dumps({"settings": s, "method": METHOD, **results}, indent=1))


if __name__ == "__main__":
    main()
