"""§25.335 design airspeeds against hand calculations in the paragraph's own units (lb, ft, slug, kn).

Independent of certkit's SI path: ρ₀ = 0.0023769 slug/ft³, g = 32.174 ft/s², 1 kn = 1.68781 ft/s,
and the paragraph's dimensional constant 498 in (d)(1). Tolerances state the rounding of 498 (0.1 %).
§25.335(c)/(d) say estimated stall speeds must be conservative: C_Nmax = C_Lmax (factor 1) unless the aircraft
file justifies more, so the stall line of the hand calculations below uses CLmax 1.40 itself.
"""

import math

import pytest

from certkit.units import KN

from .helpers import CONSTANT_CN_MAX, VA_SCHEDULE, run_rule

RHO0_SLUG, G_FT, KT_FT = 0.0023769, 32.174, 1.6878099
S_FT2, CLMAX = 4927.3, 1.4
SPAN_FT = 208.35


def constant(rule_id, tmp_path, edits=()):
    """``rule_id`` on the baseline with the low-speed C_N,max at every Mach number and its single VA 266 / VB 226 KEAS
    (the closed-form envelope of these hand calculations; the declared C_Lmax(M) and the VA/VB schedules:
    tests/loads/test_vn_envelope_mach.py)."""
    return run_rule(rule_id, tmp_path, CONSTANT_CN_MAX + list(edits))


def vs1_kn(w_lb, cn_over_cl=1.0):
    return math.sqrt(2 * w_lb / (RHO0_SLUG * S_FT2 * cn_over_cl * CLMAX)) / KT_FT


def by_mass(result, lb, altitude_m=0.0):
    return next(
        f for f in result.findings if abs(f.condition.mass / 0.45359237 - lb) < 1 and f.condition.altitude == altitude_m
    )


def test_va_hand_calculation(tmp_path):
    """(c): VA ≥ min(VS1·√2.5, VC), VS1 = √(2W/(ρ₀ S CLmax)) at 657,000 lb (MRW) with C_Nmax = CLmax = 1.40:
    VS1 = 167.73 kn, VS1·√2.5 = 265.20 kn (below VC 272); declared VA 266 KEAS → margin +0.80 kn."""
    assert vs1_kn(657_000) == pytest.approx(167.73, abs=0.01)
    r = constant("25.335(c)", tmp_path)
    f = by_mass(r, 657_000)
    assert f.limit / KN == pytest.approx(265.20, abs=0.01)
    assert f.margin / KN == pytest.approx(266.0 - 265.20, abs=0.02)
    assert r.status == "complies"


def test_va_at_265_fails_by_the_conservative_stall(tmp_path):
    """The baseline's former VA, 265 KEAS (VS1·√2.5 at MTOW), is 0.20 kn below the MRW minimum: fails."""
    r = constant("25.335(c)", tmp_path, [("  VA: 266 kn EAS", "  VA: 265 kn EAS")])
    assert r.status == "fails" and r.critical.margin / KN == pytest.approx(-0.20, abs=0.02)


def test_justified_cn_factor_override(tmp_path):
    """A declared C_Nmax/C_Lmax of 1.1 with its justification lowers the (c) minimum to 167.73/√1.1·√2.5 = 252.86 kn;
    the override and its justification travel with the result (the report prints them)."""
    why = "wind-tunnel C_N,max of the clean wing, test report X-123 (illustrative)"
    override = f'criteria:\n  "25.335(c)":\n    values: {{cn_over_cl: 1.1}}\n    justification: "{why}"\n'
    r = constant("25.335(c)", tmp_path, [("\nsources:\n", "\n" + override + "sources:\n")])
    f = by_mass(r, 657_000)
    assert f.limit / KN == pytest.approx(252.86, abs=0.01)
    assert r.overrides["cn_over_cl"] == {"default": 1.0, "value": 1.1, "unit": "", "justification": why}


def test_vb_hand_calculation_with_the_498_formula(tmp_path):
    """(d)(1): VB ≥ VS1·[1 + Kg Uref Vc a/(498 w)]^½, Kg = 0.88μ/(5.3+μ), μ = 2w/(ρ c a g), at sea level, 657,000 lb."""
    r = constant("25.335(d)", tmp_path)
    f = by_mass(r, 657_000)
    a = f.details["lift_slope"]
    w = 657_000 / S_FT2
    c = S_FT2 / SPAN_FT
    mu = 2 * w / (RHO0_SLUG * c * a * G_FT)
    kg = 0.88 * mu / (5.3 + mu)
    ng = 1 + kg * 56.0 * 272.0 * a / (498 * w)
    assert f.details["mu"] == pytest.approx(mu, rel=2e-3)
    assert f.limit / KN == pytest.approx(vs1_kn(657_000) * math.sqrt(ng), rel=1e-3)
    # with the model's lift slope this is 225.1 kn: the former declared VB of 222 KEAS was 3.1 kn short
    assert f.limit / KN == pytest.approx(225.1, abs=0.1) and f.margin / KN == pytest.approx(226 - 225.1, abs=0.1)
    # the lift slope is the DATCOM value for AR 8.81 at the Mach of 272 KEAS at sea level (M 0.411)
    assert 4.0 < a < 5.5


def test_vc_hand_calculation():
    """(a)(2) at sea level: VC − (VB + 1.32·56 ft/s) = 272 − (227 + 43.80) = 1.20 kn (VB's schedule starts at 227
    KEAS)."""
    r = run_rule("25.335(a)")
    f = next(f for f in r.findings if f.condition.altitude == 0.0)
    assert f.margin / KN == pytest.approx(1.20, abs=0.01)
    high = next(f for f in r.findings if f.condition.altitude > 12000)
    assert high.reason.startswith("not applicable") and high.margin is None


def test_vd_on_the_limit_and_sign(tmp_path):
    """(b): VD = 340 = VC/0.8 exactly -> margin 0 complies; a higher VC fails; a higher VD adds margin."""
    r = run_rule("25.335(b)")
    sea = next(f for f in r.findings if f.condition.altitude == 0.0)
    assert sea.status == "complies" and sea.margin == pytest.approx(0.0, abs=1e-9)
    worse = run_rule("25.335(b)", tmp_path, [("VC: 272 kn EAS", "VC: 280 kn EAS")])
    assert worse.status == "fails"
    better = run_rule("25.335(b)", tmp_path, [("VD: 340 kn EAS", "VD: 350 kn EAS")])
    assert better.critical.margin > sea.margin


def test_mach_margin_route_at_ceiling():
    """(b)(2) at 43,000 ft both speeds are Mach-limited: MD − MC = 0.94 − 0.87 = 0.07 ≥ 0.07."""
    r = run_rule("25.335(b)")
    top = max((f for f in r.findings if f.condition.altitude is not None), key=lambda f: f.condition.altitude)
    assert top.unit == "Mach" and top.value == pytest.approx(0.07, abs=1e-9)


def test_sign_more_clmax_lowers_required_va(tmp_path):
    base = constant("25.335(c)", tmp_path).critical.margin
    more = constant("25.335(c)", tmp_path, [("CLmax: 1.4 ", "CLmax: 1.6 ")]).critical.margin
    assert more > base


def test_not_evaluated_without_va(tmp_path):
    r = run_rule("25.335(c)", tmp_path, [(VA_SCHEDULE, "  # VA removed\n")])
    assert r.status == "not_evaluated" and r.headline_reason == "needs speeds.VA"
