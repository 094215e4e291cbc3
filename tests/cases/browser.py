"""The report as a reader's browser shows it: Chromium, headless, through Playwright (issue: a report
that reads well anywhere). `report_defects(path)` loads the page and returns what a reader would
notice: images that did not load, links to anchors that do not exist, markdown left as raw text
(pipes of a table that did not render, outside tables and code). `browser()` is None where no
Playwright or no Chromium can be found (the tests then skip): `pip install playwright` and a Chromium
(`apt-get install chromium`, or `playwright install chromium`)."""

from __future__ import annotations

import os
import shutil
import signal
from contextlib import contextmanager
from pathlib import Path

import pytest

CHROMIUM = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")

FIND_DEFECTS = """() => {
  const images = [...document.images];
  const broken = images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => (i.alt || i.src).slice(0, 80));
  const links = [...document.querySelectorAll('a[href^="#"]')];
  const dangling = links.map(a => a.getAttribute('href'))
    .filter(h => h.length > 1 && !document.getElementById(decodeURIComponent(h.slice(1))));
  const raw = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    if (node.parentElement.closest('table, code, pre, script, style')) continue;
    for (const line of node.textContent.split('\\n')) {  // a table row, a rule, a heading or bold left as text
      if (/^\\s*\\|.*\\|\\s*$/.test(line) || /\\|\\s*:?-{3,}/.test(line) || /^\\s*#{1,6}\\s/.test(line)
          || /\\*\\*\\S/.test(line)) raw.push(line.trim().slice(0, 80));
    }
  }
  return {images: images.length, tables: document.querySelectorAll('table').length, links: links.length,
          broken, dangling, raw, width: document.documentElement.scrollWidth, viewport: window.innerWidth};
}"""


def _executable() -> str | None:
    found = os.environ.get("DELVJAX_CHROMIUM") or next(filter(None, map(shutil.which, CHROMIUM)), None)
    return found


class BrowserHung(Exception):
    """Chromium did not answer in time (it once sat with no renderer for 12 minutes in CI)."""


@contextmanager
def deadline(seconds: int):
    """Raise `BrowserHung` in this (the main) thread after `seconds`: Playwright's sync calls wait in an
    event loop that a signal interrupts, and a page that never gets a renderer waits forever."""

    def on_alarm(signum, frame):
        raise BrowserHung(f"no answer from Chromium in {seconds} s")

    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@contextmanager
def browser():
    """A headless Chromium page factory, or None where none can be started (or it does not answer)."""
    try:
        from playwright.sync_api import Error, sync_playwright
    except ImportError:
        yield None
        return
    with sync_playwright() as p:
        try:
            with deadline(120):
                app = p.chromium.launch(executable_path=_executable(), args=["--no-sandbox"], timeout=60_000)
        except (Error, BrowserHung):
            yield None
            return
        try:
            yield app
        finally:
            try:
                with deadline(30):
                    app.close()
            except BrowserHung:
                app.process.kill() if getattr(app, "process", None) else None


def report_defects(app, path: Path, screenshot: Path | None = None) -> dict:
    """Load `path` in a fresh page (1280 px wide) and return what `FIND_DEFECTS` finds. A Chromium that
    does not answer in 180 s skips the test (the browser, not the report, is then what failed)."""
    try:
        with deadline(180):
            page = app.new_page(viewport={"width": 1280, "height": 900})
            page.goto(Path(path).resolve().as_uri(), wait_until="load")
            found = page.evaluate(FIND_DEFECTS)
            if screenshot is not None:
                page.screenshot(path=str(screenshot), full_page=False)
            page.close()
    except BrowserHung as exc:
        pytest.skip(str(exc))
    return found
