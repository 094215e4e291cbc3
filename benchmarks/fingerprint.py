"""Fingerprint every number the command line writes, to prove a refactor changed none of them.

Runs a fixed set of `delvjax` commands (vector maps of every method with noise and with a hidden
landmark, catchments with noise and with every choice of one hidden landmark, a success-rate
table, a sweep, and `reproduce --quick`) into a temporary folder and prints one SHA-256 per
output: CSV and netCDF files byte for byte, `study.json` and summaries with their timing,
version and path fields dropped. Run it at two commits and compare:

    python benchmarks/fingerprint.py --save before.json          # at the start commit
    python benchmarks/fingerprint.py --compare before.json       # at the end: exit 1 on a difference

`--no-reproduce` leaves out `reproduce --quick` (about 2 minutes on 2 cores). This is a check
script, not a test: it takes minutes.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

METHODS = (
    "delv", "delv-compass", "delv-visual", "alv", "alv-visual", "acv", "acv-visual", "warping",
    "mfdid", "cc", "delv-agent", "delv-compass-agent", "delv-gap", "delv-gap-compass", "delv-refined",
)  # fmt: skip
NOISE = ["--bearing-noise-deg", "2", "--step-noise", "0.05", "--compass-noise-deg", "3"]
# fields that describe the run, not its numbers
VOLATILE = {"seconds", "compile_seconds", "wall_seconds", "started", "finished", "versions",
            "version", "python", "jax", "platform", "out", "path", "cache", "workers", "host",
            "timings", "devices", "code_digest", "sources", "hash"}  # fmt: skip

SWEEP = """
[sweep]
kind = "catchment"
metrics = ["catchment_pct"]
[axes]
env = ["env1", "env2"]
method = ["delv-compass", "alv"]
d = [30, 50]
bearing_noise_deg = [0.0, 2.0]
spacing = [100]
"""


def commands(out: Path, reproduce: bool) -> list[list[str]]:
    cmds = []
    for m in METHODS:
        cmds.append(["vector-map", "env1", "--method", m, "--spacing", "50", *NOISE,
                     "--out", str(out / f"vm_{m}.csv"), "--summary", str(out / f"vm_{m}.json")])  # fmt: skip
        cmds.append(["vector-map", "env2", "--method", m, "--spacing", "50", "--hide", "0",
                     "--out", str(out / f"vm_hide_{m}.csv")])  # fmt: skip
    for m in ("delv", "delv-compass", "alv", "acv", "delv-gap-compass", "warping"):
        cmds.append(["catchment", "env1", "--method", m, "--spacing", "100", *NOISE,
                     "--out", str(out / f"c_{m}.csv"), "--summary", str(out / f"c_{m}.json")])  # fmt: skip
    for m in ("delv-compass", "acv", "delv-compass-agent"):
        cmds.append(["catchment", "env1", "--method", m, "--spacing", "100", "--occlude", "1",
                     "--out", str(out / f"occ_{m}.csv")])  # fmt: skip
    cmds.append(["success-rate", "env1", "--method", "delv-compass", "--trials", "10", *NOISE,
                 "--out", str(out / "sr.csv")])  # fmt: skip
    (out / "sweep.toml").write_text(SWEEP)
    cmds.append(["sweep", str(out / "sweep.toml"), "--out", str(out / "sweep")])
    if reproduce:
        cmds.append(["reproduce", "--quick", "--out", str(out / "reproduce")])
    return cmds


def scrub(x):
    if isinstance(x, dict):
        return {k: scrub(v) for k, v in sorted(x.items()) if k not in VOLATILE}
    if isinstance(x, list):
        return [scrub(v) for v in x]
    return x


def digest(path: Path) -> str:
    if path.suffix == ".json":
        data = json.dumps(scrub(json.loads(path.read_text())), sort_keys=True).encode()
    else:
        data = path.read_bytes()
    return hashlib.sha256(data).hexdigest()


def fingerprint(reproduce: bool) -> dict[str, str]:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        env = {**os.environ, "DELVJAX_CACHE_DIR": str(out / "cache")}
        for c in commands(out, reproduce):
            r = subprocess.run([sys.executable, "-m", "delvjax.cli", *c], env=env, capture_output=True, text=True)
            if r.returncode:
                sys.exit(f"failed: delvjax {' '.join(c)}\n{r.stderr[-2000:]}")
            print(".", end="", flush=True, file=sys.stderr)
        files = [p for p in out.rglob("*") if p.is_file() and p.suffix in {".csv", ".nc", ".json"}]
        keep = [p for p in files if "cache" not in p.relative_to(out).parts]
        return {str(p.relative_to(out)): digest(p) for p in sorted(keep)}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--save", help="write the fingerprint to this JSON file")
    p.add_argument("--compare", help="compare with a saved fingerprint; exit 1 on any difference")
    p.add_argument("--no-reproduce", action="store_true", help="leave out reproduce --quick")
    a = p.parse_args()
    fp = fingerprint(not a.no_reproduce)
    print(f"\n{len(fp)} outputs fingerprinted", file=sys.stderr)
    if a.save:
        Path(a.save).write_text(json.dumps(fp, indent=1, sort_keys=True) + "\n")
    if a.compare:
        old = json.loads(Path(a.compare).read_text())
        diff = sorted(k for k in old.keys() | fp.keys() if old.get(k) != fp.get(k))
        for k in diff:
            print(f"DIFFERS {k}: {old.get(k, 'missing')[:12]} -> {fp.get(k, 'missing')[:12]}")
        print(f"{len(fp) - len(diff)} of {len(old.keys() | fp.keys())} outputs identical")
        sys.exit(1 if diff else 0)


if __name__ == "__main__":
    main()
