"""A method set: several methods compiled into one program (docs/reproduce.md "One compiled rollout
program").

`MethodSet(methods, index)` is itself a method: a traced `index` picks one of `methods` through
`lax.switch`. Unbatched under `vmap`, the switch runs only the chosen branch, so methods that
share a program cost what they cost alone, and changing `index` (`eqx.tree_at`) reuses the
compiled program.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..sensing import UnitMove
from .base import HomingMethod


class MethodSet(HomingMethod):
    """methods: a tuple of methods; index: which one runs (a traced int32 leaf)."""

    methods: tuple
    index: Array = eqx.field(default=0, converter=lambda i: jnp.asarray(i, jnp.int32))

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        if len(self.methods) == 1:
            return self.methods[0](home, view)

        def branch(method):
            def run(home, view):
                angle, valid = method(home, view)
                return jnp.asarray(angle, jnp.float32), jnp.asarray(valid, bool)

            return run

        return jax.lax.switch(self.index, [branch(m) for m in self.methods], home, view)

    def _flag(self, flags: list) -> bool | Array:
        """A per-method flag: decided when tracing where every method agrees, else by the index."""
        return flags[0] if len(set(flags)) == 1 else jnp.asarray(flags)[self.index]

    def reads_start_view(self) -> bool | Array:
        return self._flag([bool(m.reads_start_view()) for m in self.methods])

    def reads_image(self) -> bool | Array:
        return self._flag([bool(m.reads_image()) for m in self.methods])

    def reads_gray(self, channel: str) -> bool | Array:
        return self._flag([bool(m.reads_gray(channel)) for m in self.methods])

    def reads_panorama(self) -> bool:
        return any(m.reads_panorama() for m in self.methods)

    def check_input(self, n_pix: int) -> None:
        for m in self.methods:
            m.check_input(n_pix)
