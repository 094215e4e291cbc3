"""`delvjax reproduce`: every simulation study of the thesis in one command (docs/reproduce.md).

A study is a module of the `studies` package with a `TITLE` and a `run(ctx)` function; the
registry `studies.STUDIES` lists them in report order. The runner gives each study a
`StudyContext` (its output folder, the run's config, writers that record every figure,
table and number), then writes `<study>/study.json` last. A study whose content hash (its
code, the code of `delvjax`, the run's config and the versions) matches its `study.json` is
skipped, so an interrupted run resumes where it stopped and a second run does no work.
Every file is written under a temporary name and renamed (`outputs._files.atomic_path`).
"""

from __future__ import annotations

import ast
import hashlib
import importlib
import json
import os
import sys
import threading
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path
from typing import Any

from ..core.checks import seed_value
from ..core.deprecation import deprecated
from ..core.errors import InputError, did_you_mean, warn
from ..outputs._cache import enable_compilation_cache, package_sources, release_programs_near_map_limit
from ..outputs._files import check_out_dir, write_json
from ._report import write_report
from ._study import (
    STUDY_FILE,
    RunConfig,
    StudyContext,
    StudyRecord,
    compile_seconds,
    config_record,
    stop_sampling,
    versions,
)

STUDIES = "delvjax.studies"  # the package of the study runners, the thesis's numbers and the claim checks


def _studies_root() -> Path:
    return Path(importlib.import_module(STUDIES).__file__).parent


def _module_file(root: Path, module: str) -> Path | None:
    """The file of a module of the studies package (`delvjax.studies.runs._common` -> runs/_common.py)."""
    parts = module.split(".")[2:]
    for path in (root.joinpath(*parts).with_suffix(".py"), root.joinpath(*parts, "__init__.py")):
        if parts and path.is_file():
            return path
    return None


