"""Compiled programs and trace-time facts kept on disk between command-line runs (issue 54): a warm
`delvjax vector-map` loads its program without tracing or lowering it, which JAX's persistent cache
needs to find an entry (0.7 s of a 1.2 s map on env1), and reads its memory bound without a trace.

Each entry's name is a digest of everything its program depends on: delvjax's source files, the
versions of JAX, jaxlib, equinox, optimistix and NumPy, JAX's settings, the device, and the structure,
static settings, shapes and dtypes of the arguments. A program is compiled fresh (not read from JAX's
cache, whose loaded programs do not serialise whole), checked by loading it back, and that loaded copy
runs, so a first and a later run execute the same compiled program and give the same numbers."""

from __future__ import annotations

import hashlib
import os
import pickle
import platform
import re
import threading
from collections.abc import Callable
from functools import cache
from importlib import metadata
from pathlib import Path

import equinox
import jax
import jaxlib
import numpy as np

from ._cache import package_sources

try:  # what jax.export calls before it runs a program it did not lower (a kept one is not traced either)
    from jax._src.lax.linalg import initialize_lapack
except ImportError:  # another JAX: a program with LAPACK calls is then compiled again, not loaded
    initialize_lapack = None

PREFIX = "delvjax-program-"  # beside JAX's entries (jit_...-cache) in the compilation cache folder
FACT = "delvjax-fact-"  # a number found by tracing (`kept_number`)
MAX_ENTRIES = 64  # programs kept (about 0.5-3 MB each); the least recently used go first
FORMAT = 2  # of an entry file: {"format", "outputs", "targets" (its custom calls), "payload"}
UNKEYED = ("compilation_cache", "persistent_cache", "log", "explain_cache_misses")  # settings that change no program

_LOADED: dict[str, Callable] = {}  # this process's loaded programs, by entry name


def folder() -> Path | None:
    """Where programs are kept: the compilation cache's folder (`enable_compilation_cache`), if any."""
    path = jax.config.jax_compilation_cache_dir
    return Path(path) if path and jax.config.jax_enable_compilation_cache else None


@cache
def setup_digest() -> str:
    """The digest of what every program depends on besides its arguments: delvjax's sources, library
    versions, JAX's settings, the device and the machine."""
    h = hashlib.sha256()
    root = Path(__file__).resolve().parents[1]
    for path in package_sources():
        h.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes())
    h.update(f"{jax.__version__};{jaxlib.__version__};{equinox.__version__};{np.__version__};".encode())
    for name in ("optimistix", "lineax"):  # not loaded by a map: their installed versions (3 ms each)
        try:
            h.update(f"{name}={metadata.version(name)};".encode())
        except metadata.PackageNotFoundError:
            h.update(f"{name}=none;".encode())
    settings = jax.config.values
    h.update(repr([(k, settings[k]) for k in sorted(settings) if not any(u in k for u in UNKEYED)]).encode())
    device = jax.devices()[0]
    h.update(repr((device.platform, device.device_kind, device.client.platform_version, jax.device_count())).encode())
    h.update(repr((platform.machine(), os.environ.get("XLA_FLAGS", ""), cpu_model())).encode())
    return h.hexdigest()


def cpu_model() -> str:
    """The host CPU's model line (/proc/cpuinfo): a program compiled for one CPU may not load on another."""
    try:
        with open("/proc/cpuinfo") as f:
            return next((line for line in f if line.startswith("model name")), "")
    except OSError:
        return platform.processor()


def arguments_key(args: tuple) -> str | None:
    """The structure, static settings, shapes and dtypes of `args` as text; None when some part of it
    could not be written whole (a setting whose text is elided), and the program is then not kept."""
    leaves, tree = jax.tree.flatten(args)
    parts = [str(tree)]
    for x in leaves:
        if isinstance(x, (bool, int, float, complex)):
            parts.append(type(x).__name__)  # a Python number: traced as a weakly typed scalar
        elif isinstance(x, (np.ndarray, np.generic, jax.Array)):
            parts.append(f"{np.shape(x)}{x.dtype}{'w' if getattr(x, 'weak_type', False) else ''}")
        else:
            return None
    text = "|".join(parts)
    return None if "..." in text else text


def entry_name(fn: Callable, args: tuple) -> str | None:
    """The file name of `fn`'s program for `args`, or None where it is not kept."""
    key = arguments_key(args)
    if key is None:
        return None
    name = f"{getattr(fn, '__module__', '')}.{getattr(fn, '__qualname__', repr(fn))}"
    return PREFIX + hashlib.sha256(f"{setup_digest()}|{name}|{key}".encode()).hexdigest()[:40]


