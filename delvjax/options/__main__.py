"""`python -m delvjax.options`: print the table of options (docs/options.md's, made when the site is
built); `python -m delvjax.options api`: print docs/api.md's entries of the registered methods."""

import sys

from ._docs import api_methods_markdown, options_markdown

print(api_methods_markdown() if sys.argv[1:] == ["api"] else options_markdown().rstrip("\n"))
