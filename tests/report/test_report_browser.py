"""The compliance report in a real browser (headless Debian Chromium through Playwright): no console errors, every
in-page anchor resolves to one element, no horizontal scroll at 800 px, the summary filters work, and the printed
PDF holds every finding (collapsed sections open on print)."""

from __future__ import annotations

import re
import unicodedata
from collections import Counter

import pytest

from tests.browser import MARKS, open_page, printed_pages
from tests.report.report_run import results

# skipped with the reason when Playwright or Chromium is missing; on one pytest-xdist worker with the small check
pytestmark = [*MARKS, pytest.mark.xdist_group("small-check")]


@pytest.fixture(scope="module")
def chromium(browser):
    return browser


def _open(browser, path, width):
    return open_page(browser, path, width)


def test_clean_page_and_every_anchor_resolves(chromium, small_check):
    page, problems = _open(chromium, small_check[0] / "index.html", 1280)
    # the report's own ids are unique (the ids inside matplotlib's SVG are the evidence drawing's: evidence
    # as data makes them deterministic and unique)
    ids = page.eval_on_selector_all("[id]", "els => els.filter(e => !e.closest('svg')).map(e => e.id)")
    assert [i for i, n in Counter(ids).items() if n > 1] == []
    targets = page.eval_on_selector_all('a[href^="#"]', "els => els.map(e => e.getAttribute('href').slice(1))")
    assert targets and [t for t in set(targets) if t not in set(ids)] == []
    external = page.eval_on_selector_all('a[href^="http"]', "els => els.map(e => e.href)")
    assert external and all(
        u.startswith("https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/section-25.")
        for u in external
    )
    # §25.121(b) links to its own section, not to (a); a reference to §25.121 itself goes to the eCFR page
    assert page.eval_on_selector_all('a[href="#r25-121-b"]', "els => els.length") >= 2
    # failing and unevaluated rules are expanded, those that comply collapsed
    opened = dict(
        page.eval_on_selector_all("section.rule", "els => els.map(s => [s.id, s.querySelector('details').open])")
    )
    data = results(small_check[0])
    for r in data["rules"]:
        slug = "r" + re.sub(r"[^0-9a-z]+", "-", r["id"]).strip("-")
        assert opened[slug] == (r["status"] in ("fails", "not_evaluated")), r["id"]
    # following a link to a collapsed rule opens it
    page.click('#triage a[href="#r25-335-a"]')
    assert page.eval_on_selector("#r25-335-a details", "d => d.open")
    assert problems == []
    page.close()


def test_summary_order_and_filters(chromium, small_check):
    page, problems = _open(chromium, small_check[0] / "index.html", 1280)
    statuses = page.eval_on_selector_all("#triage tbody tr", "els => els.map(e => e.dataset.status)")
    rank = {"fails": 0, "not_evaluated": 1, "complies_partial": 2, "complies": 3}
    assert [rank[s] for s in statuses] == sorted(rank[s] for s in statuses)
    page.uncheck('#filters input[value="complies"]')
    shown = page.eval_on_selector_all("#triage tbody tr:not([hidden])", "els => els.map(e => e.dataset.status)")
    assert "complies" not in shown and len(shown) == len(statuses) - statuses.count("complies")
    page.check('#filters input[value="complies"]')
    page.select_option("#filter-subpart", "C")
    shown = page.eval_on_selector_all(
        "#triage tbody tr:not([hidden]) td:first-child", "els => els.map(e => e.textContent)"
    )
    assert shown and all(s.startswith("§25.3") for s in shown)
    page.select_option("#filter-subpart", "")
    page.fill("#filter-text", "dynamic stability")
    shown = page.eval_on_selector_all(
        "#triage tbody tr:not([hidden]) td:first-child", "els => els.map(e => e.textContent)"
    )
    assert shown == ["§25.181"]
    # not-evaluated rules show their reason, not a margin
    reasons = page.eval_on_selector_all(
        '#triage tr[data-status="not_evaluated"]',
        "els => els.map(e => [e.cells[5].textContent, e.cells[7].textContent])",
    )
    assert reasons and all(m == "—" and r.startswith("not evaluated: ") for m, r in reasons)
    assert problems == []
    page.close()


def test_no_horizontal_scroll_at_800_px(chromium, small_check):
    page, problems = _open(chromium, small_check[0] / "index.html", 800)
    assert page.evaluate("document.documentElement.scrollWidth") <= 800
    page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
    assert page.evaluate("document.documentElement.scrollWidth") <= 800  # wide tables scroll in their own box
    assert problems == []
    page.close()


@pytest.mark.parametrize("script", [True, False], ids=["beforeprint-handler", "print-css-alone"])
def test_printed_pdf_contains_every_finding(chromium, small_check, tmp_path, script):
    """Both the beforeprint handler and the print stylesheet alone (a reader with scripts off) print every finding
    (without either, the collapsed findings tables print as bare headings: about a quarter of the findings here).
    With scripts off, a table stored compressed (the report's size budget) prints as its note, which names its rows
    and results.json; every other finding is printed."""
    context = chromium.new_context(java_script_enabled=script, viewport={"width": 1280, "height": 900})
    page, problems = _open(context, small_check[0] / "index.html", 1280)
    assert page.eval_on_selector_all("details:not([open])", "els => els.length") > 0  # some are collapsed on screen
    packed = page.eval_on_selector_all("section.rule:has(div.packed)", "els => els.map(e => e.id)")
    if script:
        page.wait_for_function("document.querySelectorAll('div.packed').length === 0")
        packed = []
    page.emulate_media(media="print")
    pdf = tmp_path / "report.pdf"
    page.pdf(path=str(pdf), format="A4", print_background=True)
    printed = "".join(printed_pages(pdf))
    # NFKC: the PDF's typographic ligatures (ﬁ) read as their letters
    text = re.sub(r"\s+", "", unicodedata.normalize("NFKC", printed))
    data = results(small_check[0])
    slug = lambda rid: "r" + re.sub(r"[^0-9a-z]+", "-", rid).strip("-")  # noqa: E731
    wanted = Counter(
        re.sub(r"\s+", "", f["check"]) for r in data["rules"] if slug(r["id"]) not in packed for f in r["findings"]
    )
    missing = {c: n for c, n in wanted.items() if text.count(c) < n}
    assert missing == {}
    assert text.count("storedcompressedinthisfile") >= len(packed)
    assert "page1of" in text.replace("Page", "page")  # numbered pages
    assert problems == []
    context.close()
