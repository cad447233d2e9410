"""§25.161 longitudinal trim: the segments' speeds by hand, the margin arithmetic, limit and sign cases.

Climb speed 1.3 VSR1 with VSR1 = √(2W/(ρ0 S CLmax)) (Anderson, *Introduction to Flight*, eq. 6.47):
at fwd_mrw, 657,000 lb, CLmax 1.4, S 4927.3 ft², ρ0 0.0023769 slug/ft³: VSR1 = 167.73 kn, 1.3 VSR1 = 218.05 kn
(tolerance 0.01 kn). The margin is the design limit on the deflected side minus |δe| (deg): elevator design
limits −21.8°/+16.8° (aircraft file).
"""

import math

import pytest

from certkit.units import KN

from .helpers import run_rule


@pytest.fixture(scope="module")
def base():
    return run_rule("25.161")


def finding(result, loading, segment):
    return next(f for f in result.findings if f.condition.loading == loading and f.condition.get("segment") == segment
                and f.margin is not None)


def test_hand_calculation_climb_speed_and_margin(base):
    f = finding(base, "fwd_mrw", "climb")
    vsr1 = math.sqrt(2 * 657_000 / (0.0023769 * 4927.3 * 1.4)) / 1.6878099
    assert f.condition.speed / KN == pytest.approx(1.3 * vsr1, abs=0.01)
    limit = 16.8 if f.value >= 0 else -21.8
    assert f.margin == pytest.approx(abs(limit) - abs(f.value), abs=1e-9)
    assert f.details["elevator_deg"] == pytest.approx(f.value, abs=1e-3)


def test_on_the_limit(tmp_path, base):
    """Elevator-down design limit set to the aft_light climb trim elevator: that finding's margin is 0."""
    f = finding(base, "aft_light", "climb")
    assert f.value > 0
    r = run_rule("25.161", tmp_path, [("design_limits: {min: -21.8 deg, max: 16.8 deg}",
                                       f"design_limits: {{min: -21.8 deg, max: {f.value:.9f} deg}}")])
    g = finding(r, "aft_light", "climb")
    assert g.margin == pytest.approx(0.0, abs=1e-6)


def test_sign_larger_design_limit_more_margin_and_aft_cg_more_trailing_edge_down(tmp_path, base):
    r = run_rule("25.161", tmp_path, [("design_limits: {min: -21.8 deg, max: 16.8 deg}",
                                       "design_limits: {min: -21.8 deg, max: 18.8 deg}")])
    assert finding(r, "aft_light", "climb").margin == pytest.approx(finding(base, "aft_light", "climb").margin + 2, abs=1e-6)
    # aft CG needs less nose-up (more trailing-edge-down) elevator than forward CG at the same weight
    assert finding(base, "aft_mrw", "climb").value > finding(base, "fwd_mrw", "climb").value


def test_not_evaluated_without_vc(tmp_path):
    r = run_rule("25.161", tmp_path, [("  VC: 272 kn EAS ", "  # VC: 272 kn EAS ")])
    assert r.status == "not_evaluated" and r.findings[0].reason == "needs speeds.VC"
