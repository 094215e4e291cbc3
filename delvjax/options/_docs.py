"""docs/options.md, made from the settings declared on the modules (`python -m delvjax.options`), and
docs/api.md's entries of the registered methods (`python -m delvjax.options api`)."""

from __future__ import annotations

from ..core.sensor import Noise, Sensor
from ._registry import public_classes
from ._schema import all_options, extractor_options

HEADER = """# Options

Made from the settings declared on the modules (`delvjax/core/settings.py`; docs/architecture.md
"Settings") by `python -m delvjax.options > docs/options.md`; a test checks it is current. Each
option is a keyword of the Python API (`delvjax.vector_map(..., levels=3)`), a flag of the command
line (`--levels 3`) and an axis of a sweep file (`levels = [2, 3, 4]`).

| option | flag | what | unit | check | default | module |
|---|---|---|---|---|---|---|
"""


def options_markdown() -> str:
    rows = []
    for opt in {**all_options(), **extractor_options()}.values():  # extractor: options of --images
        s = opt.setting
        check = s.check + (f" <= {s.limit}" if s.limit else "") + (f": {', '.join(s.choices)}" if s.choices else "")
        owner = "Sensor" if opt.owners[0] in (Sensor, Noise) else ", ".join(t.__name__ for t in opt.owners)
        owner += f".{'noise.' if opt.owners[0] is Noise else ''}{opt.field}"
        rows.append(
            f"| `{opt.name}` | `{opt.flag}` | {s.help} | {s.unit or '-'} | {check} | {opt.shown_default} | `{owner}` |"
        )
    return HEADER + "\n".join(rows) + "\n"


API_START = "<!-- the registered methods: made by `python -m delvjax.options api` (options.public_classes) -->"
API_END = "<!-- end of the registered methods -->"


def api_methods_markdown() -> str:
    """docs/api.md's entries of the public method classes (the registry's, in its order), from
    `API_START` to `API_END`: a new method's registry line documents it."""
    entries = [
        f"::: {cls.__module__}.{name}\n    options:\n      members: false\n" for name, cls in public_classes().items()
    ]
    return "\n".join([API_START + "\n", *entries, API_END])


def with_api_methods(page: str) -> str:
    """`page` (docs/api.md) with its block of registered methods made again."""
    start, end = page.index(API_START), page.index(API_END) + len(API_END)
    return page[:start] + api_methods_markdown() + page[end:]
