"""Familiarity models (issue 57; docs/familiarity.md): time per query against the plain NumPy twin
(tests/twins/familiarity.py) in the same run, compile time separate; and route-following trials.

A query is one view against the trained model over all its rotations: perfect memory (the RIDF table
against S route images, then the best match), InfoMax (the decision of every rotation) and the
mushroom body (the KC code and MBON of every rotation). JAX runs a batch of queries as one program;
the twin runs them one at a time, loops over rotations (and snapshots, KCs) as written. Target:
JAX >= 100x the twin per query on 2 CPU cores.

    python benchmarks/bench_familiarity.py            # 10 x 90 views, 200 route images, 64 queries
    python benchmarks/bench_familiarity.py --smoke    # tiny sizes, no targets (the test suite runs it)
    python benchmarks/bench_familiarity.py --dft      # also InfoMax's scan by the columns' DFT (not in delvjax)

The last route row is a thousand-image route (natural, 0.5 cm between images: 1068 images).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the twin lives in tests/

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import numpy as np  # noqa: E402

from delvjax.core.familiarity.infomax import infomax  # noqa: E402
from delvjax.core.familiarity.mushroom_body import mushroom_body  # noqa: E402
from delvjax.core.familiarity.perfect_memory import PerfectMemory  # noqa: E402
from delvjax.core.familiarity.ridf import rolled, turn_of_shift  # noqa: E402
from delvjax.familiarity._run import route_experiments  # noqa: E402
from delvjax.images import image_world  # noqa: E402
from tests.twins import familiarity as tw  # noqa: E402


def timed(fn, *args, rounds: int = 3) -> tuple[float, float]:
    """(first call s, best warm call s) of fn(*args), results blocked on."""
    t0 = time.perf_counter()
    jax.block_until_ready(fn(*args))
    first = time.perf_counter() - t0
    best = float("inf")
    for _ in range(rounds):
        t0 = time.perf_counter()
        jax.block_until_ready(fn(*args))
        best = min(best, time.perf_counter() - t0)
    return first, best


def models(shape, n_kc: int):
    key = jax.random.key(0)
    return {
        "perfect-memory": PerfectMemory(),
        "infomax": infomax(shape, key),
        "mushroom-body": mushroom_body(shape, key, n_kc=n_kc, n_active=max(n_kc // 100, 1)),
    }


def twin_query(name, trained, view, turns):
    """One query through the twin: every rotation scored one at a time."""
    w = view.shape[1]
    if name == "perfect-memory":
        table = tw.ridf_table(view, np.asarray(trained.images))
        return tw.perfect_memory_choice(table, turns)[0]
    if name == "infomax":
        weights = np.asarray(trained.weights, np.float64)
        scores = [tw.infomax_unfamiliarity(weights, tw.roll_right(view, i)) for i in range(w)]
    else:
        wiring, weights = np.asarray(trained.wiring), np.asarray(trained.kc_weights, np.float64)
        scores = [
            tw.mushroom_unfamiliarity(wiring, weights, tw.roll_right(view, i), trained.n_active) for i in range(w)
        ]
    return turns[int(np.argmin(scores))]


def query_table(shape, n_images: int, n_queries: int, n_kc: int, twin_queries: int) -> list[dict]:
    rng = np.random.default_rng(0)
    route = rng.integers(0, 256, (n_images, *shape)).astype(np.float32)
    queries = rng.integers(0, 256, (n_queries, *shape)).astype(np.float32)
    w = shape[1]
    shifts = jnp.arange(w)
    turns = turn_of_shift(shifts, w)
    rows = []
    for name, model in models(shape, n_kc).items():
        trained = model.train(route)
        run = jax.jit(jax.vmap(lambda v, m=trained: m.choose(rolled(v, shifts), turns).turn))
        first, warm = timed(run, jnp.asarray(queries))
        t0 = time.perf_counter()
        for q in queries[:twin_queries]:
            twin_query(name, trained, q, np.asarray(turns))
        twin = (time.perf_counter() - t0) / twin_queries
        per = warm / n_queries
        rows.append({"model": name, "compile_s": first - warm, "jax_ms_per_query": 1e3 * per,
                     "twin_ms_per_query": 1e3 * twin, "ratio": twin / per})  # fmt: skip
    return rows


def infomax_dft_row(shape, n_images: int, n_queries: int) -> dict:
    """InfoMax's scan of every column rotation two ways, per query: the direct product (what delvjax runs) and
    the circular correlation along the columns by the real DFT, u(r) = irfft(sum_rows rfft(W) conj(rfft(x)))
    (docs/familiarity.md §5: measured, not used); their largest relative difference and whether the first
    least unfamiliar rotation is the same."""
    rng = np.random.default_rng(0)
    h, w = shape
    trained = infomax(shape, jax.random.key(0)).train(rng.integers(0, 256, (n_images, *shape)).astype(np.float32))
    queries = jnp.asarray(rng.integers(0, 256, (n_queries, *shape)).astype(np.float32))
    shifts = jnp.arange(w)
    direct = jax.jit(jax.vmap(lambda v: trained.unfamiliarity(rolled(v, shifts))))
    spectrum = jnp.fft.rfft(trained.weights.reshape(-1, h, w), axis=-1)  # (M, H, W/2 + 1), once per model

    @jax.jit
    def by_dft(views):
        xf = jnp.conj(jnp.fft.rfft(trained.inputs(views).reshape(-1, h, w), axis=-1))  # (Q, H, W/2 + 1)
        u = jnp.fft.irfft(jnp.einsum("mhk,qhk->qmk", spectrum, xf), n=w, axis=-1)  # (Q, M, rotations)
        return jnp.sum(jnp.abs(u), axis=1)

    _, t_direct = timed(direct, queries)
    _, t_dft = timed(by_dft, queries)
    a, b = np.asarray(direct(queries)), np.asarray(by_dft(queries))
    return {"direct_ms_per_query": 1e3 * t_direct / n_queries, "dft_ms_per_query": 1e3 * t_dft / n_queries,
            "largest_relative_difference": float(np.max(np.abs(a - b) / np.abs(a))),
            "same_choice_pct": 100.0 * float(np.mean(np.argmin(a, 1) == np.argmin(b, 1)))}  # fmt: skip


def trials_row(world: str, model: str, trials: int, smoke: bool, route_spacing: float = 4.0) -> dict:
    """One `route_experiments` call, first and warm; a route spacing below the 4 cm step gives a long route
    (natural at 0.5 cm: 1068 images) followed in 4 cm moves."""
    iw = image_world(world)
    kw = dict(trials=trials, grid_spacing=60.0 if smoke else None, max_steps=20 if smoke else None,
              route_spacing=route_spacing, step=4.0)  # fmt: skip
    if model == "mushroom-body" and smoke:
        kw.update(n_kc=500, n_active=5)
    t0 = time.perf_counter()
    r = route_experiments(iw, model, **kw)
    first = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = route_experiments(iw, model, seed=1, **kw)
    warm = time.perf_counter() - t0
    moves = int(np.sum(np.asarray(r.trials.steps)))
    return {"world": world, "model": model, "route_images": r.route.n_images, "trials": trials,
            "first_s": first, "warm_s": warm, "moves": moves, "success_pct": r.summary()["success_pct"]}  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--smoke", action="store_true", help="tiny sizes, no targets")
    p.add_argument("--dft", action="store_true", help="also InfoMax's scan by the columns' DFT (measured, not used)")
    p.add_argument("--json", default=None, help="write the numbers here")
    a = p.parse_args()
    if a.smoke:
        shape, n_images, n_queries, n_kc, twin_q = (4, 12), 10, 8, 200, 2
    else:
        shape, n_images, n_queries, n_kc, twin_q = (10, 90), 200, 64, 20000, 3
    rows = query_table(shape, n_images, n_queries, n_kc, twin_q)
    print(f"one query = a {shape[0]} x {shape[1]} view over its {shape[1]} rotations; {n_images} route images")
    print(f"{'model':16s} {'compile s':>9s} {'JAX ms/query':>12s} {'twin ms/query':>13s} {'twin / JAX':>10s}")
    for r in rows:
        print(
            f"{r['model']:16s} {r['compile_s']:9.2f} {r['jax_ms_per_query']:12.3f} {r['twin_ms_per_query']:13.1f} {r['ratio']:9.0f}x"
        )
    dft = infomax_dft_row(shape, n_images, n_queries) if a.dft else None
    if dft:
        twin = next(r["twin_ms_per_query"] for r in rows if r["model"] == "infomax")
        print(f"InfoMax scan, direct {dft['direct_ms_per_query']:.3f} ms/query ({twin / dft['direct_ms_per_query']:.0f}x "
              f"the twin), by the columns' DFT {dft['dft_ms_per_query']:.3f} ms/query ({twin / dft['dft_ms_per_query']:.0f}x); "
              f"largest relative difference {dft['largest_relative_difference']:.1e}, same choice "
              f"{dft['same_choice_pct']:.0f} %")  # fmt: skip
    trials = [
        trials_row("robot", m, 4 if a.smoke else 20, a.smoke) for m in ("perfect-memory", "infomax", "mushroom-body")
    ]
    trials.append(trials_row("robot" if a.smoke else "natural", "perfect-memory", 4 if a.smoke else 20, a.smoke, 0.5))
    print("route experiments (heading field, trials, catchments), whole call:")
    for t in trials:
        print(f"  {t['world']} {t['model']:15s} {t['route_images']} images, {t['trials']} trials, {t['moves']} moves: "
              f"first {t['first_s']:.1f} s, warm {t['warm_s']:.1f} s, success {t['success_pct']:.0f} %")  # fmt: skip
    if a.json:
        Path(a.json).write_text(
            json.dumps({"queries": rows, "infomax_dft": dft, "route_experiments": trials}, indent=1)
        )


if __name__ == "__main__":
    main()
