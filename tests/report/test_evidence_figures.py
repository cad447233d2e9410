"""Evidence drawn from data (certkit/report/figures.py, svg.py, tables.py, display.py): one convention for every figure,
deterministic bytes, ids unique across a page, decimation that keeps what the eye sees, tables in aviation units
without None/-0/noise cells. References: the unit definitions (1 kn = 1852/3600 m/s exactly, 1 ft = 0.3048 m exactly,
1 lbf = 4.4482216152605 N, NIST SP 811 appendix B), and the data each test builds."""

import re

import numpy as np
import pytest

from certkit.engine.evidence import Axis, Bars, Chart, Column, Heatmap, Limit, Panel, Point, Series, Table
from certkit.engine.results import Evidence
from certkit.report.figures import FAIL, decimate, render, render_evidence
from certkit.report.tables import formatted


def _chart():
    t = np.linspace(0.0, 10.0, 4001)
    return Chart(
        Axis("time", "s"),
        [
            Panel(
                Axis("elevator", "rad"),
                [Series("run A", t, 0.1 * np.sin(t), critical=True), Series("run B", t, 0.1 * np.cos(t), end=6.0)],
                [Limit(-0.2, "design limit", kind="allowable")],
            ),
            Panel(
                Axis("root shear", "N", "kN"),
                [Series("run A", t, 1e6 * np.sin(t)), Series("run B", t, 1e6 * np.cos(t))],
                [Limit(1.5e6, "allowable (+)", kind="allowable"), Limit(3.0, "(c) settled", axis="x", kind="event")],
                [Point(np.pi / 2, 1e6)],
            ),
        ],
        title="test chart",
    )


def _ids(svg: str) -> list[str]:
    return re.findall(r'\bid="([^"]+)"', svg)


def test_same_data_same_bytes():
    a, b = render(_chart(), "ev-x-0"), render(_chart(), "ev-x-0")
    assert a == b
    assert "<dc:date>" not in a and "Date" not in a


def test_ids_prefixed_unique_and_resolved():
    bars = Bars(["a", "b"], [-0.1, 0.2], Axis("normalised margin"), [True, False], Limit(0.0, "0"))
    evs = [Evidence("a", bars), Evidence("b", bars), Evidence("c", _chart())]
    render_evidence(evs, "ev-25-341-a")
    page = "".join(e.svg for e in evs)
    ids = _ids(page)
    assert ids and len(ids) == len(set(ids))  # identical figures on one page share no id
    assert len(ids) >= 2 and all(i.startswith(("ev-25-341-a-0-", "ev-25-341-a-1-")) for i in ids)
    for ref in re.findall(r'(?:url\(#|href="#)([^")]+)', page):
        assert ref in ids


def test_conventions_in_a_chart():
    svg = render(_chart(), "c")
    for text in (
        "design limit",
        "allowable (+)",
        "(c) settled",
        "run A (critical)",
        "critical: root shear 1,000 kN",
        "root shear (kN)",
        "elevator (deg)",
        "time (s)",
    ):
        assert text in svg, text
    sizes = [float(s) for s in re.findall(r'font-size="([0-9.]+)"', svg)]
    assert sizes and min(sizes) >= 8.0  # no 6 px labels
    assert "#0072b2" in svg.lower() and "#e69f00" in svg.lower()  # Okabe–Ito palette, in order


def test_series_end_where_the_run_ended():
    t = np.linspace(0.0, 10.0, 101)
    s = Series("run", t, t, end=6.0)
    assert s.x[-1] == pytest.approx(6.0) and s.x.size == 61


def test_decimation_keeps_extremes_and_breaks():
    x = np.arange(100_000, dtype=float)
    y = np.sin(x / 5000.0)
    y[31_337] = 50.0  # a one-sample spike
    y[70_000:70_010] = np.nan  # a gap
    dx, dy = decimate(x, y, buckets=500)
    assert dx.size <= 1000 + 20
    assert np.nanmax(dy) == 50.0 and dx[np.nanargmax(dy)] == 31_337
    assert np.nanmin(dy) == pytest.approx(np.nanmin(y))
    assert np.isnan(dy).any()  # the line stays broken at the gap
    assert np.all(np.diff(dx) > 0)
    short = np.arange(10.0)
    assert decimate(short, short, buckets=500)[0] is short


def test_heatmap_has_colour_bar_and_distinct_failing_cells():
    hm = Heatmap(
        ["fwd", "aft"],
        ["clean", "flaps"],
        np.array([[0.3, -0.01], [np.nan, 0.5]]),
        Axis("smallest normalised margin"),
        "CG corner",
        "configuration",
    )
    svg = render(hm, "h")
    assert "smallest normalised margin (&lt; 0 fails)" in svg or "smallest normalised margin (< 0 fails)" in svg
    fills = {tuple(int(c[i : i + 2], 16) for i in (0, 2, 4)) for c in re.findall(r'fill="#([0-9a-fA-F]{6})"', svg)}
    # the barely failing cell (−0.01) is a strong vermillion (the palette's failing colour), not a pale one
    fail = tuple(int(FAIL[i : i + 2], 16) for i in (1, 3, 5))
    assert any(sum(abs(a - b) for a, b in zip(f, fail)) < 30 for f in fills)
    assert "<pattern" in svg  # and hatched
    assert "—" in svg  # not evaluated
    assert len(re.findall(r'<rect [^>]*height="[0-9.]+" fill="#', svg)) >= 64 + 3  # the cells and the colour bar


