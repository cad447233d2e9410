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

from .helpers import run_rule

RULE = "25.177"


@pytest.fixture(scope="module")
def result():
    return run_rule(RULE)


def _at(result, loading, configuration, point, check_start, altitude=0.0):
    return next(f for f in result.findings if f.condition.loading == loading and f.condition.configuration == configuration
                and f.condition.get("speed_point") == point and f.condition.altitude == altitude and f.check.startswith(check_start))


def test_hand_calculation_sideslip_and_cn_beta(result, ctx):
    """fwd_light (92.04 ft), takeoff, sea level, 1.13 VSR: Cn_β about the CG and the 10° sideslip deflections."""
    cn = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(a)")
    rud = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(c) 10° steady-heading sideslip: rudder within")
    ail = _at(result, "fwd_light", "takeoff", "1.13 VSR", "(c) 10° steady-heading sideslip: aileron within")
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
    beta = math.radians(10.0)
    det = cn_a * cl_r - cn_r * cl_a
    da = (-cn_beta * beta * cl_r + cl_b * beta * cn_r) / det
    dr = (-cl_b * beta * cn_a + cn_beta * beta * cl_a) / det
    assert rud.details["deflection_deg"] == pytest.approx(math.degrees(dr), rel=0.05)
    assert ail.details["deflection_deg"] == pytest.approx(math.degrees(da), rel=0.05)
    assert rud.margin == pytest.approx(23.2 - abs(math.degrees(dr)), abs=0.05 * abs(math.degrees(dr)))
    # stable sense: rudder trailing edge left (+) and right aileron up (−) for wind from the right
    assert dr > 0 and da < 0


def test_rudder_design_limit_on_the_limit(result, tmp_path):
    """Design rudder limit set to the largest rudder the baseline's sideslips need: smallest rudder margin 0."""
    rudder = [f for f in result.findings if "rudder within" in f.check and f.value is not None]
    need = max(f.value for f in rudder)
    limit = f"{need:.6f}"
    r = run_rule(RULE, tmp_path, edits=[("design_limits: {min: -23.2 deg, max: 23.2 deg}",
                                         f"design_limits: {{min: -{limit} deg, max: {limit} deg}}")])
    edited = [f for f in r.findings if "rudder within" in f.check and f.margin is not None]
    assert min(f.margin for f in edited) == pytest.approx(0.0, abs=1e-4)


def test_sign_larger_fin_raises_directional_margin(result, tmp_path):
    """A 30 % larger vertical tail raises Cn_β at the critical (aft) corner."""
    before = min(f.margin for f in result.findings if f.check.startswith("(a) Cn"))
    r = run_rule(RULE, tmp_path, edits=[("area: 527.84 ft^2", "area: 686.2 ft^2")])
    after = min(f.margin for f in r.findings if f.check.startswith("(a) Cn"))
    assert after > before + 0.003


def test_not_evaluated_without_clean_clmax(tmp_path):
    r = run_rule(RULE, tmp_path, edits=[("    CLmax: 1.4                 # [given]\n", "")])
    assert r.status == "not_evaluated"
    assert r.findings[0].reason == "needs configurations.clean.CLmax"


def test_baseline_complies_and_aft_corner_is_critical(result):
    assert result.status == "complies"
    crit = result.critical
    assert crit.condition.loading.startswith("aft") and crit.check.startswith("(a) Cn")
    assert np.isfinite(crit.margin) and crit.condition.x_cg > 100 * FT
