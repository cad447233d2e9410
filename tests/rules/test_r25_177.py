"""§25.177 static lateral-directional stability.

Hand calculation: the steady-heading sideslip as the two linear moment equations of Etkin & Reid
(Dynamics of Flight, §6.x steady sideslip), Cn_β β + Cn_δa δa + Cn_δr δr = 0 and
Cl_β β + Cl_δa δa + Cl_δr δr = 0, about the CG, solved by Cramer's rule from the model's derivatives;
the yawing derivatives moved from the 97.25 ft reference point to the CG by CY·(x_cg − x_ref)/b with
x in feet and b = 208.35 ft. Tolerance 5 % (the trim adds the small side force of bank, thrust and the
non-zero roll/yaw cross terms the linear pair leaves out).
"""

import math

import numpy as np
import pytest

from certkit.units import FT

from .helpers import CN_MAX_TABLE, control_forces_edit, own, run_rule

RULE = "25.177"


@pytest.fixture(scope="module")
def result():
    return run_rule(RULE)


def _at(result, loading, configuration, point, check_start, altitude=0.0):
    return next(
        f
        for f in own(result)
        if f.condition.loading == loading
        and f.condition.configuration == configuration
        and f.condition.get("speed_point") == point
        and f.condition.altitude == altitude
        and f.check.startswith(check_start)
    )


def test_hand_calculation_sideslip_and_cn_beta(result, ctx):
    """fwd_light (92.04 ft), takeoff, sea level, 1.13 VSR: Cn_β about the CG and the deflections at the end of
    the (c) range, whose rudder is half the available 23.2° (the range is scaled from a 5° trim; 2 %)."""
    cn = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(a)")
    rud = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(c) steady sideslips: rudder within")
    ail = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(c) steady sideslips: aileron within")
    assert rud.details["range_bound"] == "half the available rudder"
    assert rud.details["deflection_deg"] == pytest.approx(0.5 * 23.2, rel=0.02)
    m = ctx.aero("takeoff").model
    cond = cn.condition
    mach = float(cond.speed / 340.294)  # CAS at sea level: Mach = V / a0
    d = lambda name: float(m.derivative(name, mach))  # noqa: E731
    arm = (92.04 - 97.25) / 208.35  # (x_cg − x_ref)/b, ft/ft
    cn_beta = d("Cn_beta") + d("CY_beta") * arm
    assert cn.value == pytest.approx(cn_beta, rel=1e-3)
    assert cn.status == "complies" and cn.margin == pytest.approx(cn_beta, rel=1e-3)
    cn_a, cn_r = d("Cn_aileron") + d("CY_aileron") * arm, d("Cn_rudder") + d("CY_rudder") * arm
    cl_a, cl_r, cl_b = d("Cl_aileron"), d("Cl_rudder"), d("Cl_beta")
    beta = math.radians(rud.details["sideslip_range_deg"])
    det = cn_a * cl_r - cn_r * cl_a
    da = (-cn_beta * beta * cl_r + cl_b * beta * cn_r) / det
    dr = (-cl_b * beta * cn_a + cn_beta * beta * cl_a) / det
    assert rud.details["deflection_deg"] == pytest.approx(math.degrees(dr), rel=0.05)
    assert ail.details["deflection_deg"] == pytest.approx(math.degrees(da), rel=0.05)
    assert rud.margin == pytest.approx(23.2 - abs(math.degrees(dr)), abs=0.05 * abs(math.degrees(dr)))
    # stable sense: rudder trailing edge left (+) and right aileron up (−) for wind from the right
    assert dr > 0 and da < 0


def test_an_aileron_too_small_for_the_sideslips_fails_at_every_point_it_cannot_hold(result, tmp_path):
    """The baseline's aileron with half its chord (8 % of the wing chord for 17 %): the (c) sideslips, whose range the
    rudder sets, need more aileron than its ±25° design limit at 80 points (27–35°), where the baseline stays inside
    it. Every sideslip earns its verdict: a trim that needs the aileron past its limit, or more thrust than the
    engines give, is judged where the airplane can fly it, never left unevaluated."""
    small = run_rule(RULE, tmp_path, edits=[("chord_ratio: 0.17      # [given]", "chord_ratio: 0.08")])
    assert all(f.status in ("complies", "fails") for f in own(small)), {f.reason for f in own(small)}
    over = [f for f in own(small) if "aileron within" in f.check and f.status == "fails"]
    assert len(over) >= 40 and all(f.value > 25.0 for f in over)
    assert all(f.status == "complies" for f in own(result) if "aileron within" in f.check)


def test_sideslips_beyond_the_level_flight_ceiling_are_flown_in_the_descent_at_full_thrust(result, tmp_path):
    """Where level flight in the sideslip needs more than full thrust (at 35,000 ft), the sideslip is flown in the
    steady descent at full thrust, its flight path in the finding's condition: shallow on the baseline (0.04–1.7°), and
    steeper with a fifth less thrust (to about 3°), where each sideslip is still judged."""
    descents = [f.condition.get("flight_path_deg") for f in own(result) if f.condition.get("flight_path_deg")]
    assert descents and all(-2.0 < d < 0.0 for d in descents)
    weak = run_rule(RULE, tmp_path, edits=[("  static_thrust: 97300 lbf", "  static_thrust: 77840 lbf")])
    assert all(f.status in ("complies", "fails") for f in own(weak)), {f.reason for f in own(weak)}
    steeper = [f.condition.get("flight_path_deg") for f in own(weak) if f.condition.get("flight_path_deg")]
    assert len(steeper) > len(descents) and min(steeper) < min(descents)


