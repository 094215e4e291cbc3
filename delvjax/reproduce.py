"""`delvjax reproduce`: every simulation study of the thesis in one command (docs/reproduce.md).

A study is a module of the `studies` package with a `TITLE` and a `run(ctx)` function; the
registry `studies.STUDIES` lists them in report order. The runner gives each study a
`StudyContext` (its output folder, the run's settings, writers that record every figure,
table and number), then writes `<study>/study.json` last. A study whose content hash (its
code, the code of `delvjax`, the settings and the versions) matches its `study.json` is
skipped, so an interrupted run resumes where it stopped and a second run does no work.
Every file is written under a temporary name and renamed (`io.atomic_path`).
"""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import platform
import sys
import time
from concurrent.futures import Future, ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator

import jax

from .errors import InputError
from .io import _jsonable, write_csv, write_figure, write_json, write_rows_csv

STUDY_FILE = "study.json"
COMPILE_EVENTS = ("/jax/core/compile/jaxpr_trace_duration", "/jax/core/compile/jaxpr_to_mlir_module_duration",
                  "/jax/core/compile/backend_compile_duration")


@dataclass(frozen=True)
class Settings:
    """What a run depends on besides the code (recorded in the report and every JSON).

    spacing: grid spacing cm (docs/model.md §5, 25 = 40 x 40; --quick: 100 = 10 x 10); trials: rollouts
    per success-rate distance bin (thesis: 100; they fill one trial block, so --quick keeps
    them); seed: every random heading, release point and noise draw; lanes: trials advanced side by
    side in the rollout program (`rollouts.run_trials`; no number depends on it): 256 fill the
    program best on the large calls of a full run, 128 waste less on the 99-trial calls of --quick.
    """

    quick: bool = False
    seed: int = 0
    spacing: float = 25.0
    trials: int = 100
    lanes: int = 256

    @classmethod
    def make(cls, quick: bool = False, seed: int = 0) -> "Settings":
        return cls(quick=quick, seed=seed, spacing=100.0 if quick else 25.0, trials=100, lanes=128 if quick else 256)


def settings_record(settings: Settings) -> dict:
    """The settings as recorded in every study.json and the report, with the rollout rules."""
    from .rollouts import DEFAULT_RULES, PHYSICAL_RULES

    return {**asdict(settings), "rules": {"default": DEFAULT_RULES, "physical": PHYSICAL_RULES}}


def versions() -> dict[str, str]:
    from . import __version__

    import numpy

    return {"delvjax": __version__, "jax": jax.__version__, "numpy": numpy.__version__,
            "python": platform.python_version(), "backend": jax.default_backend()}


# --- compile-time accounting -------------------------------------------------------------

_COMPILE_SECONDS = [0.0]


def _on_duration(event: str, duration: float, **_: Any) -> None:
    if event in COMPILE_EVENTS:
        _COMPILE_SECONDS[0] += duration


_LISTENING = []


def compile_seconds() -> float:
    """Seconds spent tracing, lowering and compiling XLA programs in this process so far."""
    if not _LISTENING:
        jax.monitoring.register_event_duration_secs_listener(_on_duration)
        _LISTENING.append(True)
    return _COMPILE_SECONDS[0]


# --- one study's context -----------------------------------------------------------------

@dataclass
class StudyRecord:
    """What a study produced, as written to its study.json and read by the report."""

    name: str
    title: str
    hash: str = ""
    settings: dict = field(default_factory=dict)
    versions: dict = field(default_factory=dict)
    seconds: float = 0.0
    compile_seconds: float = 0.0
    figures: list = field(default_factory=list)  # {"file", "caption"}
    tables: list = field(default_factory=list)  # {"id", "title", "source", "file", "columns", "rows", "note"}
    numbers: dict = field(default_factory=dict)  # flat keys -> JSON values, read by the claims
    files: list = field(default_factory=list)


