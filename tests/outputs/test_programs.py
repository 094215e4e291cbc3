"""Programs kept between command-line runs (`outputs._programs`, issue 54): a warm `delvjax vector-map`
neither traces nor compiles its map program, and writes the same bytes as a run without any cache."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import jax
import jax.numpy as jnp
import numpy as np

from delvjax.outputs import _programs

RUN = [sys.executable, "-m", "delvjax.cli", "vector-map", "env1", "--method", "alv", "--spacing", "100"]


def cli(out, cache: str) -> str:
    """Run the vector map with JAX's compile log on; its stderr."""
    env = {**os.environ, "DELVJAX_CACHE_DIR": cache, "JAX_LOG_COMPILES": "1"}
    run = subprocess.run([*RUN, "--out", str(out)], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and "wrote" in run.stdout, run.stderr[-2000:]
    return run.stderr


def test_a_warm_run_loads_its_program_and_writes_the_same_numbers(tmp_path):
    cache = tmp_path / "xla"
    cold = cli(tmp_path / "cold.csv", str(cache))
    assert "jit(_vector_map)" in cold  # compiled once, then kept
    assert len(list(cache.glob(_programs.PREFIX + "*"))) == 1 and list(cache.glob(_programs.FACT + "*"))
    warm = cli(tmp_path / "warm.csv", str(cache))
    assert "jit(_vector_map)" not in warm  # neither traced nor compiled: loaded
    cli(tmp_path / "plain.csv", "")  # no cache at all: jit as usual
    plain = (tmp_path / "plain.csv").read_bytes()
    assert (tmp_path / "cold.csv").read_bytes() == plain == (tmp_path / "warm.csv").read_bytes()


def test_a_kept_program_is_the_jitted_one_and_a_broken_entry_is_compiled_again(tmp_path, monkeypatch):
    monkeypatch.setattr(_programs, "folder", lambda: tmp_path)
    fn = jax.jit(lambda x, s: (jnp.cumsum(x) * s, jnp.sort(x)))
    x = jnp.linspace(-3.0, 5.0, 37, dtype=jnp.float32)[::-1]
    kept = _programs.stored_program(fn, tuple)
    first, again = kept(x, 2.5), kept(x, 2.5)  # compiled and written, then found in this process
    (entry,) = tmp_path.glob(_programs.PREFIX + "*")
    _programs._LOADED.clear()
    entry.write_bytes(b"not a program")
    third = kept(x, 2.5)  # unreadable: compiled and written again
    assert entry.stat().st_size > 100
    want = fn(x, 2.5)  # last: a program compiled by a jit call first does not serialise (it then runs unkept)
    assert all(
        np.array_equal(a, w) and np.array_equal(b, w) and np.array_equal(c, w)
        for a, b, c, w in zip(first, again, third, want)
    )
    assert _programs.entry_name(fn, (x, 2.5)) != _programs.entry_name(fn, (x[:5], 2.5))  # shapes are in the name
    assert _programs.entry_name(fn, (x, np.float32(2.5))) != _programs.entry_name(fn, (x, 2.5))  # so are dtypes
    assert _programs.arguments_key((x, object())) is None  # what it cannot name is not kept


def test_a_number_is_computed_once_and_read_back(tmp_path, monkeypatch):
    monkeypatch.setattr(_programs, "folder", lambda: tmp_path)
    calls = []
    compute = lambda: calls.append(1) or 5760  # noqa: E731
    assert _programs.kept_number("peak", "key", compute) == 5760
    assert _programs.kept_number("peak", "key", compute) == 5760 and len(calls) == 1
    assert _programs.kept_number("peak", "other key", compute) == 5760 and len(calls) == 2
    monkeypatch.setattr(_programs, "folder", lambda: None)
    assert _programs.kept_number("peak", "key", compute) == 5760 and len(calls) == 3  # no folder: computed


def test_only_the_most_recently_used_entries_are_kept(tmp_path):
    for i in range(5):
        path = tmp_path / f"{_programs.PREFIX}{i}"
        path.write_bytes(b"x")
        os.utime(path, (time.time() + i, time.time() + i))
    (tmp_path / "jit_other-cache").write_bytes(b"JAX's")
    _programs.evict(tmp_path, keep=2)
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        f"{_programs.PREFIX}3",
        f"{_programs.PREFIX}4",
        "jit_other-cache",
    ]


LAPACK = """
import sys, jax, jax.numpy as jnp
jax.config.update("jax_compilation_cache_dir", sys.argv[1])
from delvjax.outputs import _programs
kept = _programs.stored_program(jax.jit(lambda a: jnp.linalg.qr(a)[1]), lambda leaves: leaves[0])
print(repr(kept(jnp.eye(3, dtype=jnp.float32) + 1.0).tolist()))
"""


def test_a_kept_program_with_lapack_calls_runs_in_a_fresh_process(tmp_path):
    """A program's LAPACK kernels (delv-refined's least squares) need LAPACK initialised, which a trace
    does: a loaded program is not traced (it segfaulted before `load` initialised it, as jax.export does)."""
    runs = [
        subprocess.run([sys.executable, "-c", LAPACK, str(tmp_path)], capture_output=True, text=True, timeout=300)
        for _ in range(2)
    ]
    assert [r.returncode for r in runs] == [0, 0], runs[-1].stderr[-2000:]
    assert runs[0].stdout == runs[1].stdout and len(list(tmp_path.glob(_programs.PREFIX + "*"))) == 1