def test_sideslip_sweep_stable_and_beyond(result):
    """(c): four points to the range, every increment in the stable sense; (d): more rudder for more sideslip up to
    full rudder (the sweep reaches twice the range: 23.2° in the linear estimate) or full aileron."""
    steps = [f for f in own(result) if "at every step" in f.check]
    assert steps and all(len(f.details["gradients"]) == 4 and f.status == "complies" for f in steps)
    beyond = [f for f in own(result) if f.check.startswith("(d)")]
    assert beyond and all(f.status == "complies" for f in beyond)
    assert any(
        f.margin is not None and f.details["largest_sideslip_deg"] > f.details["sideslip_range_deg"] for f in beyond
    )


def test_pedal_force_bounds_the_range(tmp_path):
    """With a stiff q-feel rudder (F = 10 lbf + 200 lbf/in × q/10 kPa × δr / (6 °/in)) the 180 lbf bound is the
    lesser at VMO: its range ends where the pedal force is 180 lbf (the feel law by hand, 3 %)."""
    feel = (
        "control_forces:\n  rudder:\n    type: artificial_feel\n    preload: 10 lbf\n    gradient: 200 lbf/in\n"
        "    gearing: 6 deg/in\n    q_feel_reference: 10 kPa\n"
    )
    r = run_rule(RULE, tmp_path, edits=[control_forces_edit(feel)])
    bounded = [
        f for f in own(r) if "rudder within" in f.check and f.details.get("range_bound") == "180 lbf pedal force"
    ]
    assert bounded
    for f in bounded:
        v = f.condition.speed  # CAS, m/s; q from EAS ≈ CAS at these speeds only at sea level
        if f.condition.altitude:
            continue
        q_kpa = 0.5 * 1.225 * v**2 / 1e3
        force = 10 + 200 * q_kpa / 10 * abs(f.details["deflection_deg"]) / 6
        assert force == pytest.approx(180.0, rel=0.03)
    forces = [f for f in own(r) if f.check.startswith("(d) rudder force does not reverse")]
    assert forces and all(f.status in ("complies", "fails") for f in forces)


def test_sign_larger_fin_raises_directional_margin(result, tmp_path):
    """A 30 % larger vertical tail raises Cn_β at the critical (aft) corner."""
    before = min(f.margin for f in own(result) if f.check.startswith("(a) Cn"))
    r = run_rule(RULE, tmp_path, edits=[("area: 527.84 ft^2", "area: 686.2 ft^2")])
    after = min(f.margin for f in own(r) if f.check.startswith("(a) Cn"))
    assert after > before + 0.003


def test_not_evaluated_without_clean_clmax(tmp_path):
    r = run_rule(RULE, tmp_path, edits=[("    CLmax: 1.4                 # [given]\n", ""), (CN_MAX_TABLE, "")])
    assert r.status == "not_evaluated"
    assert own(r)[0].reason == "needs configurations.clean.CLmax"


def test_baseline_complies_and_aft_corner_is_critical(result):
    """What the rule computes on the baseline complies (rudder- and aileron-free stability are read controls fixed,
    so the rule complies in part); its critical check (normalised margin) lies at an aft corner — the directional
    stability Cn_β about the CG, or the aileron a flap configuration needs at the end of the (c) range — and the
    smallest directional-stability margin is aft."""
    assert result.status == "complies_partial" and all(f.status == "complies" for f in own(result))
    crit = result.critical
    assert crit.condition.loading.startswith("aft")
    assert crit.check.startswith("(a) Cn") or "aileron within" in crit.check
    cn = min((f for f in own(result) if f.check.startswith("(a) Cn")), key=lambda f: f.margin)
    assert cn.condition.loading.startswith("aft") and np.isfinite(cn.margin) and cn.condition.x_cg > 100 * FT


def test_vfc_point_checks_b2_not_b1(result):
    """Clean, at VFC (the least §25.253(b) allows on the baseline): (a) and (c) are checked as at the other speeds;
    the lateral stability there is (b)(2) (between VMO/MMO and VFC/MFC), not (b)(1); the extended configurations'
    VFC point is not applicable (their range ends at VFE/VLE)."""
    at_vfc = [f for f in own(result) if f.condition.get("speed_point") == "VFC"]
    clean = [f for f in at_vfc if f.condition.configuration == "clean"]
    assert any(f.check.startswith("(a)") for f in clean) and any(f.check.startswith("(c)") for f in clean)
    assert {f.check for f in clean if f.check.startswith("(b)")} == {"(b)(2) Cl_β < 0 between VMO/MMO and VFC/MFC"}
    assert all(f.condition.get("VFC") == "§25.253(b) least: (VMO + VD)/2" for f in clean)
    assert all(f.margin is None and f.status == "complies" for f in at_vfc if f.condition.configuration != "clean")
