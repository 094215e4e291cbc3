"""`Progress`: the one object a long call of the Python API reports to (the command line passes its bar)."""

from __future__ import annotations

from collections.abc import Callable


class Progress:
    """What a long call (`vector_map`, `catchment`, `success_rate`, `trajectories`) reports while it runs.

    `start(total)` is called once, when every option is valid and just before the work (`total`: the
    items the call runs, e.g. grid points; None when known only at the first report), then
    `__call__(done, total)` after each chunk of `done` more of `total` items. This base class reports
    nothing; subclass it (the command line's `cli._args.ProgressBar` draws a bar). A plain function
    `f(done, total)` is accepted wherever a `Progress` is (`as_progress`).
    """

    def start(self, total: int | None, phase: str | None = None) -> None:
        """The work begins: `total` items; `phase` says what happens first (e.g. compiling)."""

    def __call__(self, done: int, total: int) -> None:
        """`done` more of `total` items are finished."""


class _Calls(Progress):
    """A plain `f(done, total)` as a `Progress` (`start` reports nothing)."""

    def __init__(self, fn: Callable[[int, int], None]):
        self.fn = fn

    def __call__(self, done: int, total: int) -> None:
        self.fn(done, total)


class OnStart(Progress):
    """A `Progress` that calls `fn()` when the work begins and reports nothing else (what the deprecated
    `announce=` keyword did)."""

    def __init__(self, fn: Callable[[], None]):
        self.fn = fn

    def start(self, total: int | None, phase: str | None = None) -> None:
        self.fn()


def as_progress(progress: Progress | Callable[[int, int], None] | None) -> Progress:
    """`progress` as a `Progress`: itself, a plain `f(done, total)` wrapped, or a silent one for None."""
    if progress is None:
        return Progress()
    if isinstance(progress, Progress):
        return progress
    return _Calls(progress)
