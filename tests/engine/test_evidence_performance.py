"""The generic performance evidence (certkit/engine/evidence/performance.py) on hand-made findings: the table carries
every evaluated finding (gradients in percent), the bar chart the worst ones, and nothing is drawn without margins."""

import pytest

from certkit.engine.evidence import Bars
from certkit.engine.evidence.performance import climb_gradient_evidence, margins_evidence
from certkit.engine.results import Condition, Finding
from certkit.report.figures import render_evidence


def _findings():
    c = Condition(loading="MTOW aft", configuration="takeoff", altitude=0.0, speed_name="V2")
    return [
        Finding.compare(
            c,
            "(b) gradient at V2, gear up",
            0.031,
            0.024,
            at_least=True,
            unit="gradient",
            rudder_deg=-12.5,
            elevator_deg=-3.0,
        ),
        Finding.compare(
            c.with_(loading="MTOW forward"),
            "(b) gradient at V2, gear up",
            0.020,
            0.024,
            at_least=True,
            unit="gradient",
            rudder_deg=-12.0,
        ),
        Finding.compare(c, "(b) rudder within design limit", -25.0, -23.2, at_least=True, unit="deg"),
        Finding.not_evaluated(c, "(b) something", "needs speeds.VMC"),
    ]


def test_margins_table_and_plot():
    (ev,) = margins_evidence(_findings(), "title", "caption.", ("rudder_deg",), plot=True)
    assert isinstance(ev.figure, Bars) and ev.figure.failing == [True, True, False]
    render_evidence([ev], "t")
    assert "<svg" in ev.svg
    assert len(ev.table) == 3  # the not-evaluated finding has no margin
    rows = ev.table.as_dicts()
    worst = rows[0]
    assert worst["check"].startswith("(b) gradient") and worst["status"] == "fails"
    assert worst["value"] == pytest.approx(2.0) and worst["limit"] == pytest.approx(2.4) and worst["unit"] == "%"
    assert worst["margin"] == pytest.approx(-0.4)
    # ordered by normalised margin: −0.4/2.4 = −0.167, then −1.8/23.2 = −0.078, then +0.7/2.4
    assert rows[1]["check"].startswith("(b) rudder") and rows[1]["rudder_deg"] is None
    assert ev.table.columns[-1].name == "rudder" and ev.table.columns[-1].unit == "deg"  # a human name, the unit apart
    assert rows[2]["rudder_deg"] == -12.5 and rows[2]["margin"] == pytest.approx(0.7)


def test_climb_gradients_and_nothing_without_margins():
    evs = climb_gradient_evidence(_findings(), "§25.121(b)")
    assert [e.title for e in evs] == ["§25.121(b): gradients", "§25.121(b): trims"]
    assert margins_evidence(_findings()[3:], "t", "c") == []
    (table_only,) = margins_evidence(_findings(), "t", "c")
    assert table_only.figure is None and table_only.svg == "" and len(table_only.table) == 3
