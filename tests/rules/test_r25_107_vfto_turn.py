"""§25.107(g)(2): VFTO not less than a speed that provides the §25.143(h) manoeuvring capability — the en-route
40° coordinated turn at VFTO with asymmetric WAT-limited thrust, free of stall warning.

By hand (Anderson, *Introduction to Flight*, n = 1/cos φ in a level coordinated turn; the 1-g stall speed scales with
√n): without a declared warning onset the latest §25.207(c) allows is used, VSW = 1.05 VSR, so the 40° turn stays
free of warning down to 1.05 VSR √n = 1.05 × 167.598 × √(1/cos 40°) = 201.1 KCAS at MTOW (VSR clean 167.598 kn:
656,000 lb, CLmax 1.4, S 4927.3 ft²). The WAT-limited climb's path changes n by less than 0.2 %, hence the 0.3-kn
tolerance. The baseline's VFTO, the (g)(1) minimum 198 KCAS, lies below: (g)(2) fails on the stall warning at every CG,
altitude and turn direction while the controls are within their limits; a VFTO of 204 KCAS gives the capability.
"""

import math

import pytest

from .helpers import own, run_rule

RULE = "25.107(g)(2)"
VSR_CLEAN_KN = 167.598


def warnings(result):
    return [f for f in own(result) if f.check.endswith("free of stall warning")]


@pytest.fixture(scope="module")
def base():
    return run_rule(RULE)


def test_the_baselines_vfto_is_below_the_turns_warning_free_speed(base):
    found = warnings(base)
    assert len(found) == 12  # three CGs, two altitudes, two directions
    hand = 1.05 * VSR_CLEAN_KN * math.sqrt(1 / math.cos(math.radians(40)))
    for f in found:
        assert f.status == "fails" and f.unit == "C_L" and f.limit == pytest.approx(1.4 / 1.05**2, rel=1e-6)
        assert f.condition.speed_name == "VFTO" and abs(f.details["bank_deg"]) == pytest.approx(40.0)
        assert f.details["speed_at_warning_onset_kn"] == pytest.approx(hand, abs=0.3)
    controls = [f for f in own(base) if f.check.endswith("within design limit")]
    assert len(controls) == 36 and all(f.status == "complies" for f in controls)


def test_a_vfto_above_that_speed_gives_the_capability(tmp_path):
    res = run_rule(RULE, tmp_path, [("  VFTO: 198 kn CAS", "  VFTO: 204 kn CAS")])
    found = warnings(res)
    assert len(found) == 12 and all(f.status == "complies" for f in found)
    assert all(f.status == "complies" for f in own(res))


def test_the_verdicts_are_those_of_the_143h_en_route_case(base):
    """§25.143(h) and §25.107(g)(2) judge the same turns (one computation): the same values per turn."""
    other = run_rule("25.143(h)")
    mine = {(f.condition.loading, f.condition.altitude, f.condition.get("turn")): f.value for f in warnings(base)}
    theirs = {
        (f.condition.loading, f.condition.altitude, f.condition.get("turn")): f.value
        for f in other.findings
        if f.condition.get("case") == "en route VFTO" and f.check.endswith("free of stall warning")
    }
    assert mine == theirs


def test_a_smaller_wing_loses_the_capability_at_the_same_vfto(tmp_path):
    """A deficient airplane: the wing (and reference area) 15 % smaller at the VFTO of 204 KCAS that gives the baseline
    the capability. The turn's C_L = n W/(q S) grows by 1/0.85 (1.234 → about 1.45, above the 1.270 onset): every turn
    is inside stall warning."""
    smaller = [
        ("  area: 4927.3 ft^2            # [given] wing reference area", "  area: 4188.2 ft^2"),
        ("    area: 4927.3 ft^2          # [given]", "    area: 4188.2 ft^2"),
        ("  VFTO: 198 kn CAS", "  VFTO: 204 kn CAS"),
    ]
    found = warnings(run_rule(RULE, tmp_path, smaller))
    assert len(found) == 12 and all(f.status == "fails" and f.value > 1.4 for f in found)


def test_without_vfto_nothing_is_judged(tmp_path):
    res = run_rule(RULE, tmp_path, [("  VFTO: 198 kn CAS", "  #VFTO: 198 kn CAS")])
    assert res.status == "not_evaluated" and all(f.status == "not_evaluated" for f in own(res))
    assert all("speeds.VFTO" in (f.reason or "") for f in own(res))
