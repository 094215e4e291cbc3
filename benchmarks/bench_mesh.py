"""Mesh panoramas (issue 58; docs/mesh.md §2): views a second of the generated habitat (about 5000 triangles)
batched over poses along its route, the ant eye (74 x 19) and 360 x 90 panoramas, compile time separate; and the
plain NumPy ray caster (tests/twins/mesh.py) on the same views in the same run, with the ratio. Target: at least
1000 ant-eye views a second on 2 CPU cores.

    python benchmarks/bench_mesh.py            # 256 ant-eye poses, 32 panoramas, 2 twin views
    python benchmarks/bench_mesh.py --smoke    # tiny sizes, no targets (the test suite runs it)
    python benchmarks/bench_mesh.py --twin-views 0   # no NumPy views (benchmarks/gpu.sh: GPU_PARTS=mesh)
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the twin lives in tests/

import jax  # noqa: E402
import numpy as np  # noqa: E402

from delvjax.core.mesh.render import mesh_panoramas  # noqa: E402
from delvjax.mesh import ANT_EYE, Eye, habitat, mesh_world  # noqa: E402
from tests.twins import mesh as twin  # noqa: E402


def row(world, h, eye, name: str, n: int, batch: int, twin_views: int) -> dict:
    idx = np.linspace(0, len(h.route) - 1, n).astype(int)
    poses = np.c_[h.route[idx, :2], np.ones(n), h.route[idx, 2]].astype(np.float32)
    run = jax.jit(lambda p: mesh_panoramas(world, eye, p, batch=batch))
    t0 = time.perf_counter()
    jax.block_until_ready(run(poses))
    first = time.perf_counter() - t0
    warm = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        jax.block_until_ready(run(poses))
        warm = min(warm, time.perf_counter() - t0)
    v, rgb = np.asarray(world.vertices, np.float64), np.asarray(world.rgb)
    g, s = np.asarray(world.ground_rgb), np.asarray(world.sky_rgb)
    t0 = time.perf_counter()
    for p in poses[:twin_views]:
        twin.render(v, rgb, g, s, p.astype(np.float64), eye.rows, eye.cols, eye.width_deg, eye.elev_top_deg,
                    eye.elev_bottom_deg)  # fmt: skip
    per_twin = (time.perf_counter() - t0) / twin_views if twin_views else float("nan")
    return {"eye": name, "poses": n, "batch": batch, "compile_s": first - warm, "views_per_s": n / warm,
            "twin_s_per_view": per_twin, "ratio": per_twin * n / warm}  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--smoke", action="store_true", help="tiny sizes, no targets")
    p.add_argument("--json", default=None, help="write the numbers here")
    p.add_argument("--twin-views", type=int, default=None, help="views the NumPy caster draws (0: none, no ratio)")
    a = p.parse_args()
    h = habitat(0, tussocks=10, blades=4, trees=1) if a.smoke else habitat(0)
    world = mesh_world(h)
    n_ant, n_pano, twin_views = (4, 2, 1) if a.smoke else (256, 32, 2)
    twin_views = twin_views if a.twin_views is None else a.twin_views
    rows = [row(world, h, ANT_EYE, "ant eye 74 x 19", n_ant, 16, twin_views)]
    rows.append(row(world, h, Eye(rows=90, cols=360), "360 x 90", n_pano, 4, min(twin_views, 1)))
    print(f"{h.name}: {world.n_triangles} triangles; twin: tests/twins/mesh.py (NumPy, one core, a loop over pixels)")
    print(f"{'eye':16s} {'poses':>5s} {'compile s':>9s} {'views/s':>8s} {'twin s/view':>11s} {'JAX / twin':>10s}")
    for r in rows:
        print(f"{r['eye']:16s} {r['poses']:5d} {r['compile_s']:9.2f} {r['views_per_s']:8.1f} "
              f"{r['twin_s_per_view']:11.3f} {r['ratio']:9.0f}x")  # fmt: skip
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
