"""The study report in the study's declared units with response names in words: the profiler's sliders show the
variables in their declared unit (ft², deg, not the SI number beside an aviation unit), its predictions and the
CDF axes name the response in words in an aviation unit (block fuel in lb, range margin in nmi).

References: exact unit definitions (1 lb = 0.45359237 kg, 1 nmi = 1852 m, 1 ft = 0.3048 m, 1 deg = π/180 rad)."""

from __future__ import annotations

import math
import re
from functools import lru_cache

import pytest

from certkit.study.analysis.labels import display_factor, response_axis, response_label
from tests.browser import MARKS, open_page
from tests.study_analysis.synthetic import DEG, FT2, store_frame, study_dict, study_of

# the tests of the synthetic study's reports run on one pytest-xdist worker, which builds each once
pytestmark = pytest.mark.xdist_group("study-report")


def test_response_words_and_aviation_units():
    assert response_label("objective.block_fuel_kg") == ("block fuel", "lb", pytest.approx(0.45359237, rel=1e-12))
    assert response_label("constraint.range_margin_m") == ("range margin", "nmi", pytest.approx(1852.0, rel=1e-12))
    assert response_label("objective.block_time_s") == ("block time", "h", pytest.approx(3600.0, rel=1e-12))
    assert response_label("objective.cruise_CD") == ("cruise CD", "", 1.0)
    assert response_label("subcheck.25.335(a).margin_m_s")[:2] == ("§25.335(a) margin", "kn")
    assert response_axis("objective.OEW_kg") == "OEW (lb)"
    # a mode quantity of the record: the mode, the quantity and where (SI: rad/s, and the CAP's own unit)
    assert response_label("mode.short_period.wn_rad_s.fwd_mrw.clean") == (
        "short period natural frequency ω_n, fwd_mrw clean",
        "rad/s",
        1.0,
    )
    assert response_label("mode.phugoid.zeta.aft_mid.takeoff")[0] == "phugoid damping ratio ζ, aft_mid takeoff"


def test_declared_units_of_the_variables():
    assert display_factor("ft^2") == pytest.approx(0.3048**2, rel=1e-12)
    assert display_factor("deg") == pytest.approx(math.pi / 180, rel=1e-12)
    assert display_factor("") == 1.0 and display_factor("no-such-unit") == 1.0


@lru_cache(maxsize=1)
def _declared_units_report():
    from certkit.report.study_report import render
    from certkit.study.analysis.analyse import analyse

    study = study_dict(gp_max_cases=150)
    for v in study["variables"]:
        v["unit_label"] = {"rad": "deg", "m^2": "ft^2"}.get(v["unit_label"], v["unit_label"])
    analysis = analyse(study_of(study), store_frame(n_train=200, n_val=60), samples=20_000, check=False)
    return analysis, render(analysis)


def test_cdf_axes_name_the_response_in_aviation_units():
    analysis, html = _declared_units_report()
    names = [c.response for c in analysis.view.constraints if c.response.endswith(("_kg", "_m", "_m_s"))]
    assert names
    cdfs = [svg for svg in re.findall(r"<svg.*?</svg>", html, re.S) if "P(success)" in svg]
    assert cdfs
    for name in names:
        assert any(response_axis(name) in svg for svg in cdfs), name
    assert not any(re.search(r"(constraint|objective)\.\w+", svg) for svg in cdfs)  # no internal key on an axis


@MARKS[0]
@MARKS[1]
def test_profiler_shows_declared_units_and_response_words(browser, tmp_path):
    analysis, html = _declared_units_report()
    path = tmp_path / "index.html"
    path.write_text(html, encoding="utf-8")
    page, problems = open_page(browser, path, 1200, ready='#profiler[data-ready="1"]')
    for i, v in enumerate(analysis.view.variables):
        shown = page.text_content(f"#pvalue-{i}")
        x = float(page.eval_on_selector(f"#pslider-{i}", "e => e.value"))
        if v.unit_label == "ft^2":
            assert shown.endswith(" ft^2") and float(shown.split()[0]) == pytest.approx(x / FT2, rel=1e-3)
            assert 800 < float(shown.split()[0]) < 1500  # square feet, not the square metres of the SI value
        if v.unit_label == "deg":
            assert shown.endswith(" deg") and float(shown.split()[0]) == pytest.approx(x / DEG, rel=1e-3)
    cells = page.eval_on_selector_all("td.pred", "els => els.map(e => [e.dataset.response, e.textContent])")
    for key, text in cells:
        words, unit, _ = response_label(key)
        assert text.startswith(f"{words} = ") and key not in text
        if unit:
            assert f" {unit}" in text
    assert problems == []
    page.close()


def test_fit_figures_and_planforms_speak_aviation():
    """A surrogate's fit figure names its response in words and aviation units (block fuel in lb: the predicted
    100,000 kg is drawn at 220,462 lb), never the key; planforms are drawn in feet."""
    from types import SimpleNamespace

    import numpy as np

    from certkit.report.study_figures import fit_svg, planforms_svg
    from certkit.study.analysis.planform import Planform

    kg = np.array([9.0e4, 1.0e5, 1.1e5])
    s = SimpleNamespace(
        response="objective.block_fuel_kg",
        plot_data={"training": (kg, kg * 1.01), "validation": (kg, kg * 0.99)},
        kept=SimpleNamespace(label="quadratic"),
    )
    svg = fit_svg(s)
    assert "block fuel: quadratic" in svg and "predicted (lb)" in svg and "actual − predicted (lb)" in svg
    assert "objective." not in svg and "block_fuel" not in svg
    p = Planform(1119.2 * FT2, 4.62, 0.33, 34.82 * DEG, (0.07, 0.94, 0.29))
    plan = planforms_svg([("baseline", p)])
    assert "span position y (ft)" in plan and "(m" not in plan
