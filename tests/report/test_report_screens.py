"""The report on small and large screens, by keyboard and on paper (headless Debian Chromium through Playwright):
the summary with the first failing rule and its reason on the first screen at 390, 800 and 1400 px; table headers
that stay in view; the status sort by severity with its direction shown; a skip link and visible focus; a shape
beside each status colour; figures with an accessible name; Part 25 citations only linked to the eCFR; the printed
summary's header not blank; big tables stored compressed and drawn when shown.

References: WCAG 2.2 success criteria 1.4.1 (use of colour), 2.4.1 (bypass blocks), 2.4.7 (focus visible), 1.1.1
(non-text content: a name for each figure), 1.4.11 (non-text contrast ≥ 3:1); WAI-ARIA 1.2 aria-sort values."""

from __future__ import annotations

import re

import pytest

from tests.browser import MARKS, open_page, printed_pages
from tests.report.report_run import results

# skipped with the reason when Playwright or Chromium is missing; on one pytest-xdist worker with the small check
pytestmark = [*MARKS, pytest.mark.xdist_group("small-check")]


@pytest.fixture(scope="module")
def chromium(browser):
    return browser


def _first_failing_row_visible(page) -> dict:
    return page.evaluate("""() => {
        const row = document.querySelector('#triage tbody tr[data-status="fails"]');
        const reason = row.querySelector('td.reason').getBoundingClientRect();
        const link = row.querySelector('a').getBoundingClientRect();
        return {top: link.top, bottom: reason.bottom, left: reason.left, right: link.right,
                width: innerWidth, height: innerHeight, scroll: document.documentElement.scrollWidth};
    }""")


@pytest.mark.parametrize("width", [390, 800, 1400])
def test_first_screen_shows_a_failing_rule_and_its_reason(chromium, small_check, width):
    assert "fails" in {r["status"] for r in results(small_check[0])["rules"]}
    page, problems = open_page(chromium, small_check[0] / "index.html", width)
    page.set_viewport_size({"width": width, "height": 844 if width == 390 else 900})
    box = _first_failing_row_visible(page)
    assert box["top"] >= 0 and box["bottom"] <= box["height"], box  # on the first screen, no scrolling
    assert box["left"] < box["width"] and box["right"] <= box["width"], box
    assert box["scroll"] <= width  # no horizontal scroll of the page
    assert problems == []
    page.close()


@pytest.mark.parametrize("width", [390, 800])
def test_summary_comes_before_the_contents_on_small_screens(chromium, small_check, width):
    page, _ = open_page(chromium, small_check[0] / "index.html", width)
    summary = page.eval_on_selector("#summary", "e => e.getBoundingClientRect().top")
    toc = page.eval_on_selector("#toc", "e => e.getBoundingClientRect().top")
    assert summary < toc
    page.close()


def test_status_sorts_by_severity_and_shows_its_direction(chromium, small_check):
    page, problems = open_page(chromium, small_check[0] / "index.html", 1400)
    rank = {"fails": 0, "not_evaluated": 1, "complies_partial": 2, "complies": 3}
    header = 'th:has(button[data-key="rank"])'
    statuses = lambda: page.eval_on_selector_all("#triage tbody tr", "els => els.map(e => e.dataset.status)")  # noqa: E731
    assert page.get_attribute('th:has(button[data-key="order"])', "aria-sort") == "ascending"
    page.click(f"{header} button")
    assert page.get_attribute(header, "aria-sort") == "ascending"
    assert page.get_attribute('th:has(button[data-key="order"])', "aria-sort") is None
    first = [rank[s] for s in statuses()]
    assert first == sorted(first) and first[0] == 0  # fails first: by severity, not alphabetically
    arrow = page.evaluate("getComputedStyle(document.querySelector('th[aria-sort] button'), '::after').content")
    assert "▲" in arrow
    page.click(f"{header} button")
    assert page.get_attribute(header, "aria-sort") == "descending"
    second = [rank[s] for s in statuses()]
    assert second == sorted(second, reverse=True)
    assert "▼" in page.evaluate("getComputedStyle(document.querySelector('th[aria-sort] button'), '::after').content")
    assert problems == []
    page.close()


