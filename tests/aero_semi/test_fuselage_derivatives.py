"""Fuselage Cm_α (Gilruth & White / Raymer eq. 16.25) and Cn_β (Raymer eq. 16.50)."""

import numpy as np
import pytest

from certkit.models.aero import fuselage as fz


def test_fuselage_is_destabilising_in_pitch_and_yaw(baseline):
    """Sign check (certkit.conventions: Cm nose up +, Cn nose right +): a fuselage adds a positive
    Cm_α and a negative Cn_β (Raymer §16.3–16.4, 'the fuselage is destabilising')."""
    d = fz.fuselage_derivatives(baseline.model.geometry, baseline.model.reference)
    assert d.Cm_alpha > 0
    assert d.Cn_beta < 0


def test_cm_alpha_hand_calculation_for_the_baseline(baseline):
    """Hand calculation with the file's values: root LE 63.24 ft + c_r/4 (c_r 40.08 ft) = 73.26 ft
    = 0.3548 L; K_f = 0.01361 + (0.3548 − 0.3496)/(0.3797 − 0.3496)·(0.01623 − 0.01361) = 0.01406
    per degree (Raymer Fig. 16.14); ΔCm_α = K_f W² L/(c̄ S)·57.296 = 0.01406·6.3276²·62.941/
    (8.3686·457.76)·57.296 = 0.530 per radian. Tolerance 0.5 %."""
    ft = 0.3048
    x = (63.24 + 40.08 / 4) / 206.5
    k = 0.01361 + (x - 0.3496) / (0.3797 - 0.3496) * (0.01623 - 0.01361)
    expected = k * (20.76 * ft) ** 2 * 206.5 * ft / (27.456 * ft * 4927.3 * ft**2) * 180 / np.pi
    d = fz.fuselage_derivatives(baseline.model.geometry, baseline.model.reference)
    assert d.root_quarter_chord_fraction == pytest.approx(x, rel=2e-3)
    assert d.K_f == pytest.approx(k, rel=5e-3)
    assert d.Cm_alpha == pytest.approx(expected, rel=5e-3)
    assert d.Cm_alpha == pytest.approx(0.530, abs=0.005)


def test_cn_beta_hand_calculation_for_the_baseline(baseline):
    """Hand calculation: V = π/4·W·D·L·(1 − 2√(WD)/L) = π/4·6.3276·6.1661·62.941·(1 − 2·6.2464/62.941)
    = 1545.9 m³; ΔCn_β = −1.3·V/(S b)·D/W = −1.3·1545.9/(457.76·63.505)·0.97447 = −0.0674 per
    radian (Raymer eq. 16.50). Tolerance 0.5 %."""
    w, dpt, length = 6.327648, 6.166104, 62.9412
    vol = np.pi / 4 * w * dpt * length * (1 - 2 * np.sqrt(w * dpt) / length)
    expected = -1.3 * vol / (457.761149 * 63.50508) * dpt / w
    d = fz.fuselage_derivatives(baseline.model.geometry, baseline.model.reference)
    assert d.volume == pytest.approx(1545.9, rel=5e-4)
    assert d.Cn_beta == pytest.approx(expected, rel=5e-3)
    assert d.Cn_beta == pytest.approx(-0.0674, abs=0.0005)


def test_pitch_factor_table_grows_aft_and_refuses_extrapolation():
    """K_f rises monotonically with the wing's station (Raymer Fig. 16.14) and a station outside the
    figure (10–62 % of the body) is an error rather than an extrapolation."""
    assert np.all(np.diff(fz.K_F_PER_DEG) > 0)
    assert fz.pitching_moment_factor(fz.K_F_STATION[0]) == pytest.approx(fz.K_F_PER_DEG[0])
    with pytest.raises(ValueError, match="Fig. 16.14"):
        fz.pitching_moment_factor(0.8)


def test_scaling_laws():
    """ΔCm_α ∝ W² L at a fixed wing station fraction; ΔCn_β ∝ V/(S b) (exact, 1e-12)."""
    a = fz.cm_alpha_fuselage(60.0, 6.0, 21.0, 400.0, 8.0)
    b = fz.cm_alpha_fuselage(60.0, 12.0, 21.0, 400.0, 8.0)
    assert b / a == pytest.approx(4.0, rel=1e-12)
    assert fz.cn_beta_fuselage(2000.0, 6, 6, 400, 60) / fz.cn_beta_fuselage(1000.0, 6, 6, 400, 60) == pytest.approx(2.0)


def test_cy_beta_body_by_hand(baseline):
    """DATCOM 5.2.1.1 with K_i = 1: ΔCY_β = −2 (π/4 W D)/S; baseline 20.76 × 20.23 ft on 4927.3 ft²."""
    import math

    from certkit.models.aero.fuselage import fuselage_derivatives

    a = baseline.model
    f = fuselage_derivatives(a.geometry, a.reference)
    assert f.CY_beta == pytest.approx(-2 * math.pi / 4 * 20.76 * 20.23 / 4927.3, rel=1e-6)
    assert f.CY_beta < 0