class StudyContext:
    """The output folder and writers of one study; every write is atomic and recorded."""

    def __init__(self, out: Path, record: StudyRecord, settings: Settings, bar=None,
                 painter: ThreadPoolExecutor | None = None):
        self.out, self.record, self.settings, self._bar = out, record, settings, bar
        self._painter, self._pending = painter, []  # type: ignore[var-annotated]
        out.mkdir(parents=True, exist_ok=True)

    def _file(self, name: str) -> Path:
        self.record.files.append(name)
        return self.out / name

    def figure(self, name: str, fig, caption: str) -> None:
        """Save a matplotlib figure as `name` (.png) with the caption the report prints under it."""
        import matplotlib.pyplot as plt

        plt.close(fig)  # pyplot state stays in this thread; rendering needs none
        path = self._file(name)
        if self._painter is None:
            write_figure(fig, path)
        else:  # rendered while this thread waits on the device: figures overlap the computation
            self._pending.append(self._painter.submit(write_figure, fig, path))
        self.record.figures.append({"file": name, "caption": caption})

    def finish(self, last: Callable[[], None]) -> Future | None:
        """Run `last` (the study.json write) once every figure of the study is written: on the
        figure thread, after them (one thread, first in first out), and only if none failed.
        Returns its future (None when run here, without a figure thread)."""
        pending: list[Future] = self._pending
        self._pending = []
        if self._painter is None:
            last()
            return None

        def after_figures() -> None:
            for f in pending:
                f.result()  # a failed figure raises here: no study.json, so the study runs again
            last()

        return self._painter.submit(after_figures)

    def table(self, table_id: str, title: str, rows: list[dict], source: str = "", note: str = "",
              columns: list[str] | None = None) -> None:
        """A table of the report (and `<table_id>.csv`): rows of flat dicts, `columns` shown in the report."""
        write_rows_csv(self._file(f"{table_id}.csv"), rows)
        self.record.tables.append({"id": table_id, "title": title, "source": source, "note": note,
                                   "file": f"{table_id}.csv",
                                   "columns": columns or list(dict.fromkeys(k for r in rows for k in r)),
                                   "rows": _jsonable(rows)})

    def csv(self, name: str, columns: dict | None = None, rows: list[dict] | None = None) -> None:
        """A data file beside the figures (columns of equal length, or rows)."""
        if rows is not None:
            write_rows_csv(self._file(name), rows)
        else:
            write_csv(self._file(name), columns or {})

    def json(self, name: str, obj: Any) -> None:
        write_json(self._file(name), obj)

    def number(self, key: str, value: Any) -> None:
        """A headline number the claims table reads (`numbers[key]`)."""
        self.record.numbers[key] = _jsonable(value)

    def step(self, text: str) -> None:
        """Progress within a long study (advances the inner bar)."""
        if self._bar is not None:
            self._bar.set_postfix_str(text[:60])
            self._bar.update(1)


# --- content hash and resume ---------------------------------------------------------------

def _package_sources() -> list[Path]:
    root = Path(__file__).resolve().parent
    return sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)


def study_hash(module, settings: Settings) -> str:
    """Hash of the study's module, studies/common.py, every delvjax source, settings and versions."""
    h = hashlib.sha256()
    files = [Path(module.__file__)] + [Path(module.__file__).with_name(n) for n in ("common.py", "thesis.py")]
    for path in files + _package_sources():
        if path.is_file():
            h.update(path.name.encode())
            h.update(path.read_bytes())
    h.update(json.dumps(asdict(settings), sort_keys=True).encode())
    h.update(json.dumps({k: v for k, v in versions().items() if k != "python"}, sort_keys=True).encode())
    return h.hexdigest()[:16]


def load_record(folder: Path) -> StudyRecord | None:
    path = folder / STUDY_FILE
    try:
        data = json.loads(path.read_text())
        return StudyRecord(**data)
    except (OSError, ValueError, TypeError):
        return None


def is_current(folder: Path, digest: str) -> bool:
    """True if the study's record has this hash and every file it lists still exists."""
    rec = load_record(folder)
    return rec is not None and rec.hash == digest and all((folder / f).is_file() for f in rec.files)


# --- the registry and the run --------------------------------------------------------------

def registry(names: list[str] | None = None) -> dict[str, Any]:
    """name -> study module, in report order (`studies.STUDIES`), or only `names`."""
    names = list(importlib.import_module("studies").STUDIES) if names is None else names
    return {name: importlib.import_module(f"studies.{name}") for name in names}


def select(only: str | None) -> list[str]:
    """Validated study names (`--only a,b`), in registry order."""
    names = list(importlib.import_module("studies").STUDIES)
    if only is None:
        return names
    wanted = [s.strip() for s in only.split(",") if s.strip()]
    if not wanted:
        raise InputError("--only", only, "must name at least one study")
    for s in wanted:
        if s not in names:
            raise InputError("--only", s, f"unknown study (choose from {', '.join(names)})")
    return [n for n in names if n in wanted]


