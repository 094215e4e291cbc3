"""What one study of `delvjax reproduce` sees and leaves behind (docs/reproduce.md): the run's
`RunConfig`, the `StudyContext` writers (figures, tables, numbers, data files) and the
`StudyRecord` written last as `<study>/study.json`; plus the run's versions and compile time."""

from __future__ import annotations

import platform
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import jax
import numpy

from .. import __version__
from ..core.deprecation import deprecated
from ..core.errors import InputError
from ..core.maps import SPACING
from ..core.rollouts import DEFAULT_LANES, DEFAULT_RULES, PHYSICAL_RULES, TRIALS_PER_DISTANCE
from ..outputs._files import jsonable, write_csv, write_figure, write_json, write_rows_csv

STUDY_FILE = "study.json"
COMPILE_EVENTS = (
    "/jax/core/compile/jaxpr_trace_duration",
    "/jax/core/compile/jaxpr_to_mlir_module_duration",
    "/jax/core/compile/backend_compile_duration",
)


@dataclass(frozen=True)
class RunConfig:
    """What a reproduce run depends on besides the code (recorded in the report and every JSON; named
    `Settings` before this release: "settings" now means only the options declared on modules).

    spacing: grid spacing cm (docs/model.md §5, 25 = 40 x 40; --quick: 100 = 10 x 10); trials: rollouts
    per success-rate distance bin (thesis: 100; they fill one trial block, so --quick keeps
    them); seed: every random heading, release point and noise draw; lanes: trials advanced side by
    side in the rollout program (`rollouts.run_trials`; no number depends on it): 256 fill the
    program best on the large calls of a full run, 128 waste less on the 99-trial calls of --quick;
    formats: the figure files written, PNG first (the report shows the PNG), then any of pdf, svg.
    """

    quick: bool = False
    seed: int = 0
    spacing: float = SPACING
    trials: int = TRIALS_PER_DISTANCE
    lanes: int = DEFAULT_LANES
    formats: tuple[str, ...] = ("png",)

    @classmethod
    def make(cls, quick: bool = False, seed: int = 0, formats: str | Sequence[str] = "png") -> "RunConfig":
        return cls(
            quick=quick,
            seed=seed,
            spacing=100.0 if quick else SPACING,
            trials=TRIALS_PER_DISTANCE,
            lanes=128 if quick else DEFAULT_LANES,
            formats=figure_formats(formats),
        )


@dataclass(frozen=True)
class Settings(RunConfig):
    """Deprecated (one release): `RunConfig`'s name before this release; building one warns."""

    def __post_init__(self):
        deprecated("delvjax: reproduce.Settings is now reproduce.RunConfig; Settings goes next release")


FORMATS = ("png", "pdf", "svg")


def figure_formats(value: str | Sequence[str]) -> tuple[str, ...]:
    """`--format png,pdf,svg` as a tuple, PNG first and always (the report shows it); `InputError`
    naming --format for anything else."""
    items = [v.strip().lower() for v in (value.split(",") if isinstance(value, str) else value)]
    unknown = [v for v in items if v not in FORMATS]
    if unknown or not items:
        raise InputError("--format", value, f"must be a comma-separated list of {', '.join(FORMATS)}")
    return tuple(dict.fromkeys(["png", *items]))


def config_record(config: RunConfig) -> dict:
    """The run's configuration as recorded in every study.json (its key `settings`, as earlier
    releases wrote it) and the report, with the rollout rules."""
    record = {**asdict(config), "formats": list(config.formats)}  # as JSON reads it back
    return {**record, "rules": {"default": DEFAULT_RULES, "physical": PHYSICAL_RULES}}


def versions() -> dict[str, str]:
    return {
        "delvjax": __version__,
        "jax": jax.__version__,
        "numpy": numpy.__version__,
        "python": platform.python_version(),
        "backend": jax.default_backend(),
    }


# --- compile-time accounting -------------------------------------------------------------

_COMPILE_SECONDS: dict[int, float] = {}  # thread id -> seconds: studies run side by side (`_run.py`)


_ADDING = threading.Lock()


