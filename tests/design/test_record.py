"""Flat responses of a design record, from hand-made rule results (values checked by hand)."""

import math
from types import SimpleNamespace

import pytest

from certkit.design.evaluate import mission_needed, rule_needed
from certkit.design.record import check_name, offered_responses, rule_responses
from certkit.engine.registry import ControlCase, ControlResponses, ModeResponses
from certkit.engine.results import Condition, Finding, RuleResult

TRAVEL = {"elevator": (math.radians(-30.0), math.radians(25.0)), "rudder": (math.radians(-27.3), math.radians(27.3))}


def _result():
    c1, c2 = Condition(loading="fwd_mrw"), Condition(loading="aft_mrw")
    return RuleResult(
        "25.143(h)",
        "maneuvering-capability",
        "t",
        [
            Finding.compare(c1, "(h) takeoff V2 elevator within design limit", -20.0, -21.8, at_least=True, unit="deg"),
            Finding.compare(c2, "(h) takeoff V2 elevator within design limit", -21.0, -21.8, at_least=True, unit="deg"),
            Finding.compare(c1, "(h) takeoff V2 rudder within design limit", 24.0, 23.2, at_least=False, unit="deg"),
            Finding.not_evaluated(c2, "(h) takeoff V2 rudder within design limit", "trim did not converge"),
            Finding.compare(
                c1, "(a) gust, wing: ultimate bending at root (max)", 9.0, 10.0, at_least=False, unit="N·m"
            ),
        ],
    )


def test_rule_and_subcheck_responses():
    out, st = rule_responses([_result()], TRAVEL)
    # smallest normalised margin: rudder (23.2 − 24)/23.2
    assert out["rule.25.143(h).margin"] == pytest.approx((23.2 - 24.0) / 23.2)
    assert st["rule.25.143(h)"] == "fails"
    key = "subcheck.25.143(h).h_takeoff_v2_elevator_within_design_limit"
    assert out[key + ".margin"] == pytest.approx(0.8 / 21.8) and out[key + ".value"] == -21.0
    assert st[key] == "complies"
    assert st["subcheck.25.143(h).h_takeoff_v2_rudder_within_design_limit"] == "fails"  # fails outranks not evaluated
    assert out["subcheck.25.143(h).a_gust_wing.margin"] == pytest.approx(0.1)  # station text after ': ' dropped


def test_travel_fractions_by_direction():
    out, _ = rule_responses([_result()], TRAVEL)
    assert out["travel.25.143(h).elevator"] == pytest.approx(21.0 / 30.0)  # trailing edge up: the -30° stop
    assert out["travel.25.143(h).rudder"] == pytest.approx(24.0 / 27.3)
    assert out["travel.elevator"] == pytest.approx(21.0 / 30.0)


def test_levels_worst_per_mode_corner_configuration():
    c = Condition(loading="fwd_mrw", configuration="clean")
    mk = lambda lv: Finding.compare(  # noqa: E731
        c,
        "(a) short period heavily damped",
        0.5,
        0.35,
        at_least=True,
        unit="ζ",
        modes={"short_period": {"level_A": 1, "level_B": lv, "level_B_limited_by": "x"}},
    )
    rules = [_rule("25.181", ModeResponses(("short_period",)))]
    levels = offered_responses([RuleResult("25.181", "dynamic-stability", "t", [mk(1), mk(2)])], rules)
    assert {k: v for k, v in levels.items() if k.startswith("level.")} == {"level.short_period.fwd_mrw.clean": 2}
    # a rule that does not declare mode responses gives none, whatever its findings hold
    assert offered_responses([RuleResult("25.181", "dynamic-stability", "t", [mk(1)])], [_rule("25.181")]) == {}


def _rule(rid, *offers):
    return SimpleNamespace(id=rid, offers=tuple(offers))


def test_check_name_slug():
    assert (
        check_name("(c)(2) checked manoeuvre, nose up: ultimate bending at root (min)")
        == "c_2_checked_manoeuvre_nose_up"
    )


MODES = ModeResponses(("short_period", "phugoid"))


@pytest.mark.parametrize(
    "patterns, rid, offers, needed",
    [
        (None, "25.103", (), True),
        (["rule.25.331(c)(2).margin"], "25.331(c)(2)", (), True),
        (["rule.25.331(c)(2).margin"], "25.331(c)(1)", (), False),
        (["subcheck.25.143(h).*"], "25.143(h)", (), True),
        (["level.*"], "25.181", (MODES,), True),
        (["level.phugoid.fwd_mrw.clean"], "25.181", (MODES,), True),
        (["level.*.fwd_mrw.*"], "25.181", (MODES,), True),
        (["level.dutch_roll.*"], "25.181", (MODES,), False),
        (["level.*"], "25.171", (), False),
        (["travel.elevator"], "25.171", (), True),
        (["objective.*"], "25.171", (), False),
        (["*"], "25.171", (), True),
    ],
)
def test_rules_needed_by_responses(patterns, rid, offers, needed):
    assert rule_needed(_rule(rid, *offers), patterns) is needed


def test_mission_needed():
    assert mission_needed(None) and mission_needed(["objective.*"]) and mission_needed(["constraint.range_margin_m"])
    assert not mission_needed(["objective.OEW_kg"])  # from the sizing loop
    assert not mission_needed(["rule.*"])


