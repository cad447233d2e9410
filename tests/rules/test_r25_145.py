"""§25.145(b) longitudinal control: elevator changes of flap and thrust changes against the remaining authority.

* Trim speeds 1.3 VSR with VSR = √(2W/(ρ0 S CLmax)) (Anderson, *Introduction to Flight*, eq. 6.47), ρ0 0.0023769
  slug/ft³, S 4927.3 ft²: fwd_mlw (460,000 lb) landing, CLmax 2.25: VSR = 110.54 kn, 1.3 VSR = 143.70 kn; clean,
  CLmax 1.4: 1.3 VSR1 = 182.18 kn (tolerance 0.01 kn).
* Idle glide by the energy relation sin γ = (T_idle − D)/W (Anderson, *Aircraft Performance and Design*, eq. 5.12)
  with D read as the thrust an independent level trim needs, T_idle two engines of the parametric turbofan (Mattingly
  lapse, see test_r25_121) at throttle 0.003: thrust idle fraction 0.05 + 0.95 · 0.003 (tolerance 0.002 rad, the
  induced-drag change with cos γ).
* Margin: authority left on the side of the change at the start, design limit −21.8°/+16.8° (aircraft file), minus
  |δe,end − δe,start|, i.e. the end elevator against the limit on that side.
"""

import math

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import evaluate_rule
from certkit.units import KN, LB

from ..conftest import BASELINE
from .helpers import own
from .test_r25_121 import mattingly_thrust_n
from .test_r25_143 import edited_context, evaluate_part, rule_class

G = 9.80665


@pytest.fixture(scope="module")
def shared145():
    return Context(load_aircraft(BASELINE))


@pytest.fixture(scope="module")
def base(shared145):
    return evaluate_rule(rule_class("25.145(b)"), shared145)


def finding(findings, loading, para, flap="landing"):
    findings = findings if isinstance(findings, list) else own(findings)
    return next(
        f
        for f in findings
        if f.condition.loading == loading
        and (f.condition.get("manoeuvre") or "").startswith(para)
        and (flap in f.condition.get("manoeuvre") or para == "(b)(4)")
    )


def test_hand_calculation_speeds_idle_glide_and_margin(base, shared145):
    f = finding(base, "fwd_mlw", "(b)(1)")  # clean, idle → landing flaps, idle
    vsr = lambda cl: math.sqrt(2 * 460_000 / (0.0023769 * 4927.3 * cl)) / 1.6878099  # noqa: E731
    assert f.condition.speed / KN == pytest.approx(1.3 * vsr(2.25), abs=0.01)
    assert f.details["start_speed_m_s"] / KN == pytest.approx(1.3 * vsr(1.4), abs=0.01)
    assert f.details["direction"] == "trailing edge up" and f.details["end_throttle:left"] == pytest.approx(
        0.003, abs=2e-4
    )
    assert f.margin == pytest.approx(f.details["end_elevator_deg"] + 21.8, abs=1e-3)
    assert f.value == pytest.approx(abs(f.details["end_elevator_deg"] - f.details["start_elevator_deg"]), abs=1e-3)
    level = shared145.trim([f.condition], kind="straight").results[0]
    v = f.condition.speed
    idle = 2 * mattingly_thrust_n(v) * (0.05 + 0.95 * 0.003)
    gamma = math.asin((idle - sum(level.thrust.values())) / (460_000 * LB * G))
    assert math.radians(f.details["end_flight_path_deg"]) == pytest.approx(gamma, abs=0.002)


def test_sign_more_flap_more_nose_up_and_thrust_below_cg_needs_nose_down(base):
    """At forward CG, extending the flaps further needs more trailing-edge-up elevator (the flap's nose-down
    moment); setting go-around thrust needs trailing-edge-down elevator at every corner (thrust line 9 ft below
    the fuselage axis, near the CG: a nose-up moment)."""
    ext = [finding(base, "fwd_mrw", "(b)(1)", flap) for flap in ("takeoff", "approach", "landing")]
    assert all(f.details["direction"] == "trailing edge up" for f in ext)
    assert ext[0].value < ext[1].value < ext[2].value and ext[0].margin > ext[1].margin > ext[2].margin
    corners = {f.condition.loading for f in own(base)}
    for loading in corners:
        assert finding(base, loading, "(b)(4)").details["direction"] == "trailing edge down"


def test_not_evaluated_force_and_missing_stall_speed(tmp_path, base):
    forces = [f for f in own(base) if "lbf" in f.check]
    assert len(forces) == 8 and all(f.status == "not_evaluated" and "control-force model" in f.reason for f in forces)
    ctx = edited_context(tmp_path, [("    CLmax: 2.25 ", "    # CLmax: 2.25 ")])
    r = evaluate_part("25.145(b)", ctx, lambda c: c.loading == "fwd_mlw")
    g = finding(r, "fwd_mlw", "(b)(1)")
    assert g.status == "not_evaluated" and g.reason == "needs configurations.landing.CLmax (or speeds.VSR.landing)"
    assert finding(r, "fwd_mlw", "(b)(1)", "takeoff").margin is not None
