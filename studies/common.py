"""Helpers shared by the study modules: output folder, batched-result slicing, progress."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import jax

from delvjax.cache import enable_compilation_cache
from delvjax.io import write_json, write_rows_csv


class Study:
    """An output folder plus timing/progress lines on stderr and a JSON summary."""

    def __init__(self, out: str | Path, name: str):
        self.out = Path(out)
        self.out.mkdir(parents=True, exist_ok=True)
        self.name = name
        enable_compilation_cache()
        self.summary: dict = {}
        self.t0 = time.perf_counter()

    def step(self, msg: str) -> None:
        print(f"[{self.name} {time.perf_counter() - self.t0:6.1f}s] {msg}", file=sys.stderr, flush=True)

    def path(self, name: str) -> Path:
        return self.out / name

    def rows(self, name: str, rows: list[dict]) -> None:
        write_rows_csv(self.path(name), rows)

    def finish(self) -> None:
        self.summary["seconds"] = time.perf_counter() - self.t0
        write_json(self.path(f"{self.name}.json"), self.summary)
        self.step(f"done: {self.out}/{self.name}.json")


def take(tree, i: int):
    """Element i of a batched pytree (a sweep's result)."""
    return jax.tree.map(lambda a: a[i], tree)