def test_not_evaluated_first_then_evaluated():
    """A check whose first finding could not be evaluated still takes the margin of a later evaluated one."""
    c = Condition(loading="fwd_mrw")
    r = RuleResult(
        "25.149",
        "minimum-control-speed",
        "t",
        [
            Finding.not_evaluated(c, "(c) VMCA ≤ 1.13 VSR", "trim did not converge"),
            Finding.compare(c, "(c) VMCA ≤ 1.13 VSR", 70.0, 80.0, at_least=False, unit="m/s"),
            Finding.compare(c, "(c) VMCA ≤ 1.13 VSR", 75.0, 80.0, at_least=False, unit="m/s"),
        ],
    )
    out, st = rule_responses([r], {})
    assert out["subcheck.25.149.c_vmca_1_13_vsr.margin"] == pytest.approx(5.0 / 80.0)
    assert st["subcheck.25.149.c_vmca_1_13_vsr"] == "not_evaluated"


def test_mode_quantities_of_the_condition_that_sets_the_level():
    """The record's mode.* quantities are those of the worst-level condition (lowest ζ among equal levels)."""
    c = Condition(loading="fwd_mrw", configuration="clean")
    row = lambda z, lv: {  # noqa: E731
        "short_period": {
            "zeta": z,
            "wn_rad_s": 1.1,
            "period_s": 6.0,
            "t_half_s": 2.0,
            "t_double_s": None,
            "cap": 0.4,
            "level_A": lv,
            "level_B": lv,
        }
    }
    fs = [
        Finding.compare(c, "(a) short period heavily damped", z, 0.3, at_least=True, unit="ζ", modes=row(z, lv))
        for z, lv in ((0.5, 1), (0.27, 2), (0.22, 2))
    ]
    out = offered_responses([RuleResult("25.181", "d", "t", fs)], [_rule("25.181", ModeResponses(("short_period",)))])
    assert out["level.short_period.fwd_mrw.clean"] == 2
    assert out["mode.short_period.zeta.fwd_mrw.clean"] == 0.22
    assert out["mode.short_period.cap.fwd_mrw.clean"] == 0.4
    assert out["mode.short_period.t_double_s.fwd_mrw.clean"] is None


def test_control_responses_per_case_as_fractions_of_travel():
    """control.<rule>.<case>.<control>: the largest fraction of the travel over the case's findings (by hand: 21/30
    of the −30° elevator stop, 24/27.3 of the rudder's); a case's prefix does not take another case's findings."""
    case = ControlResponses(
        (
            ControlCase("takeoff OEI V2 30deg", "(h) takeoff V2 "),
            ControlCase("takeoff AEO V2+XX 40deg", "(h) takeoff V2+XX "),
        )
    )
    res = _result()
    res.findings.append(
        Finding.compare(
            Condition(loading="fwd_mrw"),
            "(h) takeoff V2+XX elevator within design limit",
            -3.0,
            -21.8,
            at_least=True,
            unit="deg",
        )
    )
    out = offered_responses([res], [_rule("25.143(h)", case)], TRAVEL)
    assert out["control.25.143(h).takeoff_oei_v2_30deg.elevator"] == pytest.approx(21.0 / 30.0)
    assert out["control.25.143(h).takeoff_oei_v2_30deg.rudder"] == pytest.approx(24.0 / 27.3)
    assert out["control.25.143(h).takeoff_aeo_v2_xx_40deg.elevator"] == pytest.approx(3.0 / 30.0)
    assert rule_needed(_rule("25.143(h)", case), ["control.25.143(h).takeoff_oei_v2_30deg.*"])


def test_least_level_margins_over_the_conditions():
    """mode.<mode>.level<L>_margin: the least over the conditions of the offer's level margin. Short period, clean
    (categories A and B; Table IV: Level 1 ζ ≥ 0.35 in A; 3.2.2.1.1: CAP ≥ 0.28 in A), three conditions ζ 0.5 / 0.27
    / 0.22 at CAP 0.4: Level 1 margin (0.22 − 0.35)/0.35 = −0.371 (the worst ζ), Level 2 (0.22 − 0.25)/0.25 = −0.12
    (A's 0.25), Level 3 (0.22 − 0.15)/0.15 = +0.467: Level 3 exactly where the margins say so."""
    from certkit_rules.part25.support import handling_levels as hq

    c = Condition(loading="fwd_mrw", configuration="clean")
    fs = [
        Finding.compare(
            c,
            "(a) short period heavily damped",
            z,
            0.3,
            at_least=True,
            unit="ζ",
            modes={"short_period": {"zeta": z, "wn_rad_s": 1.1, "cap": 0.4, "level_A": lv, "level_B": lv}},
        )
        for z, lv in ((0.5, 1), (0.27, 2), (0.22, 3))
    ]
    offer = ModeResponses(("short_period",), level=hq.damping_level, level_margin=hq.damping_level_margin)
    out = offered_responses([RuleResult("25.181", "d", "t", fs)], [_rule("25.181", offer)])
    assert out["mode.short_period.level1_margin.fwd_mrw.clean"] == pytest.approx((0.22 - 0.35) / 0.35)
    assert out["mode.short_period.level2_margin.fwd_mrw.clean"] == pytest.approx((0.22 - 0.25) / 0.25)
    assert out["mode.short_period.level3_margin.fwd_mrw.clean"] == pytest.approx((0.22 - 0.15) / 0.15)
    assert out["level.short_period.fwd_mrw.clean"] == 3
    # without the offer's margin function nothing is recorded
    plain = offered_responses([RuleResult("25.181", "d", "t", fs)], [_rule("25.181", ModeResponses(("short_period",)))])
    assert not any("_margin." in k for k in plain)