def test_keyboard_reaches_the_skip_link_and_the_sort_buttons_with_a_visible_focus(chromium, small_check):
    page, problems = open_page(chromium, small_check[0] / "index.html", 1400)
    page.keyboard.press("Tab")
    first = page.evaluate("[document.activeElement.textContent, document.activeElement.getAttribute('href')]")
    assert first == ["Skip to the summary", "#summary"]
    assert page.evaluate("document.activeElement.getBoundingClientRect().left") >= 0  # shown when focused
    page.keyboard.press("Enter")
    assert page.evaluate("location.hash") == "#summary"
    for _ in range(60):
        page.keyboard.press("Tab")
        if page.evaluate("document.activeElement.matches('#triage th button')"):
            break
    else:
        pytest.fail("no sort button reached by Tab")
    style = page.evaluate(
        "(() => { const s = getComputedStyle(document.activeElement); "
        "return [s.outlineStyle, parseFloat(s.outlineWidth)]; })()"
    )
    assert style[0] != "none" and style[1] >= 2
    page.keyboard.press("Enter")
    assert page.evaluate("document.activeElement.parentElement.getAttribute('aria-sort')") in (
        "ascending",
        "descending",
    )
    assert problems == []
    page.close()


def _luminance(rgb):
    def channel(c):
        c /= 255
        return c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4

    r, g, b = (channel(int(v)) for v in re.findall(r"\d+", rgb)[:3])
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def test_status_marks_are_shapes_with_contrast_and_figures_are_named(chromium, small_check):
    page, problems = open_page(chromium, small_check[0] / "index.html", 1400)
    marks = page.eval_on_selector_all(
        "#toc .status-mark", "els => els.map(e => [e.className, e.textContent, getComputedStyle(e).color])"
    )
    by_status = {}
    for cls, text, colour in marks:
        status = cls.split("mark-")[1]
        by_status.setdefault(status, set()).add(text)
        contrast = (1.05) / (_luminance(colour) + 0.05)  # against the white page
        assert contrast >= 3.0, (status, colour, contrast)
    shapes = {s: next(iter(t)) for s, t in by_status.items()}
    assert all(len(t) == 1 for t in by_status.values()) and len(set(shapes.values())) == len(shapes)
    assert {"fails", "complies"} <= set(shapes) or {"fails", "complies_partial"} <= set(shapes)
    figures = page.eval_on_selector_all(
        ".evidence svg",
        "els => els.map(e => [e.getAttribute('role'), "
        "e.getAttribute('aria-label'), e.querySelector('title') && "
        "e.querySelector('title').textContent])",
    )
    assert figures and all(role == "img" and label and title == label for role, label, title in figures)
    assert problems == []
    page.close()


def test_table_headers_stay_in_view_when_a_long_table_scrolls(chromium, small_check):
    page, problems = open_page(chromium, small_check[0] / "index.html", 1400)
    page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
    page.wait_for_function("document.querySelectorAll('div.packed').length === 0")
    box = page.evaluate("""() => {
        const wraps = [...document.querySelectorAll('section.rule .table-wrap')]
            .filter(w => w.scrollHeight > w.clientHeight + 50);
        if (!wraps.length) { return null; }
        const w = wraps[0]; w.scrollIntoView(); w.scrollTop = w.scrollHeight / 2;
        const th = w.querySelector('thead th').getBoundingClientRect(), top = w.getBoundingClientRect().top;
        return [th.top - top, w.scrollTop];
    }""")
    assert box is not None, "no findings table taller than its box in this report"
    offset, scrolled = box
    assert scrolled > 0 and abs(offset) <= 2  # the header row sits at the top of its scrolled box
    assert problems == []
    page.close()


def test_printed_summary_header_is_not_blank(chromium, small_check, tmp_path):
    """The summary table's header repeated on the next printed page names its columns (Chromium does not repeat a
    header's buttons: printed, the header shows their text instead)."""
    page, problems = open_page(chromium, small_check[0] / "index.html", 1400)
    page.evaluate("""() => { const body = document.querySelector('#triage tbody'), rows = [...body.rows];
                             for (let k = 0; k < 20; k++) {
                               rows.forEach(r => body.appendChild(r.cloneNode(true)));
                             } }""")
    page.emulate_media(media="print")
    headers = page.eval_on_selector_all("#triage thead th", "els => els.map(e => e.innerText.trim())")
    assert headers and all(headers), headers
    assert page.eval_on_selector("#triage thead th", "e => getComputedStyle(e).position") == "static"
    assert page.eval_on_selector(".skip", "e => getComputedStyle(e).display") == "none"
    pdf = tmp_path / "summary.pdf"
    page.pdf(path=str(pdf), format="A4", print_background=True)
    second = printed_pages(pdf)[1]
    top = second[: second.index("§")]  # the repeated header, before the first rule row of the page
    assert "Rule" in top and "Status" in top and "Title" in top, top
    assert problems == []
    page.close()
