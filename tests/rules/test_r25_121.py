"""§25.121 one-engine-inoperative climb, checked by hand where the path is independent of certkit:

* thrust available, Mattingly (*Aircraft Engine Design*, 2nd ed., §2.3) lapse of the parametric engine at
  sea level: θ0 = 1 + 0.2 M², δ0 = θ0^3.5, T = 97,300 lbf · δ0 (1 − 0.49 √M − 3 (θ0 − 1)/(1.5 + M))
  (θ0 above the throttle ratio 1), M = V/a0, a0 = 340.294 m/s;
* the energy relation sin γ = (T − D)/W (Anderson, *Aircraft Performance and Design*, eq. 5.12), with the
  drag D read as the thrust the level OEI trim needs (zero sideslip) — the rule trims at the gradient, so
  the two agree to the change of induced drag with cos γ (tolerance 0.0015 in gradient);
* the gear-up credit ΔCD0 = 0.012 − 0.0074·0.30·0.60·(15 − 10) = 0.00534 (Raymer eq. 12.61 flap part
  removed from the declared takeoff increment), drag credit ΔCD0 · ½ρ0V²S.
"""

import math

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.units import KN, LB, LBF

from ..conftest import BASELINE
from .helpers import own, run_rule

G = 9.80665
S_M2 = 4927.3 * 0.3048**2


def mattingly_thrust_n(v_ms):
    m = v_ms / 340.294
    theta0 = 1 + 0.2 * m * m  # > TR = 1 (flat-rated to ISA sea level): the hot-day branch applies
    return 97_300 * LBF * theta0**3.5 * (1 - 0.49 * math.sqrt(m) - 3 * (theta0 - 1) / (1.5 + m))


@pytest.fixture(scope="module")
def base_b():
    return run_rule("25.121(b)")


def gradient(result, loading="MTOW reference"):
    return next(f for f in own(result) if f.unit == "gradient" and f.condition.loading == loading)


def test_hand_calculation_thrust_gear_credit_and_energy_method(base_b):
    """(b) at V2 = 161 kn, MTOW 656,000 lb, reference CG: T_avail by hand (one engine), credit by hand, and
    γ ≈ (T_avail − T_level + ΔD_gear)/W from an independent level (γ = 0) OEI trim."""
    f = gradient(base_b)
    v = 161 * KN
    assert f.details["thrust_available_N"] == pytest.approx(mattingly_thrust_n(v), rel=1e-4)
    credit = (0.012 - 0.0074 * 0.30 * 0.60 * 5) * 0.5 * 1.225 * v**2 * S_M2
    assert f.details["gear_drag_credit_N"] == pytest.approx(credit, rel=1e-3)
    ctx = Context(load_aircraft(BASELINE))
    level = ctx.trim([f.condition], kind="sideslip", beta=0.0, gamma=0.0, inoperative="left").results[0]
    assert level.converged
    w = 656_000 * LB * G
    hand = (mattingly_thrust_n(v) - level.thrust["right"] + credit) / w
    assert f.value == pytest.approx(hand, abs=0.0015)
    assert f.details["throttle:right"] == pytest.approx(1.0, abs=1e-3)  # the trim is at the available thrust
    assert abs(f.details["gradient_residual"]) < 1e-4


def test_too_little_thrust_fails(tmp_path, base_b):
    """A deficient airplane: 20 % less static thrust (77,840 lbf) lowers the (b) gradient by about
    0.2·T_avail/W ≈ 0.023 (hand, as below), from +0.0278 to about +0.005, under the 2.4 % minimum: fails."""
    weak = run_rule("25.121(b)", tmp_path, [("static_thrust: 97300 lbf", "static_thrust: 77840 lbf")])
    d = gradient(base_b).value - gradient(weak).value
    assert d == pytest.approx(0.2 * mattingly_thrust_n(161 * KN) / (656_000 * LB * G), rel=0.1)
    assert gradient(weak).status == "fails" and gradient(weak).value < 0.024


def test_sign_more_thrust_more_gradient_and_rudder_margin(tmp_path, base_b):
    """10 % more static thrust raises the gradient by about ΔT/W ≈ 0.0114 (hand: 0.1·T_avail/W)."""
    more = run_rule("25.121(b)", tmp_path, [("static_thrust: 97300 lbf", "static_thrust: 107030 lbf")])
    d = gradient(more).value - gradient(base_b).value
    assert d == pytest.approx(0.1 * mattingly_thrust_n(161 * KN) / (656_000 * LB * G), rel=0.1)
    rud = lambda r: next(  # noqa: E731
        f for f in own(r) if f.check.endswith("rudder within design limit") and f.condition.loading == "MTOW reference"
    )
    assert rud(more).margin < rud(base_b).margin  # more asymmetric thrust needs more rudder


def test_not_evaluated_without_v2_and_positive_gradient_in_a(tmp_path):
    r = run_rule("25.121(b)", tmp_path, [("  V2: 161 kn CAS ", "  # V2: 161 kn CAS ")])
    assert r.status == "not_evaluated" and own(r)[0].reason == "needs speeds.V2"
    a = run_rule("25.121(a)")
    f = gradient(a)
    assert f.condition.speed_name == "VR" and "VLOF not declared" in f.reason and f.limit == 0.0


def test_a_climb_below_the_stall_speed_fails_instead_of_going_unevaluated(tmp_path):
    """VR, V1 and V2 declared 15 kn low (140, 135 and 146 kn CAS): at MTOW and VR the takeoff configuration's 1-g lift
    needs CL 1.98 against its CLmax 1.95 (VSR about 142 kn EAS), so no steady climb exists there and the engine-out
    trim cannot converge. Each such condition fails 'steady flight within CLmax' on the least lift any steady flight
    at that speed and weight needs; its gradient stays unevaluated (there is none to read)."""
    low = [("  V1: 150 kn CAS", "  V1: 135 kn CAS"), ("  VR: 155 kn CAS", "  VR: 140 kn CAS")]
    r = run_rule("25.121(a)", tmp_path, low + [("  V2: 161 kn CAS", "  V2: 146 kn CAS")])
    untrimmed = [f for f in own(r) if f.status == "not_evaluated" and "did not converge" in f.reason]
    lift = [f for f in own(r) if f.check.endswith("steady flight within CLmax")]
    assert untrimmed and len(lift) == len(untrimmed)
    assert all(f.status == "fails" and f.limit == pytest.approx(1.95) and 1.95 < f.value < 2.05 for f in lift)
    assert r.status == "fails"
    assert not any(f.check.endswith("steady flight within CLmax") for f in own(run_rule("25.121(a)")))