def check_out_dir(out: str | Path) -> Path:
    """The output folder, created if needed and checked writable before any work (else InputError)."""
    path = Path(out)
    if path.exists() and not path.is_dir():
        raise InputError("--out", str(out), "exists and is not a directory")
    probe_parent = path
    while not probe_parent.exists():
        probe_parent = probe_parent.parent
    if not probe_parent.is_dir():
        raise InputError("--out", str(out), f"lies under {probe_parent}, which is not a directory")
    if not os.access(probe_parent, os.W_OK | os.X_OK):
        raise InputError("--out", str(out), "is not writable")
    return path


@contextmanager
def _bars(total: int, enabled: bool) -> Iterator[Any]:
    from tqdm.auto import tqdm

    bar = tqdm(total=total, desc="studies", unit="study", disable=not enabled, file=sys.stderr,
               bar_format="{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}]")
    try:
        yield bar
    finally:
        bar.close()


def run_study(name: str, module, out: Path, settings: Settings, force: bool = False,
              progress: bool = True, painter: ThreadPoolExecutor | None = None
              ) -> tuple[StudyRecord, bool, Future | None]:
    """Run one study unless current; returns (record, ran, future of its completion).

    `painter`: one thread that renders the figures while the next study computes; the
    study.json is then written by that thread after the figures (`StudyContext.finish`).
    `record.seconds` is the study's computation; rendering its figures overlaps the next one.
    """
    from tqdm.auto import tqdm

    folder = out / name
    digest = study_hash(module, settings)
    if not force and is_current(folder, digest):
        return load_record(folder), False, None  # type: ignore[return-value]
    record = StudyRecord(name=name, title=module.TITLE, hash=digest, settings=settings_record(settings),
                         versions=versions())
    c0, t0 = compile_seconds(), time.perf_counter()
    with tqdm(total=getattr(module, "STEPS", None), desc=f"  {name}", leave=False, disable=not progress,
              file=sys.stderr) as bar:
        ctx = StudyContext(folder, record, settings, bar, painter)
        module.run(ctx)
    record.seconds = time.perf_counter() - t0
    record.compile_seconds = compile_seconds() - c0
    data = asdict(record)
    # last, after the figures: its presence marks the study complete
    done = ctx.finish(lambda: write_json(folder / STUDY_FILE, data))
    return record, True, done


def reproduce(out: str | Path = "results", quick: bool = False, only: str | None = None, force: bool = False,
              seed: int = 0, progress: bool = True, settings: Settings | None = None) -> dict:
    """Run the selected studies (skipping current ones), then write report.md / report.html.

    `settings` overrides quick/seed (e.g. a tiny grid for tests: Settings(spacing=200.0, trials=10)).
    Returns {"records": {name: StudyRecord}, "ran": [names], "report": path of report.html}.
    """
    from .cache import enable_compilation_cache
    from .options import seed_value
    from .report import write_report

    names = select(only)
    seed = seed_value(seed)
    out = check_out_dir(out)
    out.mkdir(parents=True, exist_ok=True)
    settings = settings or Settings.make(quick=quick, seed=seed)
    enable_compilation_cache()
    compile_seconds()
    modules = registry(names)
    records, ran = {}, []
    t0 = time.perf_counter()
    completions = []
    with _bars(len(names), progress) as bar, ThreadPoolExecutor(1, thread_name_prefix="figures") as painter:
        for name in names:  # a dozen heterogeneous studies: the driver, not a hot path
            bar.set_postfix_str(name)
            rec, did, done = run_study(name, modules[name], out, settings, force=force, progress=progress,
                                       painter=painter)
            records[name] = rec
            completions.append(done)
            if did:
                ran.append(name)
            bar.update(1)
        for done in completions:  # figures and study.json files written; a failure is raised here
            if done is not None:
                done.result()
    order = importlib.import_module("studies").STUDIES
    for name in order:  # studies of an earlier run (other --only) still appear in the report
        if name not in records:
            rec = load_record(out / name)
            if rec is not None and rec.settings == settings_record(settings):
                records[name] = rec
    ordered = {n: records[n] for n in order if n in records}
    report = write_report(out, ordered, settings, versions(), wall_seconds=time.perf_counter() - t0, ran=ran)
    return {"records": ordered, "ran": ran, "report": report}