def _add(ident: int, seconds: float) -> None:
    with _ADDING:
        _COMPILE_SECONDS[ident] = _COMPILE_SECONDS.get(ident, 0.0) + seconds


def _on_duration(event: str, duration: float, **_: Any) -> None:
    if event in COMPILE_EVENTS:  # reported in the thread that traces and compiles
        _add(threading.get_ident(), duration)


_LISTENING: list[bool] = []
# A study that asks for a program a study beside it is compiling waits inside jaxlib (C++) until it is
# ready, and no compile event reaches its thread: without this it would count the wait as computation
# and report no compilation. A sampler looks at the study threads every SAMPLE_S seconds: one that sits
# in a call from the project's own code into C while another thread is inside JAX's tracing, lowering or
# compilation is counted as waiting for that compilation.
SAMPLE_S = 0.02
_JAX = str(Path(jax.__file__).parent / "_src")
_OWN = (str(Path(__file__).parents[1]), str(Path(__file__).parents[2] / "studies"))  # delvjax, studies
_MAKING = ("pjit.py", "pxla.py", "compiler.py", "mlir.py", "partial_eval.py")  # JAX making a program
_STUDY_THREADS: set[int] = set()
_SAMPLER_LOCK = threading.Lock()
_REGISTERED: list[bool] = []  # the compile-event listener, registered once per process


def _making_program(frame) -> bool:
    while frame is not None:
        name = frame.f_code.co_filename
        if name.startswith(_JAX) and name.endswith(_MAKING):
            return True
        frame = frame.f_back
    return False


def _sample() -> None:
    """Until no study thread is alive: every SAMPLE_S, the study threads in a call from our code into C
    while another study thread makes a program count as waiting for it. Only study threads' frames are
    read (walking every thread's frames, the test session's included, once crashed the interpreter in
    its garbage collector: a `dict` where a frame's f_back should be), and the sampler ends with the
    studies, so nothing reads frames after a run."""
    while True:
        time.sleep(SAMPLE_S)
        alive = {t.ident for t in threading.enumerate()}
        with _SAMPLER_LOCK:
            _STUDY_THREADS.intersection_update(alive)
            if not _STUDY_THREADS:
                _LISTENING.clear()  # the next study starts a new sampler
                return
            studies = set(_STUDY_THREADS)
        frames = {ident: f for ident, f in sys._current_frames().items() if ident in studies}
        making = {ident for ident, frame in frames.items() if _making_program(frame)}
        if not making:
            continue
        for ident in studies - making:
            frame = frames.get(ident)
            if frame is not None and frame.f_code.co_filename.startswith(_OWN):  # in a C call: a jit call
                _add(ident, SAMPLE_S)


def stop_sampling() -> None:
    """This thread's study is over: the sampler no longer reads its frames (and ends with the last study)."""
    with _SAMPLER_LOCK:
        _STUDY_THREADS.discard(threading.get_ident())


def compile_seconds() -> float:
    """Seconds this thread has spent tracing, lowering and compiling XLA programs so far, and waiting for
    a program another thread was compiling (each study runs in one thread, so a study's compile time is
    not mixed with its neighbour's, and a study that needs the program its neighbour compiles counts
    the wait as compilation; sampled, to SAMPLE_S)."""
    with _SAMPLER_LOCK:
        _STUDY_THREADS.add(threading.get_ident())
        if not _REGISTERED:
            jax.monitoring.register_event_duration_secs_listener(_on_duration)
            _REGISTERED.append(True)
        if not _LISTENING:
            threading.Thread(target=_sample, name="compile-waits", daemon=True).start()
            _LISTENING.append(True)
    return _COMPILE_SECONDS.get(threading.get_ident(), 0.0)


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

    @classmethod
    def from_json(cls, data: Any) -> StudyRecord:
        """The record a study.json holds, its fields' types checked (TypeError naming the field): a record
        that parses but is not one delvjax wrote must make the study run again, not fail the report."""
        if not isinstance(data, dict):
            raise TypeError(f"a study record is a JSON object, not {type(data).__name__}")
        for name, value in data.items():
            kind = RECORD_FIELDS.get(name)
            if kind is None:
                raise TypeError(f"unknown field {name!r}")
            number = isinstance(value, (int, float)) and not isinstance(value, bool)
            if not (number if kind is float else isinstance(value, kind)):
                raise TypeError(f"field {name!r} is {type(value).__name__}, not {kind.__name__}")
        for name, keys in (("figures", FIGURE_KEYS), ("tables", TABLE_KEYS)):
            for item in data.get(name, []):
                if (
                    not isinstance(item, dict)
                    or any(not isinstance(item.get(k), t) for k, t in keys.items())
                    or (name == "tables" and any(not isinstance(r, dict) for r in item["rows"]))
                ):
                    raise TypeError(f"an entry of {name!r} lacks one of {sorted(keys)} or has the wrong type")
        if any(not isinstance(f, str) for f in data.get("files", [])):
            raise TypeError("field 'files' holds a name that is not a string")
        return cls(**data)


