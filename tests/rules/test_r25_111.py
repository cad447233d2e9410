"""§25.111 takeoff path (simulated, all engines) against hand numbers in the paragraph's units.

Hand references: at brake release the runway acceleration is g · 2 T_static/W
= 32.174 ft/s² × 2 × 97,300 lbf / 656,000 lb = 9.544 ft/s² (2.909 m/s²; thrust line along the body
axis, no aerodynamic force at rest, and no rolling resistance yet: the ground model's tyre friction
μ N tanh(v/0.3 m/s) builds up over the first 0.3 m/s of the roll);
V2 = 161 KCAS is the (c)(2) limit; VR = 155 KCAS the rotation speed.
"""

import pytest

from certkit.units import FT

from .helpers import finding_by as _by
from .helpers import run_rule

GEAR = ("    main: {x: 107.0 ft, y: 18.0 ft, z: -18.5 ft}   # main gear track 36 ft, wheelbase 84.9 ft [b777-apd]\n"
        "    nose: {x: 22.1 ft, y: 0 ft, z: -18.5 ft}\n")


@pytest.fixture(scope="module")
def result():
    return run_rule("25.111")


def test_hand_calculation_initial_acceleration_and_v2_limit(result):
    """Initial acceleration 9.544 ft/s² within 0.5 %; the (c)(2) limit is V2 = 161 kn; lift-off after VR."""
    for loading in ("MTOW forward", "MTOW reference", "MTOW aft"):
        f = _by(result, loading, "(c)(2)")
        assert f.details["initial_acceleration_m_s2"] / FT == pytest.approx(32.174 * 2 * 97300 / 656000, rel=5e-3)
        assert f.limit == pytest.approx(161.0, abs=1e-6) and f.unit == "kn"
        assert f.details["vlof_kn"] > 155.0 and f.value > f.details["vlof_kn"]
        assert 3000 < f.details["distance_to_35ft_ft"] < 12000
    assert result.status == "complies"


def test_on_the_limit_when_the_design_limit_equals_the_extreme_elevator(result, tmp_path):
    """With the elevator's design limit set to the forward-CG run's extreme elevator, that margin is 0."""
    fwd = _by(result, "MTOW forward", "(b)")
    edited = run_rule("25.111", tmp_path, [("design_limits: {min: -21.8 deg, max: 16.8 deg}",
                                            f"design_limits: {{min: {fwd.value:.5f} deg, max: 16.8 deg}}")])
    f = _by(edited, "MTOW forward", "(b)")
    assert f.margin == pytest.approx(0.0, abs=1e-4)


def test_sign_aft_cg_needs_less_nose_up_elevator(result):
    """Moving the CG aft shortens the tail's lever against the weight on the mains: the elevator margin grows
    forward → reference → aft, and the lighter rotation moment lifts off earlier (lower V at 35 ft)."""
    m = [_by(result, c, "(b)").margin for c in ("MTOW forward", "MTOW reference", "MTOW aft")]
    assert m[0] < m[1] < m[2]
    v = [_by(result, c, "(c)(2)").value for c in ("MTOW forward", "MTOW reference", "MTOW aft")]
    assert v[0] > v[1] > v[2]


def test_not_evaluated_without_landing_gear(tmp_path):
    r = run_rule("25.111", tmp_path, [(GEAR, "")])
    assert r.status == "not_evaluated"
    assert all(f.status == "not_evaluated" and "landing_gear" in f.reason for f in r.findings)
