"""Headless Debian Chromium through Playwright for the report tests: the launch fixture, the skip marks, and a page
that records console errors and warnings, page errors and any request leaving the machine."""

from __future__ import annotations

import os

import pytest

CHROMIUM = "/usr/bin/chromium"
try:
    from playwright.sync_api import sync_playwright
except ImportError:  # pragma: no cover - depends on the machine
    sync_playwright = None

MARKS = [
    pytest.mark.skipif(
        sync_playwright is None, reason="Playwright for Python is not installed (pip install playwright)"
    ),
    pytest.mark.skipif(not os.path.exists(CHROMIUM), reason=f"no browser at {CHROMIUM} (apt-get install chromium)"),
]
ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


@pytest.fixture(scope="module")
def browser():
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


def open_page(browser_or_context, path, width: int, ready: str | None = None):
    """(page, problems): ``path`` opened at ``width`` px (a browser) or at its context's viewport (a context)."""
    if hasattr(browser_or_context, "contexts"):
        page = browser_or_context.new_page(viewport={"width": width, "height": 900})
    else:
        page = browser_or_context.new_page()
    problems = []
    page.on(
        "console", lambda m: problems.append(f"console {m.type}: {m.text}") if m.type in ("error", "warning") else None
    )
    page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    page.on("request", lambda r: problems.append(f"request {r.url}") if not r.url.startswith("file:") else None)
    page.goto(path.as_uri())
    if ready:
        page.wait_for_selector(ready)
    return page, problems


def printed_pages(path) -> list[str]:
    """The text of each page of a PDF the browser printed (PDFium, through pypdfium2)."""
    import pypdfium2  # deferred: a test dependency only the printing tests read

    document = pypdfium2.PdfDocument(str(path))
    try:
        return [page.get_textpage().get_text_range() for page in document]
    finally:
        document.close()