def stored_program(fn: Callable, rebuild: Callable[[list], object]) -> Callable:
    """`fn` (a `jax.jit` function) as a callable that keeps its compiled programs in the compilation
    cache's folder: loaded there when present, else compiled and written. `rebuild(leaves)` makes the
    result from the flat outputs (`lambda leaves: VectorMap(*leaves)`). Without a folder, `fn` runs."""

    def call(*args):
        where = folder()
        name = None if where is None else entry_name(fn, args)
        if name is None:
            return fn(*args)
        program = _LOADED.get(name)
        if program is None:
            program = load(where / name, args)
        if program is None:
            program = compile_and_keep(fn, args, where / name)
        if program is None:
            return fn(*args)
        _LOADED[name] = program
        return rebuild(jax.tree.leaves(program(*args)))

    return call


def load(path: Path, args: tuple) -> Callable | None:
    """The program of entry `path` for `args`, or None where there is none (or it cannot be read)."""
    from jax.experimental import serialize_executable  # jax.experimental: only when a program is kept

    try:
        entry = pickle.loads(path.read_bytes())
        if entry.get("format") != FORMAT:
            return None
        if any(t.startswith("lapack") for t in entry["targets"]):  # LAPACK's kernels find their routines
            if initialize_lapack is None:  # only once initialised (a trace does it; jax.export does too)
                return None
            initialize_lapack()
        outputs = jax.tree.structure([0] * entry["outputs"])
        compiled = serialize_executable.deserialize_and_load(entry["payload"], jax.tree.structure((args, {})), outputs)
    except Exception:  # a missing, half-evicted or foreign entry: compiled again
        return None
    try:
        os.utime(path)  # recently used: evicted last
    except OSError:
        pass
    return compiled


def compile_and_keep(fn: Callable, args: tuple, path: Path) -> Callable | None:
    """Compile `fn` for `args` without JAX's persistent cache, write it to `path` (whole or not at all),
    and return the program loaded back from what was written; where it cannot be kept (a program this
    backend does not serialise, a folder that cannot be written), the compiled program itself."""
    from jax.experimental import serialize_executable  # jax.experimental: only when a program is kept

    with _no_cache():
        lowered = fn.lower(*args)
        compiled = lowered.compile()
    targets = sorted(set(re.findall(r"custom_call @([\w.]+)", lowered.as_text())))
    if any("callback" in t for t in targets):  # a host callback's address is this process's: never kept
        return compiled
    try:
        payload, _, _ = serialize_executable.serialize(compiled)
    except Exception:  # e.g. `LessThan` is not serializable (a program compiled by a jit call before)
        return compiled
    n_out = len(jax.tree.leaves(compiled.out_info))
    data = pickle.dumps({"format": FORMAT, "outputs": n_out, "targets": targets, "payload": payload})
    temp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    try:
        temp.write_bytes(data)
        os.replace(temp, path)
    except OSError:
        temp.unlink(missing_ok=True)
        return compiled
    evict(path.parent)
    loaded = load(path, args)
    return compiled if loaded is None else loaded


class _no_cache:
    """JAX's persistent compilation cache off while a program is compiled (its decision is taken once per
    process, so it is reset on the way in and out; the folder setting stays)."""

    def __enter__(self):
        from jax.experimental.compilation_cache import compilation_cache  # jax.experimental: a program is kept

        self.reset, self.was = compilation_cache.reset_cache, jax.config.jax_enable_compilation_cache
        self.reset()
        jax.config.update("jax_enable_compilation_cache", False)

    def __exit__(self, *exc):
        jax.config.update("jax_enable_compilation_cache", self.was)
        self.reset()


def kept_number(what: str, key: str, compute: Callable[[], int]) -> int:
    """`compute()`, kept in the compilation cache's folder under (`what`, `key`, `setup_digest`): a fact
    found by tracing a program (its largest array) is read back by a later run instead of traced again."""
    where = folder()
    if where is None or "..." in key:
        return compute()
    path = where / (FACT + hashlib.sha256(f"{setup_digest()}|{what}|{key}".encode()).hexdigest()[:40])
    try:
        return int(path.read_text())
    except (OSError, ValueError):
        pass
    value = compute()
    temp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    try:
        temp.write_text(str(int(value)))
        os.replace(temp, path)
    except OSError:
        temp.unlink(missing_ok=True)
    evict(where, prefix=FACT, keep=4 * MAX_ENTRIES)
    return value


def evict(folder: Path, prefix: str = PREFIX, keep: int = MAX_ENTRIES) -> None:
    """Remove all but the `keep` most recently used entries of `folder` whose names start with `prefix`."""
    entries = []
    for path in folder.glob(prefix + "*"):
        try:
            entries.append((path.stat().st_mtime, path))
        except OSError:
            pass
    for _, path in sorted(entries, reverse=True)[keep:]:
        path.unlink(missing_ok=True)
