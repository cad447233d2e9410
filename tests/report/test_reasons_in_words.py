"""Reasons a reviewer reads: the scheduled condition fields in words, a one-line cause without the mass and CG
numbers (the full condition in a tooltip), margin descriptions in the units the numbers are shown in, and a
findings table per unit (a rule with knot and Mach margins, §25.335(b), shows two tables, never one mixed column).

Reference: the report's own display units (certkit.report.display.DEFAULT: m/s shown in kn, m/s² in g)."""

from __future__ import annotations

import re

from certkit.engine.registry import discover
from certkit.engine.results import Condition, Finding, RuleResult, RunResult, field_words
from certkit.report.display import in_display_units
from certkit.report.html import render_html
from certkit.report.reasons import reason_condition, reason_line
from certkit.units import FT, KN, LB

CONDITION = Condition(
    loading="aft_light",
    mass=200_000 * LB,
    x_cg=100 * FT,
    configuration="clean",
    altitude=20_000 * FT,
    speed=250 * KN,
    speed_kind="EAS",
    speed_name="VC",
    extra=(
        ("speed_point", "1.3 VSR"),
        ("bank_deg", 30),
        ("delta_isa_K", 15),
        ("entry_speed", "VA"),
        ("inoperative", "left"),
    ),
)


def test_scheduled_fields_read_as_words():
    label = CONDITION.label()
    for internal in ("speed_point", "bank_deg", "delta_isa_K", "entry_speed", "_"):
        assert internal not in label.replace("aft_light", ""), label
    assert "at 1.3 VSR" in label and "30° bank" in label and "ISA +15 °C" in label and "entry at VA" in label
    assert "left engine inoperative" in label
    assert field_words("some_new_field", 3) == "some new field 3"
    assert field_words("delta_isa_K", 33.019) == "ISA +33 °C"


def _result(findings, rule_id="25.335(b)"):
    return RuleResult(rule_id, "design-dive-speed", "Design dive speed VD/MD", findings)


def test_one_line_cause_leaves_the_numbers_of_the_loading_to_the_tooltip():
    f = Finding.compare(CONDITION, "(b) VC/MC ≤ 0.8 VD/MD", 240 * KN, 250 * KN, at_least=True, unit="m/s")
    r = _result([f])
    line = reason_line(r)
    assert line.startswith("fails by 10.00 kn at aft_light") and line.endswith(": (b) VC/MC ≤ 0.8 VD/MD")
    assert " lb" not in line and "CG" not in line
    assert "200,000 lb" in reason_condition(r) and "CG 100.00 ft" in reason_condition(r)


def test_margin_descriptions_in_the_shown_units():
    assert (
        in_display_units("VC − (VB + 1.32 U_ref), m/s EAS, at each altitude")
        == "VC − (VB + 1.32 U_ref), kn EAS, at each altitude"
    )
    assert in_display_units("(c) 1.13 VSR − VMCA (m/s CAS)") == "(c) 1.13 VSR − VMCA (kn CAS)"
    assert in_display_units("peak acceleration, m/s²; rate in rad/s") == "peak acceleration, g; rate in rad/s"


def test_a_rule_with_knot_and_mach_margins_shows_one_table_per_unit():
    rules = [r for r in discover() if r.id == "25.335(b)"]
    knots = Finding.compare(CONDITION, "(b) VC/MC ≤ 0.8 VD/MD", 280 * KN, 272 * KN, at_least=True, unit="m/s")
    mach = Finding.compare(
        Condition(altitude=35_000 * FT), "(b)(2) MD − M(VC) ≥ Mach margin", 0.08, 0.07, at_least=True, unit="Mach"
    )
    run = RunResult("x", "test airplane", "0" * 64, "a.yaml", "now", [_result([knots, mach])])
    html = render_html(run, rules)
    body = html[html.index('<section class="rule"') :]
    findings = body[body.index("All 2 findings") : body.index("</section>")]
    tables = re.findall(r"<table>.*?</table>", findings, re.S)
    assert len(tables) == 2
    units = [set(re.findall(r"\d (kn|Mach)</td>", t)) for t in tables]
    assert sorted(map(sorted, units)) == [["Mach"], ["kn"]]
    assert "Findings in kn" in body and "Findings in Mach" in body
    assert "m/s EAS" not in body  # the margin description reads kn
    assert 'title="aft_light · 200,000 lb · CG 100.00 ft' in html
