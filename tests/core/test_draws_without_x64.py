"""Random draws give the same numbers with and without `jax_enable_x64` (issue 56: float32 and float64
gradients differed in sign because x64 drew other random headings, not because of rounding): every
`jax.random.uniform` / `normal` in delvjax draws float32 (docs/differentiable.md "Precision")."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import jax
import numpy as np

from delvjax.core.maps import random_headings
from delvjax.core.sensor import Noise

ROOT = Path(__file__).resolve().parents[2]
CHILD = """
import json, jax
from delvjax.core.maps import random_headings
from delvjax.core.sensor import Noise
key = jax.random.PRNGKey(7)
noise = Noise(bearing=0.02, compass=0.05)
print(json.dumps({"headings": [float(v) for v in random_headings(key, 5)],
                  "bearing": [float(v) for v in noise.bearing_errors(key, (3,))],
                  "x64": bool(jax.config.jax_enable_x64)}))
"""


def test_every_draw_names_its_dtype():
    # would catch: a new jax.random.uniform(key, shape) that draws float64 numbers under x64
    bare = []
    for path in (ROOT / "delvjax").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("uniform", "normal")
                and ast.unparse(node.func.value) == "jax.random"
                and not any(k.arg == "dtype" for k in node.keywords)
            ):
                bare.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not bare, bare


def test_x64_draws_the_same_headings_and_noise():
    key = jax.random.PRNGKey(7)
    noise = Noise(bearing=0.02, compass=0.05)
    here = {"headings": random_headings(key, 5), "bearing": noise.bearing_errors(key, (3,))}
    out = subprocess.run(
        [sys.executable, "-c", CHILD], env={**os.environ, "JAX_ENABLE_X64": "1"}, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    there = json.loads(out.stdout)
    assert there["x64"]
    for name in ("headings", "bearing"):
        assert np.array_equal(np.asarray(here[name], np.float32), np.asarray(there[name], np.float32)), name
