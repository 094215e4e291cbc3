"""A griffe extension for the API reference (mkdocs.yml): a default written as a constant's name
(`spacing: float = SPACING`) is shown as its value (`25.0`), so that a signature says what a call does
without a search for the constant (issue 53 point 8). Only names and attribute chains are replaced, and
only by a short value of a plain type; the module is imported to read it (delvjax imports cheaply)."""

from __future__ import annotations

import ast
import importlib
from typing import Any

import griffe

PLAIN = (bool, int, float, str, type(None))
MAX_CHARS = 80  # a longer value keeps its name


def plain(value: Any) -> bool:
    """A value whose repr reads as Python: a number, string, bool, None, or a tuple / list of them."""
    if isinstance(value, (tuple, list)):
        return all(plain(v) for v in value)
    return isinstance(value, PLAIN)


def evaluated(expr: Any, module: str) -> str | None:
    """The repr of `expr` (a name or attribute chain, as written in `module`) where it is a short plain
    value, else None (the expression is kept)."""
    text = str(expr)
    try:
        tree = ast.parse(text, mode="eval").body
    except SyntaxError:
        return None
    node = tree
    while isinstance(node, ast.Attribute):
        node = node.value
    if not isinstance(node, ast.Name) or node is tree and text in ("None", "True", "False"):
        return None
    try:
        value = eval(compile(ast.Expression(tree), "<default>", "eval"), vars(importlib.import_module(module)))  # noqa: S307
    except Exception:  # noqa: BLE001 - a name the module does not bind at run time: keep it as written
        return None
    shown = repr(value)
    return shown if plain(value) and len(shown) <= MAX_CHARS else None


class EvaluatedDefaults(griffe.Extension):
    """Replaces constant names in defaults (parameters, dataclass fields) by their values."""

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        self._walk(pkg)

    def _walk(self, obj: griffe.Object) -> None:
        for member in list(obj.members.values()):
            if member.is_alias:
                continue
            if member.is_function:
                for param in member.parameters:
                    if param.default is not None:
                        param.default = evaluated(param.default, member.module.path) or param.default
            elif member.is_attribute and member.value is not None and member.parent.is_class:
                member.value = evaluated(member.value, member.module.path) or member.value
            if member.is_module or member.is_class:
                self._walk(member)