def test_bars_fail_and_limit():
    b = Bars(
        ["a", "b"],
        [0.01, 0.03],
        Axis("steady climb gradient", "gradient"),
        [True, False],
        Limit(0.024, "minimum 2.4 %"),
        horizontal=False,
    )
    svg = render(b, "b")
    assert "steady climb gradient (%)" in svg and "minimum 2.4 %" in svg and "fails" in svg and "complies" in svg


def test_tables_in_aviation_units_without_noise():
    t = Table(
        [
            Column("v", "speed", "m/s"),
            Column("mach", "Mach"),
            Column("f", "thrust", "N"),
            Column("n", "note", kind="text"),
            Column("bank_x", "bank", "deg"),
        ],
        [[100.0, 5.551e-17, 4448.2216152605, None, -0.0], [51.444, 0.84, None, "ok", 12.5]],
    )
    out = formatted(t)
    assert out["headers"] == ["speed (kn)", "Mach", "thrust (lbf)", "note", "bank (deg)"]
    (v1, m1, f1, n1, b1), (v2, m2, f2, n2, b2) = [[text for text, _ in row] for row in out["rows"]]
    assert v1 == "194.4" and v2 == "100.0"  # 100 m/s = 194.38 kn; one decimal for the column's 4 digits
    assert m1 == "0.0000" and m2 == "0.8400"  # round-off noise reads as zero at the column's precision
    assert f1 == "1,000" and f2 == "—" and n1 == "—"  # 4448.22 N = 1000 lbf
    assert b1 == "0.00" and b2 == "12.50"  # no -0; 4 significant digits of the column's largest
    assert [num for _, num in out["rows"][0]] == [True, True, True, False, True]


def test_dict_rows_get_human_columns():
    ev = Evidence("t", table=[{"bank_deg": 30.0, "CL_over_CLmax": 0.8, "thrust_at_trim_N": 1e5, "VEF kn": 140.0}])
    names = {c.key: (c.name, c.unit, c.display) for c in ev.table.columns}
    assert names["bank_deg"] == ("bank φ", "deg", "deg")
    assert names["CL_over_CLmax"][0] == "CL / CLmax"
    assert names["VEF kn"][:2] == ("VEF", "kn")
    headers = formatted(ev.table)["headers"]
    assert headers == ["bank φ (deg)", "CL / CLmax", "thrust at trim (lbf)", "VEF (kn)"]
    with pytest.raises(TypeError):
        Evidence("t", "<svg/>")  # a figure is data, never drawn SVG


def test_a_rules_evidence_is_the_same_bytes_twice(baseline):
    """Two evaluations of §25.333 on fresh contexts draw byte-identical evidence (no random ids, no date)."""
    from certkit.engine.context import Context
    from certkit.engine.registry import discover
    from certkit.engine.scheduler import evaluate_rule
    from certkit.report.figures import render_result

    rule = next(r for r in discover() if r.id == "25.333")
    svgs = []
    for _ in range(2):
        result = evaluate_rule(rule, Context(baseline))
        render_result(result)
        svgs.append([e.svg for e in result.evidence])
    assert svgs[0] and svgs[0][0].startswith("<svg") and svgs[0] == svgs[1]


def test_close_vertical_lines_get_separate_labels():
    """VA and VC a few knots apart (the V–n diagram): their labels are pushed apart by at least a text height."""
    v = np.linspace(0.0, 180.0, 50)
    chart = Chart(
        Axis("equivalent airspeed", "m/s", "kn"),
        [
            Panel(
                Axis("load factor n", "g"),
                [Series("W", v, v / 70.0)],
                [Limit(136.8, "VA", axis="x", kind="reference"), Limit(139.9, "VC", axis="x", kind="reference")],
            )
        ],
    )
    svg = render(chart, "v")
    xs = [float(m) for m in re.findall(r'<text x="([0-9.]+)"[^>]*rotate\(-90[^>]*>V[AC]<', svg)]
    assert len(xs) == 2 and abs(xs[1] - xs[0]) >= 8.0


def test_mixed_unit_columns_convert_per_row():
    """A findings table (value, limit, margin in each row's unit): m/s rows read in kn, deg rows stay."""
    t = Table(
        [Column("value", "value", unit_key="unit"), Column("unit", "unit", kind="text")],
        [[77.1666, "m/s"], [12.5, "deg"]],
    )
    rows = [[text for text, _ in row] for row in formatted(t)["rows"]]
    assert rows == [["150.0", "kn"], ["12.5", "deg"]]  # 77.1666 m/s = 150.0 kn; one decimal for the column
