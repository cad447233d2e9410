"""§25.107 takeoff speeds against hand calculations in kn CAS.

VSR (takeoff, MTOW 656,000 lb, CLmax 1.95, S 4927.3 ft², ρ₀ 0.0023769 slug/ft³) = 142.009 kn by
VS = √(2W/(ρ₀ S CLmax)) (Anderson, *Introduction to Flight*, eq. 6.47). Tolerance 1e-4 on ratios.
"""

import pytest

KN_TO_MS = 1852.0 / 3600.0

from .helpers import run_rule

VSR_KN = 142.0091


def check(result, prefix):
    return next(f for f in result.findings if f.check.startswith(prefix))


def test_hand_calculation_v2_over_vsr_and_vr_over_v1():
    """V2/VSR − 1.13 = 161/142.009 − 1.13 = 0.00373; VR/V1 − 1 = 155/150 − 1 = 0.0333."""
    r = run_rule("25.107")
    assert check(r, "(b)(1)").margin == pytest.approx(161 / VSR_KN - 1.13, abs=1e-4)
    assert check(r, "(e)(1)(i)").margin == pytest.approx(155 / 150 - 1, abs=1e-9)


def test_v2_on_the_limit(tmp_path):
    """V2 = 1.13 × 142.009 = 160.470 kn CAS: margin 0 within 1e-5."""
    r = run_rule("25.107", tmp_path, [("V2: 161 kn CAS", f"V2: {1.13 * VSR_KN:.4f} kn CAS")])
    f = check(r, "(b)(1)")
    assert f.margin == pytest.approx(0.0, abs=1e-5)


def test_sign_higher_v1_reduces_margin_and_higher_v2_adds_margin(tmp_path):
    """V1 raised to VR (155 kn) puts (e)(1)(i) on its limit (margin 0); the file loader already rejects
    VR < V1, so the check cannot be driven below zero from a valid file. V2 165 kn adds V2/VSR margin."""
    on = run_rule("25.107", tmp_path, [("V1: 150 kn CAS", "V1: 155 kn CAS")])
    assert (
        check(on, "(e)(1)(i)").margin == pytest.approx(0.0, abs=1e-12) and check(on, "(e)(1)(i)").status == "complies"
    )
    faster = run_rule("25.107", tmp_path, [("V2: 161 kn CAS", "V2: 165 kn CAS")])
    assert check(faster, "(b)(1)").margin == pytest.approx(165 / VSR_KN - 1.13, abs=1e-4)
    assert check(faster, "(b)(1)").margin > check(run_rule("25.107"), "(b)(1)").margin


def test_vmc_parts_from_computed_vmca_until_declared(tmp_path):
    """The baseline has no VMC: its parts use the VMCA §25.149 computes (the basis says so) and are evaluated; declaring
    VMC 120 kn CAS gives V2/VMC − 1.10 = 161/120 − 1.10 = 0.2417 and VR/VMC − 1.05 = 155/120 − 1.05 = 0.2417."""
    r = run_rule("25.107")
    b3 = check(r, "(b)(3)")
    assert b3.details["basis"] == "VMCA computed by §25.149 (no VMC declared)"
    assert b3.status in ("complies", "fails") and check(r, "(e)(1)(ii)").status in ("complies", "fails")
    with_vmc = run_rule("25.107", tmp_path, [("V2: 161 kn CAS", "V2: 161 kn CAS\n  VMC: 120 kn CAS")])
    assert check(with_vmc, "(b)(3)").margin == pytest.approx(161 / 120 - 1.10, abs=1e-9)
    assert check(with_vmc, "(e)(1)(ii)").margin == pytest.approx(155 / 120 - 1.05, abs=1e-9)


def _vef_hand_kn():
    """VEF by hand (kn CAS): V1 = 150 KCAS less the speed gained in the 1-s recognition interval after the failure.
    That gain is at most the all-engines acceleration at rest, g 2T_static/W = 32.174 × 2 × 97,300/656,000 = 9.544
    ft/s² = 5.65 kn/s (thrust lapse and drag only lower it), and at least half the engine-out one at rest, 2.83/2 kn/s
    (a high-bypass engine keeps more than half its static thrust at Mach 0.23, Mattingly's lapse): 144.3–148.6 kn."""
    return 150.0 - 2 * 32.174 * 97300 / 656000 / 1.6878, 150.0 - 0.5 * 32.174 * 97300 / 656000 / 1.6878


def test_vef_against_a_declared_vmcg(tmp_path):
    """(a) VEF ≥ VMCG with a declared VMCG: VMCG 130 kn gives VEF/130 with VEF inside the hand band (144.3–148.6 kn);
    VMCG 149 kn, above any VEF that band allows, fails."""
    lo, hi = _vef_hand_kn()
    ok = check(run_rule("25.107", tmp_path, [("V2: 161 kn CAS", "V2: 161 kn CAS\n  VMCG: 130 kn CAS")]), "(a)")
    assert ok.status == "complies" and lo / 130 <= ok.value <= hi / 130 and "declared VMCG" in ok.details["basis"]
    (tmp_path / "high").mkdir()
    high = check(
        run_rule("25.107", tmp_path / "high", [("V2: 161 kn CAS", "V2: 161 kn CAS\n  VMCG: 149 kn CAS")]), "(a)"
    )
    assert high.status == "fails" and lo / 149 <= high.value <= hi / 149


def test_vef_against_the_computed_vmcg_and_a_deficient_fin(tmp_path):
    """Without a declared VMCG the §25.149(e) one is used (the basis names it and its corner) and the baseline
    complies; with the fin 40 % smaller no speed on the runway holds the 30-ft band (tests/rules/test_r25_149.py), so
    no VEF can be at or above VMCG: (a) fails."""
    base = check(run_rule("25.107"), "(a)")
    assert base.status == "complies" and "VMCG computed by §25.149(e)" in base.details["basis"]
    lo, hi = _vef_hand_kn()
    assert lo <= base.details["VEF"] / (1852 / 3600) <= hi
    small = check(run_rule("25.107", tmp_path, [("area: 527.84 ft^2          # [given]", "area: 316.70 ft^2")]), "(a)")
    assert small.status == "fails"


VSR_CLEAN_KN = 167.598  # MTOW 656,000 lb, clean CLmax 1.4, S 4927.3 ft², same formula (Anderson eq. 6.47)


def test_vfto_over_clean_vsr_by_hand_and_a_low_vfto_fails(tmp_path):
    """§25.107(g)(1): VFTO/VSR − 1.18 with VSR of the en-route (clean) configuration at MTOW:
    198/167.598 − 1.18 = +0.0014 for the baseline; a declared VFTO of 195 kn gives 195/167.598 = 1.1635, which fails."""
    f = check(run_rule("25.107"), "(g)(1)")
    assert f.value == pytest.approx(198 / VSR_CLEAN_KN, abs=1e-4)
    assert f.condition.configuration == "clean" and f.status == "complies"
    low = check(run_rule("25.107", tmp_path, [("VFTO: 198 kn CAS", "VFTO: 195 kn CAS")]), "(g)(1)")
    assert low.value == pytest.approx(195 / VSR_CLEAN_KN, abs=1e-4) and low.status == "fails"
