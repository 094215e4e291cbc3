"""docs/options.md, made from the settings declared on the modules (`python -m delvjax.options`)."""

from __future__ import annotations

from ..core.sensor import Noise, Sensor
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
