"""`python -m delvjax.options`: print docs/options.md."""

from ._docs import options_markdown

print(options_markdown(), end="")
