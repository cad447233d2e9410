"""§25.103 reference stall speed against hand calculations in the paragraph's units (lb, ft, slug, kn).

VS = √(2W / (ρ₀ S CLmax)), ρ₀ = 0.0023769 slug/ft³, S = 4927.3 ft², 1 kn = 1.6878099 ft/s (Anderson,
*Introduction to Flight*, 8th ed., eq. 6.47 with L = W at CLmax). Tolerance 0.01 kn (ρ₀ rounding).
"""

import math

import pytest

from certkit.units import KN

from .helpers import run_rule

RHO0_SLUG, KT_FT, S_FT2 = 0.0023769, 1.6878099, 4927.3


def vs_kn(w_lb, clmax):
    return math.sqrt(2 * w_lb / (RHO0_SLUG * S_FT2 * clmax)) / KT_FT


def finding(result, configuration, lb=None):
    return next(
        f
        for f in result.findings
        if f.condition.configuration == configuration and (lb is None or abs(f.condition.mass / 0.45359237 - lb) < 1)
    )


def test_hand_calculation_takeoff_and_landing():
    """Takeoff at MTOW 656,000 lb, CLmax 1.95: 142.01 kn; landing at MLW 460,000 lb, CLmax 2.25: 110.71 kn;
    clean at 310,000 lb (lightest envelope weight), CLmax 1.4: 115.21 kn. The baseline declares no VSR: there is
    nothing to compare the 1-g stall speed with, so each finding is not_evaluated (no margin, never "complies")
    and carries the computed speed, and so is the rule."""
    r = run_rule("25.103")
    assert finding(r, "takeoff").value / KN == pytest.approx(vs_kn(656_000, 1.95), abs=0.01)
    assert finding(r, "landing").value / KN == pytest.approx(vs_kn(460_000, 2.25), abs=0.01)
    assert finding(r, "clean", 310_000).value / KN == pytest.approx(vs_kn(310_000, 1.4), abs=0.01)
    own = [f for f in r.findings if f.check.startswith("(a)")]
    assert own and all(
        f.status == "not_evaluated" and f.margin is None and "no declared speeds.VSR" in f.reason for f in own
    )
    assert r.status == "not_evaluated" and r.critical is None


def test_declared_vsr_on_the_limit(tmp_path):
    """A declared VSR equal to the hand value (142.01 kn CAS) sits on the limit: margin 0 ± 0.01 kn."""
    v = vs_kn(656_000, 1.95)
    r = run_rule("25.103", tmp_path, [("speeds:\n", f"speeds:\n  VSR: {{takeoff: {v:.4f} kn CAS}}\n")])
    f = finding(r, "takeoff")
    assert f.margin / KN == pytest.approx(0.0, abs=0.01) and "declared" in f.details["VSR_source"]


def test_sign_declared_below_fails_above_complies(tmp_path):
    """A declared VSR 2 kn below the 1-g stall speed fails by −2 kn; 2 kn above complies by +2 kn."""
    v = vs_kn(656_000, 1.95)
    low = run_rule("25.103", tmp_path, [("speeds:\n", f"speeds:\n  VSR: {{takeoff: {v - 2:.4f} kn CAS}}\n")])
    assert low.status == "fails" and finding(low, "takeoff").margin / KN == pytest.approx(-2.0, abs=0.01)
    high = run_rule("25.103", tmp_path, [("speeds:\n", f"speeds:\n  VSR: {{takeoff: {v + 2:.4f} kn CAS}}\n")])
    assert finding(high, "takeoff").margin / KN == pytest.approx(2.0, abs=0.01)


def test_not_evaluated_without_clmax(tmp_path):
    r = run_rule("25.103", tmp_path, [("CLmax: 1.95 ", "# CLmax: 1.95 ")])
    f = finding(r, "takeoff")
    assert f.status == "not_evaluated" and f.reason == "needs configurations.takeoff.CLmax"
    assert r.status == "not_evaluated"
