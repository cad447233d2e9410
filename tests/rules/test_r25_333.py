"""§25.333 V–n envelope corners against hand calculation (n W = ½ ρ₀ V² S C_N), C_N = ±C_Lmax (factor 1: §25.335
estimated stall speeds must be conservative), in the paragraph's units (lb, ft, slug, kn)."""

import math

import pytest

from certkit.units import KN

from .helpers import CONSTANT_CN_MAX, run_rule
from .test_r25_335 import KT_FT, RHO0_SLUG, S_FT2


def test_corners_hand_calculation(tmp_path):
    """310,000 lb, sea level, the low-speed C_N,max at every Mach number: +stall VS = √(2W/(ρ₀ S 1.40)) = 115.21 kn,
    A = VS·√2.5 = 182.17 kn; −stall with CLmin −0.80: 152.41 kn, H = that × √1 = 152.41 kn; D = (VD 340, 2.5),
    E = (340, 0), F = (VC 272, −1). (With the declared C_Lmax(M) — 1.400 at M 0.2, 1.370 at 0.4 — A is where the
    stall line at its own Mach number reaches 2.5: 182.92 kn, M 0.277, C_Lmax 1.389, by fixed point.)"""
    r = run_rule("25.333", tmp_path, CONSTANT_CN_MAX)
    declared = run_rule("25.333")
    a = next(
        f
        for f in declared.findings
        if f.check.startswith("A") and f.condition.altitude == 0.0 and abs(f.condition.mass / 0.45359237 - 310_000) < 1
    )
    v = 182.17
    for _ in range(30):
        cl = 1.4 - 0.03 * (v * 0.514444 / 340.294 - 0.2) / 0.2
        v = 182.17 * math.sqrt(1.4 / cl)
    assert v == pytest.approx(182.92, abs=0.01)
    assert a.details["corners"]["A"][0] / KN == pytest.approx(v, abs=0.01)
    f = next(
        f
        for f in r.findings
        if f.check.startswith("A") and f.condition.altitude == 0.0 and abs(f.condition.mass / 0.45359237 - 310_000) < 1
    )
    assert math.sqrt(2 * 310_000 / (RHO0_SLUG * S_FT2 * 1.4)) / KT_FT == pytest.approx(115.21, abs=0.01)
    corners = f.details["corners"]
    assert corners["A"][0] / KN == pytest.approx(182.17, abs=0.01) and corners["A"][1] == 2.5
    assert corners["H"][0] / KN == pytest.approx(152.41, abs=0.01) and corners["H"][1] == -1.0
    assert corners["D"] == [pytest.approx(340 * KN, rel=1e-4), 2.5]
    assert corners["E"][1] == 0.0 and corners["F"] == [pytest.approx(272 * KN, rel=1e-4), -1.0]
    assert r.status == "complies_partial"  # (a), strength on the envelope, is the loads rules'


def test_corner_a_at_mrw_against_the_declared_va(tmp_path):
    """657,000 lb, the low-speed C_N,max at every Mach number (the baseline before its C_Lmax(M) and VA schedule):
    A = √(2W/(ρ₀ S 1.40))·√2.5 = 265.20 kn; VA 266 closes the envelope (+0.80 kn), 265 does not."""
    r = run_rule("25.333", tmp_path, CONSTANT_CN_MAX)
    f = next(
        f
        for f in r.findings
        if f.check.startswith("A") and f.condition.altitude == 0.0 and abs(f.condition.mass / 0.45359237 - 657_000) < 1
    )
    assert f.details["corners"]["A"][0] / KN == pytest.approx(265.20, abs=0.01)
    assert f.margin / KN == pytest.approx(0.80, abs=0.01)
    low = run_rule("25.333", tmp_path, CONSTANT_CN_MAX + [("  VA: 266 kn EAS", "  VA: 265 kn EAS")])
    assert low.status == "fails"


def test_evidence_is_an_inline_svg():
    from certkit.report.figures import render_result

    r = run_rule("25.333")
    assert r.evidence and r.evidence[0].figure is not None
    render_result(r)
    assert r.evidence[0].svg.startswith("<svg") and not any("evidence" in n for n in r.notes)


def test_negative_stall_beyond_vc_fails(tmp_path):
    """A very small |CLmin| moves H beyond VC: the envelope does not close and the rule fails."""
    r = run_rule("25.333", tmp_path, [("CLmin: -0.8 ", "CLmin: -0.15 ")])
    assert r.status == "fails"
    assert any(f.check.startswith("H") and f.margin < 0 for f in r.findings)


def test_not_evaluated_without_negative_stall(tmp_path):
    r = run_rule("25.333", tmp_path, [("    CLmin: -0.8 ", "    # ")])
    assert r.status == "not_evaluated" and "configurations.clean.CLmin" in r.headline_reason
