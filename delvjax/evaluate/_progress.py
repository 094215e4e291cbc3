"""`Progress`: the one object a long call of the Python API reports to (the command line passes its bar)."""

from __future__ import annotations

from collections.abc import Callable

from ..core.deprecation import deprecated


class Progress:
    """What a long call (`vector_map`, `catchment`, `success_rate`, `trajectories`) reports while it runs.

    `start(total)` is called once, when every option is valid and just before the work (`total`: the
    items the call runs, e.g. grid points; None when known only at the first report), then
    `__call__(done, total)` after each chunk of `done` more of `total` items, and `phase(text)` where what
    runs changes ("compiling program 2 of 3"). This base class reports nothing; subclass it (the command
    line's `cli._args.ProgressBar` draws a bar). A plain function `f(done, total)` is accepted wherever a
    `Progress` is (`as_progress`).
    """

    def start(self, total: int | None, phase: str | None = None) -> None:
        """The work begins: `total` items; `phase` says what happens first (e.g. compiling)."""

    def phase(self, text: str) -> None:
        """What runs now (e.g. "compiling program 2 of 3")."""

    def __call__(self, done: int, total: int) -> None:
        """`done` more of `total` items are finished."""


class _Calls(Progress):
    """A plain `f(done, total)` as a `Progress` (`start` reports nothing)."""

    def __init__(self, fn: Callable[[int, int], None]):
        self.fn = fn

    def __call__(self, done: int, total: int) -> None:
        self.fn(done, total)


class _Callbacks(Progress):
    """A `Progress` with the separate callbacks of earlier releases (deprecated): `announce()` when the
    work begins and `phase(text)`, beside `progress` itself."""

    def __init__(self, progress: Progress, announce: Callable[[], None] | None, phase: Callable[[str], None] | None):
        self.progress, self.announce, self.on_phase = progress, announce, phase

    def start(self, total: int | None, phase: str | None = None) -> None:
        if self.announce is not None:
            self.announce()
        self.progress.start(total, phase)

    def phase(self, text: str) -> None:
        (self.progress.phase if self.on_phase is None else self.on_phase)(text)

    def __call__(self, done: int, total: int) -> None:
        self.progress(done, total)


class OnStart(_Callbacks):
    """A `Progress` that calls `fn()` when the work begins and reports nothing else (what the deprecated
    `announce=` keyword did)."""

    def __init__(self, fn: Callable[[], None]):
        super().__init__(Progress(), fn, None)


def with_callbacks(progress: Progress | Callable[[int, int], None] | None, legacy: dict, call: str) -> Progress:
    """`progress` as a `Progress` (`as_progress`) with the deprecated `announce=` and `phase=` callbacks
    of `legacy` (popped from it; a `DeprecationWarning` names them and `call`, the function given them)."""
    old = {k: legacy.pop(k) for k in ("announce", "phase") if k in legacy}
    old = {k: v for k, v in old.items() if v is not None}
    report = as_progress(progress)
    if not old:
        return report
    deprecated(
        f"delvjax: {call}(): {' and '.join(k + '=' for k in old)} {'are' if len(old) > 1 else 'is'} deprecated "
        "and will be removed in the next release: pass progress=, a delvjax.evaluate.Progress (its start(total), "
        "phase(text) and (done, total) calls)"
    )
    return _Callbacks(report, old.get("announce"), old.get("phase"))


def as_progress(progress: Progress | Callable[[int, int], None] | None) -> Progress:
    """`progress` as a `Progress`: itself, a plain `f(done, total)` wrapped, or a silent one for None."""
    if progress is None:
        return Progress()
    if isinstance(progress, Progress):
        return progress
    return _Calls(progress)
