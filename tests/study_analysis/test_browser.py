"""The study report in a real browser (headless Chromium through Playwright): no console errors, the profiler's
in-page surrogate values follow the sliders exactly as the Python surrogates do, usable at 800 px, prints."""

from __future__ import annotations

import numpy as np
import pytest

from tests.browser import MARKS, open_page
from tests.study_analysis.report_fixture import small_report, write_small_report

pytestmark = [*MARKS, pytest.mark.xdist_group("study-report")]


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
    # the classifier of possible designs reads the point as the analysis does
    impossible = page.eval_on_selector("#pvalid", "p => p.dataset.impossible") == "1"
    assert impossible == (not bool(analysis.validity.valid(x[None, :])[0]))
    assert "aircraft" in page.inner_text("#pvalid") or "planform" in page.inner_text("#pvalid")
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


def test_profiler_reads_the_classifier_of_possible_designs(browser, tmp_path):
    """With impossible designs among the cases, the page evaluates the exported classifier at the sliders' point
    as certkit.study.analysis.validity.validity_log_odds does: the same verdict and P(impossible)."""
    import json
    from pathlib import Path

    from certkit.study.analysis.validity import validity_log_odds

    doc = {
        "lo": [0.0, 10.0],
        "hi": [1.0, 30.0],
        "terms": [[[0, 1]], [[1, 1]], [[0, 2]], [[0, 1], [1, 1]]],
        "mean": [0.1, -0.2, 0.3, 0.0],
        "scale": [0.6, 0.5, 0.4, 0.3],
        "coef": [2.0, -1.5, 0.7, 1.1],
        "intercept": -0.4,
    }
    flat = {"response": "objective.x", "log": False, "lo": [0.0, 10.0], "hi": [1.0, 30.0], "kind": "polynomial"}
    data = {
        "variables": [
            {"path": p, "label": p, "lower": lo, "upper": hi, "from": lo, "to": hi, "value": v, "unit": "", "factor": 1}
            for p, lo, hi, v in (("a", 0.0, 1.0, 0.5), ("b", 10.0, 30.0, 20.0))
        ],
        "responses": [
            {
                "name": "objective.x",
                "model": {**flat, "intercept": 1.0, "coef": [], "terms": []},
                "min": None,
                "max": None,
                "flagged": False,
                "label": "polynomial",
                "title": "x",
                "unit": "",
                "factor": 1,
            }
        ],
        "validity": doc,
    }
    js = (Path(__file__).resolve().parents[2] / "certkit/report/templates/profiler.js").read_text()
    page_path = tmp_path / "p.html"
    page_path.write_text(
        '<!doctype html><html><body><div id="profiler"></div><script type="application/json" id="profiler-data">'
        + json.dumps(data)
        + "</script><script>"
        + js
        + "</script></body></html>"
    )
    page, problems = _open(browser, page_path, 900)
    seen = set()
    for a, b in ((0.5, 20.0), (0.95, 11.0), (0.05, 29.0), (0.9, 29.0)):
        for i, v in enumerate((a, b)):
            page.eval_on_selector(
                f"#pslider-{i}", "(el, t) => { el.value = t; el.dispatchEvent(new Event('input')); }", v
            )
        z = float(validity_log_odds(doc, np.array([[a, b]]))[0])
        assert page.eval_on_selector("#pvalid", "p => p.dataset.impossible") == ("1" if z > 0 else "0")
        assert f"P(impossible) = {1 / (1 + np.exp(-z)):.3f}" in page.inner_text("#pvalid")
        seen.add(z > 0)
    assert seen == {True, False}
    assert problems == []
    page.close()
