"""The persistent compilation cache is shared by processes (pytest workers, command-line subprocesses,
the processes of a sweep), so every read and write of an entry holds JAX's file lock: a bounded cache.
Without it JAX writes entries in place and a reader can meet one half written (a segfault in XLA's
deserializer, seen once in the suite)."""

from __future__ import annotations

import subprocess
import sys


def test_the_cache_is_bounded_and_locked(tmp_path):
    code = (
        "import jax, jax.numpy as jnp\n"
        "from delvjax.outputs._cache import CACHE_BYTES, enable_compilation_cache\n"
        "enable_compilation_cache()\n"
        "assert jax.config.jax_compilation_cache_max_size == CACHE_BYTES > 0\n"
        "jax.jit(lambda x: jnp.sort(x) @ x)(jnp.arange(300.0))\n"
        "from jax._src import compilation_cache as cc\n"
        "assert cc._cache is not None and cc._cache.eviction_enabled\n"  # the LRU cache: lock around get/put
        "print('locked')\n"
    )
    env = {"DELVJAX_CACHE_DIR": str(tmp_path / "xla"), "PATH": "/usr/bin:/bin", "JAX_PLATFORMS": "cpu"}
    env["JAX_PERSISTENT_CACHE_MIN_COMPILE_TIME_SECS"] = "0"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and run.stdout.strip() == "locked", run.stderr[-2000:]
    assert (tmp_path / "xla" / ".lockfile").exists() or any((tmp_path / "xla").iterdir())


def test_entries_of_an_unbounded_cache_get_the_access_time_the_bounded_one_needs(tmp_path):
    """A cache folder written by an earlier version (no `-atime` files) must not break later writes."""
    folder = tmp_path / "xla"
    folder.mkdir()
    (folder / "jit_old-0123-cache").write_bytes(b"old entry")
    code = (
        "import warnings, jax, jax.numpy as jnp\n"
        "warnings.simplefilter('error')\n"  # JAX warns when it cannot write an entry
        "from delvjax.outputs._cache import enable_compilation_cache\n"
        "enable_compilation_cache()\n"
        "jax.config.update('jax_persistent_cache_min_compile_time_secs', 0)\n"
        "jax.jit(lambda x: jnp.sort(x) @ x)(jnp.arange(300.0)).block_until_ready()\n"
    )
    env = {"DELVJAX_CACHE_DIR": str(folder), "PATH": "/usr/bin:/bin", "JAX_PLATFORMS": "cpu"}
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and "Error writing" not in run.stderr, run.stderr[-2000:]
    assert (folder / "jit_old-0123-atime").is_file()
    assert (folder / "jit_old-0123-cache").is_file() and len(list(folder.glob("*-cache"))) >= 2  # old and new


def test_compiled_programs_are_released_before_the_process_runs_out_of_memory_mappings(tmp_path):
    """Each cached CPU program holds memory mappings; near vm.max_map_count LLVM aborts the process
    (a pytest worker, twice in CI). Past the threshold `release_programs_near_map_limit` drops JAX's
    caches and the mappings with them; below it, nothing is dropped."""
    code = (
        "import jax, jax.numpy as jnp\n"
        "from delvjax.outputs import _cache\n"
        "before = _cache.mapped_regions()\n"
        "kept = [jax.jit(lambda x, i=i: jnp.cumsum(x) * i) for i in range(40)]\n"  # alive: only clearing frees
        "for i, f in enumerate(kept):\n"
        "    f(jnp.ones(i + 3)).block_until_ready()\n"
        "grown = _cache.mapped_regions()\n"
        "assert grown - before > 200, (before, grown)\n"  # about 16 a program (659 for 40, 585 freed; jax 0.11, CPU)
        "assert not _cache.release_programs_near_map_limit(1.0)\n"  # far below the cap: kept
        "assert _cache.mapped_regions() >= grown - 5\n"
        "_cache.map_limit = lambda: grown\n"  # as if the cap were where this process stands now
        "assert _cache.release_programs_near_map_limit(0.5)\n"
        "after = _cache.mapped_regions()\n"
        "assert grown - after > 200, (grown, after)\n"
        "print('released', grown - after)\n"
    )
    env = {"DELVJAX_CACHE_DIR": "", "PATH": "/usr/bin:/bin", "JAX_PLATFORMS": "cpu"}
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0 and run.stdout.startswith("released"), run.stderr[-2000:]
