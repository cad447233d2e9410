"""Flat responses of a design record, from hand-made rule results (values checked by hand)."""

import math

import pytest

from certkit.design.evaluate import mission_needed, rule_needed
from certkit.design.record import check_name, handling_levels, rule_responses
from certkit.engine.results import Condition, Finding, RuleResult

TRAVEL = {"elevator": (math.radians(-30.0), math.radians(25.0)), "rudder": (math.radians(-27.3), math.radians(27.3))}


def _result():
    c1, c2 = Condition(loading="fwd_mrw"), Condition(loading="aft_mrw")
    return RuleResult("25.143(h)", "maneuvering-capability", "t", [
        Finding.compare(c1, "(h) takeoff V2 elevator within design limit", -20.0, -21.8, at_least=True, unit="deg"),
        Finding.compare(c2, "(h) takeoff V2 elevator within design limit", -21.0, -21.8, at_least=True, unit="deg"),
        Finding.compare(c1, "(h) takeoff V2 rudder within design limit", 24.0, 23.2, at_least=False, unit="deg"),
        Finding.not_evaluated(c2, "(h) takeoff V2 rudder within design limit", "trim did not converge"),
        Finding.compare(c1, "(a) gust, wing: ultimate bending at root (max)", 9.0, 10.0, at_least=False, unit="N·m"),
    ])


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
    mk = lambda lv: Finding.compare(c, "(a) short period heavily damped", 0.5, 0.35, at_least=True,  # noqa: E731
                                    modes={"short_period": {"level_A": 1, "level_B": lv, "level_B_limited_by": "x"}})
    levels = handling_levels([RuleResult("25.181", "dynamic-stability", "t", [mk(1), mk(2)])])
    assert levels == {"level.short_period.fwd_mrw.clean": 2}


def test_check_name_slug():
    assert check_name("(c)(2) checked manoeuvre, nose up: ultimate bending at root (min)") == "c_2_checked_manoeuvre_nose_up"


@pytest.mark.parametrize("patterns, rid, needed", [
    (None, "25.103", True),
    (["rule.25.331(c)(2).margin"], "25.331(c)(2)", True),
    (["rule.25.331(c)(2).margin"], "25.331(c)(1)", False),
    (["subcheck.25.143(h).*"], "25.143(h)", True),
    (["level.*"], "25.181", True),
    (["level.*"], "25.171", False),
    (["travel.elevator"], "25.171", True),
    (["objective.*"], "25.171", False),
    (["*"], "25.171", True),
])
def test_rules_needed_by_responses(patterns, rid, needed):
    assert rule_needed(rid, patterns) is needed


def test_mission_needed():
    assert mission_needed(None) and mission_needed(["objective.*"]) and mission_needed(["constraint.range_margin_m"])
    assert not mission_needed(["objective.OEW_kg"])  # from the sizing loop
    assert not mission_needed(["rule.*"])


def test_not_evaluated_first_then_evaluated():
    """A check whose first finding could not be evaluated still takes the margin of a later evaluated one."""
    c = Condition(loading="fwd_mrw")
    r = RuleResult("25.149", "minimum-control-speed", "t", [
        Finding.not_evaluated(c, "(c) VMCA ≤ 1.13 VSR", "trim did not converge"),
        Finding.compare(c, "(c) VMCA ≤ 1.13 VSR", 70.0, 80.0, at_least=False, unit="m/s"),
        Finding.compare(c, "(c) VMCA ≤ 1.13 VSR", 75.0, 80.0, at_least=False, unit="m/s")])
    out, st = rule_responses([r], {})
    assert out["subcheck.25.149.c_vmca_1_13_vsr.margin"] == pytest.approx(5.0 / 80.0)
    assert st["subcheck.25.149.c_vmca_1_13_vsr"] == "not_evaluated"