def _sibling_imports(path: Path) -> set[Path]:
    """The modules of the studies package that `path` imports, and theirs (relative or absolute imports)."""
    root = _studies_root()
    seen: set[Path] = set()
    todo = [path]
    while todo:  # a few files: the study's import closure within its package
        current = todo.pop()
        package = [*STUDIES.split("."), *current.relative_to(root).parent.parts]  # the file's package
        for node in ast.walk(ast.parse(current.read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            base = package[: len(package) - node.level + 1] if node.level else []  # `from ..x` climbs one
            module = ".".join(base + ([node.module] if node.module else []))
            if not module.startswith(STUDIES):
                continue
            for name in [module] + [f"{module}.{a.name}" for a in node.names]:
                target = _module_file(root, name)
                if target is not None and target not in seen:
                    seen.add(target)
                    todo.append(target)
    return seen


def study_hash(module, config: RunConfig) -> str:
    """Hash of the study's module and the study modules it imports (runs/_common.py, another study),
    the thesis's numbers (studies/thesis/), every delvjax source, the run's config and versions."""
    h = hashlib.sha256()
    root = _studies_root()
    own = Path(module.__file__)
    thesis = set((root / "thesis").glob("*.py"))
    files = [own, *sorted(_sibling_imports(own) | {root / "runs" / "_common.py"} | thesis)]
    for path in files + package_sources():
        if path.is_file():
            h.update(path.name.encode())
            h.update(path.read_bytes())
    h.update(json.dumps(asdict(config), sort_keys=True).encode())
    h.update(json.dumps({k: v for k, v in versions().items() if k != "python"}, sort_keys=True).encode())
    return h.hexdigest()[:16]


def load_record(folder: Path) -> StudyRecord | None:
    """The study's record, or None if there is none; a record that cannot be read (damaged, or not
    one delvjax wrote) is None too, with a warning line: the study runs again."""
    path = folder / STUDY_FILE
    if not path.is_file():
        return None
    try:
        return StudyRecord.from_json(json.loads(path.read_text()))
    except (OSError, ValueError, TypeError) as exc:
        warn(f"study record {path} cannot be read ({type(exc).__name__}): the study runs again")
        return None


def is_current(folder: Path, digest: str) -> bool:
    """True if the study's record has this hash and every file it lists still exists."""
    rec = load_record(folder)
    return rec is not None and rec.hash == digest and all((folder / f).is_file() for f in rec.files)


# --- the registry and the run --------------------------------------------------------------


def registry(names: list[str] | None = None) -> dict[str, Any]:
    """name -> study module, in report order (`studies.STUDIES`), or only `names`."""
    names = list(importlib.import_module(STUDIES).STUDIES) if names is None else names
    return {name: importlib.import_module(f"{STUDIES}.runs.{name}") for name in names}


def select(only: str | Sequence[str] | None, quick: bool = False) -> list[str]:
    """Validated study names (`--only a,b`, or a list of names), in registry order. Without `--only`, a
    quick run leaves out the studies of `studies.FULL_RUN_ONLY`; `--only` runs what it names, also under
    `--quick`."""
    package = importlib.import_module(STUDIES)
    names = list(package.STUDIES)
    if only is None:
        return [n for n in names if not (quick and n in package.FULL_RUN_ONLY)]
    if isinstance(only, str):
        parts = only.split(",")
    elif isinstance(only, (list, tuple)) and all(isinstance(s, str) for s in only):
        parts = list(only)
    else:
        raise InputError("--only", only, "must be study names (a comma-separated string or a list of strings)")
    wanted = [s.strip() for s in parts if s.strip()]
    if not wanted:
        raise InputError("--only", only, "must name at least one study")
    for s in wanted:
        if s not in names:
            raise InputError("--only", s, f"unknown study{did_you_mean(s, names)} (choose from {', '.join(names)})")
    return [n for n in names if n in wanted]


def default_workers() -> int:
    """Studies run side by side: one per CPU core, at most MAX_WORKERS (each holds its programs and results)."""
    return max(1, min(MAX_WORKERS, os.cpu_count() or 1))


MAX_WORKERS = 4


def schedule(names: list[str]) -> list[str]:
    """The studies longest first (each study module's `COST`), all of them side by side: two studies that
    need the same new program wait for one compilation of it (docs/reproduce.md "Speed")."""
    modules = registry(names)  # already imported by a run: the order costs nothing
    return sorted(names, key=lambda n: -modules[n].COST)  # stable: registry order among equals


@contextmanager
def _bars(total: int, enabled: bool) -> Iterator[Any]:
    from tqdm.auto import tqdm  # tqdm: loaded only when a progress bar is shown

    bar = tqdm(
        total=total,
        desc="studies",
        unit="study",
        disable=not enabled,
        file=sys.stderr,
        bar_format="{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}]",
    )
    try:
        yield bar
    finally:
        bar.close()


def run_study(
    name: str,
    module,
    out: Path,
    config: RunConfig,
    force: bool = False,
    progress: bool = True,
    painter: ThreadPoolExecutor | None = None,
    digest: str | None = None,
) -> tuple[StudyRecord, bool, Future | None]:
    """Run one study unless current; returns (record, ran, future of its completion).

    `painter`: one thread that renders the figures while the next study computes; the
    study.json is then written by that thread after the figures (`StudyContext.finish`).
    `record.seconds` is the study's computation; rendering its figures overlaps the next one.
    `digest`: the study's hash taken when its code was imported (`reproduce` takes every study's
    before the first runs, so a source edited during a run marks the studies it changes as stale
    instead of stamping code that did not run with the new hash); None: taken now.
    """
    from tqdm.auto import tqdm  # tqdm: loaded only when a progress bar is shown

    folder = out / name
    digest = study_hash(module, config) if digest is None else digest
    if not force and is_current(folder, digest):
        return load_record(folder), False, None  # type: ignore[return-value]
    record = StudyRecord(
        name=name, title=module.TITLE, hash=digest, settings=config_record(config), versions=versions()
    )
    c0, t0 = compile_seconds(), time.perf_counter()
    try:
        with tqdm(
            total=getattr(module, "STEPS", None), desc=f"  {name}", leave=False, disable=not progress, file=sys.stderr
        ) as bar:
            ctx = StudyContext(folder, record, config, bar, painter)
            module.run(ctx)
        record.seconds = time.perf_counter() - t0
        record.compile_seconds = compile_seconds() - c0
    finally:
        stop_sampling()
    data = asdict(record)
    # last, after the figures: its presence marks the study complete
    done = ctx.finish(lambda: write_json(folder / STUDY_FILE, data))
    return record, True, done


def reproduce(
    out: str | Path = "results",
    quick: bool = False,
    only: str | Sequence[str] | None = None,
    force: bool = False,
    seed: int = 0,
    progress: bool = True,
    config: RunConfig | None = None,
    workers: int | None = None,
    formats: str | Sequence[str] = "png",
    settings: RunConfig | None = None,
) -> dict:
    """Run the selected studies (skipping current ones), then write report.md / report.html.

    `config=` overrides quick/seed (e.g. a tiny grid for tests: RunConfig(spacing=200.0, trials=10); `settings=`,
    its name before this release, still works for one release with a DeprecationWarning).
    `formats`: figure files besides the PNG ("png,pdf,svg"; `RunConfig.formats`).
    `workers`: studies run side by side in threads (default `default_workers()`; 1: one at a time).
    Each study's numbers are the same either way: a study reads only its own inputs and keys, and
    the programs are the same (docs/reproduce.md "Speed"; tested).
    Returns {"records": {name: StudyRecord}, "ran": [names], "report": path of report.html}.
    """

    seed = seed_value(seed)
    if settings is not None:  # the name before this release
        if config is not None:
            raise InputError("settings", settings, "is the former name of config=, given too: give config= alone")
        deprecated(
            "delvjax: reproduce(settings=...) is now reproduce(config=...) (a RunConfig); settings= goes next release"
        )
        config = settings
    config = config or RunConfig.make(quick=quick, seed=seed, formats=formats)
    names = select(only, config.quick)
    workers = default_workers() if workers is None else int(workers)
    if workers < 1:
        raise InputError("workers", workers, "must be at least 1")
    out = check_out_dir(out)
    for name in names:  # each study writes into out/<name>/ (and the report beside them)
        if (out / name).exists() and not (out / name).is_dir():
            raise InputError("--out", str(out), f"holds a file {name}, where the folder of study {name} goes")
    out.mkdir(parents=True, exist_ok=True)
    enable_compilation_cache()
    compile_seconds()  # the compile-event listener from the start; this thread runs no study itself
    stop_sampling()
    modules = registry(names)
    digests = {name: study_hash(module, config) for name, module in modules.items()}  # the code that runs
    records, ran = {}, []
    t0 = time.perf_counter()
    completions = []
    order = schedule(names)

    def one(name: str) -> None:
        rec, did, done = run_study(
            name, modules[name], out, config, force=force, progress=progress, painter=painter, digest=digests[name]
        )
        records[name] = rec
        completions.append(done)
        if did:
            ran.append(name)
        release_programs_near_map_limit()  # a full run in one process stays clear of Linux's mapping cap
        bar.update(1)

    with _bars(len(names), progress) as bar, ThreadPoolExecutor(1, thread_name_prefix="figures") as painter:
        bar.set_postfix_str(f"{min(workers, len(order))} side by side")
        _side_by_side(one, order, workers)
        for done in completions:  # figures and study.json files written; a failure is raised here
            if done is not None:
                done.result()
    ran = [n for n in names if n in ran]  # registry order, however they finished
    order = importlib.import_module(STUDIES).STUDIES
    for name in order:  # studies of an earlier run (other --only) still appear in the report
        if name not in records:
            rec = load_record(out / name)
            if rec is not None and rec.settings == config_record(config):
                records[name] = rec
    ordered = {n: records[n] for n in order if n in records}
    report = write_report(out, ordered, config, versions(), wall_seconds=time.perf_counter() - t0, ran=ran)
    return {"records": ordered, "ran": ran, "report": report}


def _side_by_side(fn, names: list[str], workers: int) -> None:
    """`fn(name)` for every name, `workers` at a time in threads (XLA runs and compiles outside the
    GIL, so two studies use two cores). The first failure stops the studies not yet started and is
    raised once the running ones end; a study that failed leaves no study.json, so it runs again."""
    if workers == 1:
        for name in names:  # a dozen heterogeneous studies: the driver, not a hot path
            fn(name)
        return
    stop = threading.Event()

    def guarded(name: str) -> None:
        if stop.is_set():  # a study failed: start no other
            return
        try:
            fn(name)
        except BaseException:
            stop.set()
            raise

    with ThreadPoolExecutor(workers, thread_name_prefix="study") as pool:
        futures = [pool.submit(guarded, name) for name in names]
        try:
            for f in futures:  # in submission order: the first failure is raised once the running ones end
                f.result()
        except BaseException:
            stop.set()
            for f in futures:
                f.cancel()
            raise
