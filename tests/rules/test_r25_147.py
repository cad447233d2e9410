"""§25.147(a), (c) directional and lateral control with the critical engine inoperative, checked by hand.

* Speed 1.3 VSR1 (14 CFR 25.147(a), (c)): VSR1 is the 1-g stall speed of the declared CLmax,
  V = √(2W / (ρ0 S CLmax)) (Anderson, *Introduction to Flight*, eq. 5.67), ρ0 = 0.0023769 slug/ft³,
  S = 4927.3 ft², 1 kn = 1.6878099 ft/s. (a): MLW 460,000 lb, approach CLmax 2.00 → VSR1 = 127.2 kn,
  1.3 VSR1 = 165.4 kn CAS; (c): MTOW 656,000 lb, clean CLmax 1.4 → VSR1 = 181.6 kn, 1.3 VSR1 = 236.1 kn CAS
  (tolerance 0.05 kn).
* Lift of the 20° coordinated turn (Anderson eq. 6.81 with the flight-path term): n = cos γ / cos 20°,
  CL/CLmax = n W / (q S CLmax) (tolerance 1e-3).
* Margin: the rudder design limit ±23.2° (aircraft file) − |δr| (deg), exact to 1e-9.
"""

import math

import pytest

from certkit.units import KN

from .helpers import run_rule

RUDDER = "design_limits: {min: -23.2 deg, max: 23.2 deg}"
RHO0, S, KT = 0.0023769, 4927.3, 1.6878099


def vs_kn(weight_lb, clmax):
    return math.sqrt(2 * weight_lb / (RHO0 * S * clmax)) / KT


@pytest.fixture(scope="module")
def base():
    return {rid: run_rule(rid) for rid in ("25.147(a)", "25.147(c)")}


def control(result, loading, name, turn=None):
    return next(
        f
        for f in result.findings
        if f.condition.loading == loading
        and f.check.endswith(f"{name} within design limit")
        and (turn is None or f.condition.get("turn") == turn)
    )


def test_hand_calculation_speed_lift_and_margin(base):
    a = control(base["25.147(a)"], "MLW aft", "rudder")
    assert a.condition.speed / KN == pytest.approx(1.3 * vs_kn(460_000, 2.00), abs=0.05)
    assert a.details["bank_deg"] == pytest.approx(0.0, abs=1e-9) and a.details["flight_path_deg"] == 0.0
    assert a.details["thrust_level_flight_N"] < a.details["thrust_mct_N"]  # level flight within MCT: γ = 0
    assert a.margin == pytest.approx(23.2 - abs(a.value), abs=1e-9) and a.status == "complies"
    c = control(base["25.147(c)"], "MTOW aft", "rudder", "toward the inoperative engine")
    v = 1.3 * vs_kn(656_000, 1.4)
    assert c.condition.speed / KN == pytest.approx(v, abs=0.05)
    n = math.cos(math.radians(c.details["flight_path_deg"])) / math.cos(math.radians(20))
    q = 0.5 * RHO0 * (v * KT) ** 2
    assert abs(c.details["bank_deg"]) == pytest.approx(20.0, abs=1e-6) and c.details["beta_deg"] == pytest.approx(
        0, abs=1e-6
    )
    # the clean C_Lmax at the condition's Mach on the declared table (1.400 at M 0.2, 1.370 at 0.4), a0 = 1,116.45 ft/s
    clmax = 1.4 - 0.03 * (v * KT / 1116.45 - 0.2) / 0.2
    assert c.details["CL_over_CLmax"] == pytest.approx(n * 656_000 / (q * S * clmax), abs=1e-3)
    assert c.margin == pytest.approx(23.2 - abs(c.value), abs=1e-9)
    assert all(f.status != "fails" for r in base.values() for f in r.findings)


def test_a_smaller_rudder_design_limit_fails_and_does_not_change_the_trim(base, tmp_path):
    """A deficient airplane: the rudder's design limit cut to ±12° (the wings-level trims need about 19°): every CG
    fails, with the same trim (the limit does not change it) and the margin 12° − |δr|."""
    ref = control(base["25.147(a)"], "MLW reference", "rudder")
    assert abs(ref.value) > 12.0
    edited = run_rule("25.147(a)", tmp_path, [(RUDDER, "design_limits: {min: -12 deg, max: 12 deg}")])
    for loading in ("MLW forward", "MLW reference", "MLW aft"):
        f = control(edited, loading, "rudder")
        assert f.status == "fails" and f.value == pytest.approx(
            control(base["25.147(a)"], loading, "rudder").value, abs=1e-6
        )


def test_sign_turn_away_from_the_dead_engine_needs_more_rudder(base):
    """Turning away from the inoperative engine, the yaw rate adds to the rudder that holds the asymmetric
    thrust; toward it, the turn's yaw rate helps: less rudder margin away from the dead engine."""
    for loading in ("MTOW forward", "MTOW reference", "MTOW aft"):
        toward = control(base["25.147(c)"], loading, "rudder", "toward the inoperative engine")
        away = control(base["25.147(c)"], loading, "rudder", "away from the inoperative engine")
        assert math.copysign(1, toward.value) == math.copysign(1, away.value)
        assert away.margin < toward.margin


def test_not_evaluated_without_clmax(tmp_path):
    result = run_rule("25.147(a)", tmp_path, [("    CLmax: 2.00\n", "")])
    trims = [f for f in result.findings if f.check.startswith("(a) wings-level")]
    assert len(trims) == 3 and all(f.status == "not_evaluated" and "CLmax" in f.reason for f in trims)
    assert not [f for f in result.findings if "within design limit" in f.check]
