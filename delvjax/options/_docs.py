"""The pages made from the declarations: docs/options.md's table of every option (the settings declared
on the modules) and docs/api.md's entries of the registered methods. The site makes them when it is
built (`docs/_ext/generated.py`, a mkdocs hook), so a new method or setting needs no edit of a page;
`python -m delvjax.options` prints the options, `python -m delvjax.options api` the method entries."""

from __future__ import annotations

from ..core.sensor import Noise, Sensor
from ._registry import public_classes
from ._schema import _shown_default, all_options, extractor_options

OPTIONS_MARK = (
    "<!-- the table of options: made from the declarations when the site is built (docs/_ext/generated.py) -->"
)
HEADER = """| option | flag | what | unit | check | default | module |
|---|---|---|---|---|---|---|
"""


def options_markdown() -> str:
    """The table of every option (flag, help, unit, check, default, owner), in declaration order."""
    rows = []
    for opt in {**all_options(), **extractor_options()}.values():  # extractor: options of --images
        for owners, d in opt.variants():  # one row per distinct declaration (n_rho: Warping's, Warping2D's)
            s = d.setting
            check = s.check + (f" <= {s.limit}" if s.limit else "") + (f": {', '.join(s.choices)}" if s.choices else "")
            owner = "Sensor" if owners[0] in (Sensor, Noise) else ", ".join(t.__name__ for t in owners)
            owner += f".{'noise.' if owners[0] is Noise else ''}{d.field}"
            rows.append(
                f"| `{opt.name}` | `{opt.flag}` | {s.help} | {s.unit or '-'} | {check} | {_shown_default(d)} "
                f"| `{owner}` |"
            )
    return HEADER + "\n".join(rows) + "\n"


API_START = "<!-- the registered methods: made when the site is built (options.public_classes) -->"
API_END = "<!-- end of the registered methods -->"


def api_methods_markdown() -> str:
    """docs/api.md's entries of the public method classes (the registry's, in its order), from
    `API_START` to `API_END`: a new method's registry line documents it."""
    entries = [
        f"::: {cls.__module__}.{name}\n    options:\n      members: false\n" for name, cls in public_classes().items()
    ]
    return "\n".join([API_START + "\n", *entries, API_END])


def with_api_methods(page: str) -> str:
    """`page` (docs/api.md) with its block of registered methods made from the registry."""
    start, end = page.index(API_START), page.index(API_END) + len(API_END)
    return page[:start] + api_methods_markdown() + page[end:]


def with_options(page: str) -> str:
    """`page` (docs/options.md) with the table of options in place of `OPTIONS_MARK`."""
    if OPTIONS_MARK not in page:
        raise ValueError(f"the page has no {OPTIONS_MARK!r}")
    return page.replace(OPTIONS_MARK, options_markdown().rstrip("\n"))


def generated_page(name: str, page: str) -> str:
    """The site's page `name` (a path under docs/) with what is made from the declarations filled in."""
    if name == "options.md":
        return with_options(page)
    if name == "api.md":
        return with_api_methods(page)
    return page
