"""Persistent XLA compilation cache for the command line and studies (not for library imports)."""

from __future__ import annotations

import os
from pathlib import Path

import jax

CACHE_SUFFIX, ATIME_SUFFIX = "-cache", "-atime"  # the names of an entry and its access time (jax._src.lru_cache)
CACHE_BYTES = 2 << 30  # the compilation cache's bound (2 GiB; a full run writes about 0.1 GiB)


def enable_compilation_cache() -> None:
    """Cache compiled programs under $DELVJAX_CACHE_DIR (default ~/.cache/delvjax/xla):
    a second run of the same command skips the seconds of compilation. Set it to "" to disable."""
    path = os.environ.get("DELVJAX_CACHE_DIR", str(Path.home() / ".cache" / "delvjax" / "xla"))
    if not path:
        return
    try:
        Path(path).mkdir(parents=True, exist_ok=True)
    except OSError:
        return
    jax.config.update("jax_compilation_cache_dir", path)
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.5)
    # A bound on its size, and with it JAX's file lock (the `filelock` package) around every read and write
    # of an entry: without one JAX writes entries in place, and a process that shares the folder (the
    # pytest workers, command-line subprocesses, the processes of a sweep) could read one half written
    # and crash in XLA's deserializer (a segfault, seen in the test suite). Least recently used entries go.
    jax.config.update("jax_compilation_cache_max_size", CACHE_BYTES)
    stamp_old_entries(Path(path))


def stamp_old_entries(folder: Path) -> None:
    """Give every cache entry written without a bound (earlier delvjax versions: no `-atime` file beside
    its `-cache` file) the access time JAX's bounded cache reads when it evicts; without one JAX fails
    every later write to the folder with a warning. The entry's modification time stands in for it."""
    for entry in folder.glob(f"*{CACHE_SUFFIX}"):
        stamp = folder / (entry.name.removesuffix(CACHE_SUFFIX) + ATIME_SUFFIX)
        if not stamp.exists():
            try:
                stamp.write_bytes(entry.stat().st_mtime_ns.to_bytes(8, "little"))
            except OSError:  # removed meanwhile by another process's eviction, or a read-only folder
                pass


def mapped_regions() -> int | None:
    """How many memory mappings this process holds (lines of /proc/self/maps); None where there is no /proc."""
    try:
        with open("/proc/self/maps", "rb") as f:
            return sum(1 for _ in f)
    except OSError:
        return None


def map_limit() -> int:
    """Linux's cap on one process's memory mappings (vm.max_map_count; 65530 unless raised)."""
    try:
        return int(Path("/proc/sys/vm/max_map_count").read_text())
    except (OSError, ValueError):
        return 65530


def release_programs_near_map_limit(fraction: float = 0.5) -> bool:
    """Drop JAX's in-memory caches of compiled programs (`jax.clear_caches`) once this process holds more
    than `fraction` of the memory mappings Linux allows it; True when it did.

    XLA's CPU backend keeps about 3.4 mappings per compiled program for as long as the program is cached
    (measured: 200 small programs, +682 mappings, all freed by `jax.clear_caches`). A long-lived process
    that compiles some 19,000 programs (a pytest worker, a notebook) reaches vm.max_map_count, and LLVM
    then aborts the whole process while loading the next one ("Unable to allocate section memory", a
    SIGABRT from `RuntimeDyldImpl::emitSection`). Later calls recompile, or read the persistent cache."""
    count = mapped_regions()
    if count is None or count <= fraction * map_limit():
        return False
    jax.clear_caches()
    return True


def package_sources() -> list[Path]:
    """Every source file of the delvjax package (study hashes, sweep cell digests), in a fixed order."""
    root = Path(__file__).resolve().parents[1]
    return sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)