RECORD_FIELDS = {
    "name": str,
    "title": str,
    "hash": str,
    "settings": dict,
    "versions": dict,
    "seconds": float,
    "compile_seconds": float,
    "figures": list,
    "tables": list,
    "numbers": dict,
    "files": list,
}
FIGURE_KEYS = {"file": str, "caption": str}
TABLE_KEYS = {"id": str, "title": str, "source": str, "note": str, "file": str, "columns": list, "rows": list}


class StudyContext:
    """The output folder and writers of one study; every write is atomic and recorded."""

    def __init__(
        self, out: Path, record: StudyRecord, config: RunConfig, bar=None, painter: ThreadPoolExecutor | None = None
    ):
        self.out, self.record, self.config, self._bar = out, record, config, bar
        self._painter, self._pending = painter, []  # type: ignore[var-annotated]
        self.steps = 0  # `step` calls so far
        out.mkdir(parents=True, exist_ok=True)

    @property
    def settings(self) -> RunConfig:
        """Deprecated (one release): now `ctx.config`, the run's `RunConfig` ("settings" names the options
        declared on the modules, core/settings.py)."""
        deprecated(
            "delvjax: StudyContext.settings is now StudyContext.config (a RunConfig); .settings goes next release"
        )
        return self.config

    def _file(self, name: str) -> Path:
        self.record.files.append(name)
        return self.out / name

    def figure(self, name: str, fig, caption: str) -> None:
        """Save a figure (`plots.subplots`: outside pyplot's state) as `name` (.png) and in every other
        format of the settings (same name, .pdf / .svg), with the caption the report prints under it."""
        paths = [self._file(str(Path(name).with_suffix(f".{f}"))) for f in self.config.formats]

        def write() -> None:
            for path in paths:
                write_figure(fig, path)

        if self._painter is None:
            write()
        else:  # rendered while this thread waits on the device: figures overlap the computation
            self._pending.append(self._painter.submit(write))
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

    def table(
        self,
        table_id: str,
        title: str,
        rows: list[dict],
        source: str = "",
        note: str = "",
        columns: list[str] | None = None,
    ) -> None:
        """A table of the report (and `<table_id>.csv`): rows of flat dicts, `columns` shown in the report."""
        write_rows_csv(self._file(f"{table_id}.csv"), rows)
        self.record.tables.append(
            {
                "id": table_id,
                "title": title,
                "source": source,
                "note": note,
                "file": f"{table_id}.csv",
                "columns": columns or list(dict.fromkeys(k for r in rows for k in r)),
                "rows": jsonable(rows),
            }
        )

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
        self.record.numbers[key] = jsonable(value)

    def step(self, text: str) -> None:
        """Progress within a long study (advances the inner bar). A study that takes more steps than its
        `STEPS` declares (a bug of the study) widens the bar's total: never "11 of 8"."""
        self.steps += 1
        if self._bar is not None:
            if self._bar.total is not None and self.steps > self._bar.total:
                self._bar.total = self.steps
            self._bar.set_postfix_str(text[:60])
            self._bar.update(1)


# --- content hash and resume ---------------------------------------------------------------
