"""`python -m delvjax.options`: print docs/options.md; `python -m delvjax.options api`: make
docs/api.md's entries of the registered methods again (in place)."""

import sys
from pathlib import Path

from ._docs import options_markdown, with_api_methods

if sys.argv[1:] == ["api"]:
    page = Path("docs/api.md")
    page.write_text(with_api_methods(page.read_text()))
else:
    print(options_markdown(), end="")
