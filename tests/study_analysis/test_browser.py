"""The study report in a real browser (headless Chromium through Playwright): no console errors, the profiler's
in-page surrogate values follow the sliders exactly as the Python surrogates do, usable at 800 px, prints."""

from __future__ import annotations

import numpy as np
import pytest

from tests.browser import MARKS, open_page
from tests.study_analysis.report_fixture import small_report, write_small_report

pytestmark = MARKS


def _open(browser, path, width):
    return open_page(browser, path, width, ready='#profiler[data-ready="1"]')


def test_profiler_follows_the_sliders_as_the_surrogates_do(browser, tmp_path):
    analysis, _ = small_report()
    page, problems = _open(browser, write_small_report(tmp_path), 1200)
    names = page.eval_on_selector_all("td.pred", "els => els.map(e => e.dataset.response)")
    assert names and set(names) <= set(analysis.surrogates)
    n_var = len(analysis.view.variables)
    rng = np.random.default_rng(4)
    for _step in range(3):
        i = int(rng.integers(n_var))
        v = analysis.view.variables[i]
        target = v.lower + (v.upper - v.lower) * float(rng.random())
        page.eval_on_selector(
            f"#pslider-{i}", "(el, t) => { el.value = t; el.dispatchEvent(new Event('input')); }", target
        )
        x = np.array(page.eval_on_selector_all("input[type=range]", "els => els.map(e => parseFloat(e.value))"))
        assert x[i] == pytest.approx(target, rel=1e-12)
        shown = page.eval_on_selector_all("td.pred", "els => els.map(e => parseFloat(e.dataset.value))")
        expected = [float(analysis.surrogates[r].predict(x[None, :])[0]) for r in names]
        # 1e-9, or 1e-7 for a near-interpolating Gaussian process (weights α of ±3·10⁴ summed to 10⁵ in another order)
        rtol = np.array([1e-7 if analysis.surrogates[r].kept.family == "Gaussian process" else 1e-9 for r in names])
        assert np.all(np.abs(np.array(shown) - expected) <= rtol * np.abs(expected) + 1e-12), (shown, expected)
        # the slope indicator of the first response against the moved variable: a central difference
        slope = float(page.eval_on_selector(f"#presp-0 ~ td:nth-of-type({i + 2}) svg", "s => s.dataset.slope"))
        h = 1e-4 * (v.upper - v.lower)
        a, b = x.copy(), x.copy()
        a[i] -= h
        b[i] += h
        s = analysis.surrogates[names[0]]
        expected_slope = (s.predict(b[None, :])[0] - s.predict(a[None, :])[0]) / (2 * h)
        assert slope == pytest.approx(expected_slope, rel=1e-6, abs=1e-12 * abs(s.predict(x[None, :])[0]) / h)
    assert problems == []
    page.close()


def test_usable_at_800_px_and_prints(browser, tmp_path):
    page, problems = _open(browser, write_small_report(tmp_path), 800)
    assert page.evaluate("document.documentElement.scrollWidth") <= 800
    page.evaluate("window.dispatchEvent(new Event('beforeprint'))")
    assert page.evaluate("[...document.querySelectorAll('details')].every(d => d.open)")
    page.emulate_media(media="print")
    pdf = page.pdf(path=str(tmp_path / "report.pdf"))
    assert pdf[:4] == b"%PDF" and len(pdf) > 10_000
    assert problems == []
    page.close()
