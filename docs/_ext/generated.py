"""mkdocs hook (mkdocs.yml `hooks`): the pages made from the declarations when the site is built,
docs/options.md's table of options and docs/api.md's entries of the registered methods
(delvjax/options/_docs.py `generated_page`), so a new method or setting edits no page."""

from delvjax.options._docs import generated_page


def on_page_markdown(markdown, page, config, files):
    return generated_page(page.file.src_uri, markdown)
