"""The drag build-up's formulas against hand calculations and their limits."""

import numpy as np
import pytest

from certkit.models.aero import drag
from certkit.models.propulsion.engine import windmill_drag

DEG = np.pi / 180


def test_turbulent_skin_friction_at_re_1e7():
    """Prandtl–Schlichting flat plate, Re 1e7, incompressible: Cf = 0.455/7^2.58 = 0.0030039 (hand
    calculation; Schlichting's curve reads 0.0030). Tolerance 1e-4 relative."""
    assert drag.turbulent_skin_friction(1e7) == pytest.approx(0.455 / 7**2.58, rel=1e-12)
    assert drag.turbulent_skin_friction(1e7) == pytest.approx(0.0030039, rel=1e-4)


def test_compressibility_lowers_skin_friction_by_raymer_factor():
    """Raymer eq. 12.27 at M 0.84: Cf(M)/Cf(0) = (1 + 0.144·0.84²)^−0.65 = 0.93906 (hand calculation,
    tolerance 1e-4 relative)."""
    ratio = drag.turbulent_skin_friction(5e7, 0.84) / drag.turbulent_skin_friction(5e7, 0.0)
    assert ratio == pytest.approx(0.93906, rel=1e-4)


def test_laminar_fraction_blends_between_blasius_and_turbulent():
    """Blasius 1.328/√Re at Re 1e6 = 0.001328 (exact); the composite is turbulent at x_tr = 0,
    laminar at x_tr = 1 and falls monotonically in between (tolerance 1e-12)."""
    re = 1e6
    assert drag.laminar_skin_friction(re) == pytest.approx(0.001328, rel=1e-12)
    assert drag.skin_friction(re, 0.0, 0.0) == pytest.approx(drag.turbulent_skin_friction(re), rel=1e-12)
    assert drag.skin_friction(re, 0.0, 1.0) == pytest.approx(drag.laminar_skin_friction(re), rel=1e-12)
    cf = drag.skin_friction(re, 0.0, np.linspace(0, 1, 11))
    assert np.all(np.diff(cf) < 0)


def test_cutoff_reynolds_hand_calculation():
    """Raymer eq. 12.28 for a 7 m chord in smooth paint (k = 2.08e-5 ft): 38.21 (7/6.34e-6)^1.053
    (hand calculation, tolerance 1e-9 relative)."""
    k = 2.08e-5 * 0.3048
    assert drag.cutoff_reynolds(7.0, k) == pytest.approx(38.21 * (7.0 / k) ** 1.053, rel=1e-9)


def test_form_factor_limits():
    """FF → 1 as t/c → 0 (unswept, low speed, Raymer eq. 12.30 with the Mach factor held at 1
    below M 0.197); bodies: FF → 1 + f/400 for slender bodies (eq. 12.31) and → 1 for nacelles
    (eq. 12.32). Tolerances 1e-6 absolute."""
    assert drag.thickness_form_factor(0.0) == 1.0
    assert drag.lifting_surface_form_factor(1e-9, 0.0, 0.15) == pytest.approx(1.0, abs=1e-6)
    assert drag.lifting_surface_form_factor(1e-9, 0.0, 0.197) == pytest.approx(1.0, abs=1e-3)
    assert drag.fuselage_form_factor(1e4) == pytest.approx(1 + 1e4 / 400, abs=1e-6)
    assert drag.nacelle_form_factor(1e7) == pytest.approx(1.0, abs=1e-6)


def test_lifting_surface_form_factor_hand_calculation():
    """Raymer eq. 12.30, t/c 0.12, (x/c)_m 0.3, Λ_m 30°, M 0.8: (1 + 2·0.12 + 100·0.12⁴)
    · 1.34·0.8^0.18 · cos30°^0.28 = 1.26074 · 1.28724 · 0.96053 = 1.5588 (hand calculation, 1e-4)."""
    ff = drag.lifting_surface_form_factor(0.12, 30 * DEG, 0.8, x_max_thickness=0.3)
    assert ff == pytest.approx(1.5588, rel=1e-4)


def test_wetted_area_closed_forms():
    """S_wet = S_exp (1.977 + 0.52 t/c) (Raymer eq. 7.10); Torenbeek's fuselage area for L 60 m,
    D 6 m: π·6·60·0.8^(2/3)·1.01 = 984.3 m² (hand calculation); → π D L as λ → ∞. Tolerance 1e-3."""
    assert drag.lifting_surface_wetted_area(100.0, 0.10) == pytest.approx(202.9, rel=1e-9)
    assert drag.fuselage_wetted_area(60.0, 6.0, 6.0) == pytest.approx(np.pi * 6 * 60 * 0.8 ** (2 / 3) * 1.01, rel=1e-9)
    assert drag.fuselage_wetted_area(60.0, 6.0, 6.0) == pytest.approx(984.3, rel=1e-3)
    assert drag.fuselage_wetted_area(6e4, 6.0, 6.0) / (np.pi * 6 * 6e4) == pytest.approx(1.0, rel=1e-3)
    assert drag.nacelle_wetted_area(7.0, 4.0) == pytest.approx(np.pi * 28.0)


def test_exposed_planform_of_rectangular_and_tapered_wings(baseline):
    """Exposed trapezoid: a rectangular wing loses w/b of its area; for the baseline wing the
    exposed area is (b − w)/2 (c_side + c_tip) with c_side = c_r (1 − (1 − λ) w/b) (hand calculation
    with the file's numbers, 1e-9) and the exposed trapezoid's root chord is c_side."""
    wing = baseline.model.geometry.wing
    rect = wing.model_copy(update={"taper": 1.0})
    b = np.sqrt(wing.area * wing.aspect_ratio)
    assert drag.exposed_planform(rect, 6.0).area == pytest.approx(wing.area * (1 - 6.0 / b), rel=1e-9)
    w = baseline.model.geometry.fuselage.width
    c_r = 2 * wing.area / (b * (1 + wing.taper))
    c_side = c_r * (1 - (1 - wing.taper) * w / b)
    exp = drag.exposed_planform(wing, w)
    assert exp.area == pytest.approx(0.5 * (b - w) * (c_side + wing.taper * c_r), rel=1e-9)
    assert 2 * exp.area / (np.sqrt(exp.area * exp.aspect_ratio) * (1 + exp.taper)) == pytest.approx(c_side, rel=1e-9)


def test_korn_drag_divergence_hand_calculations():
    """Korn–Shevell (Malone & Mason 1995). The worked case of Mason's notes could not be retrieved;
    hand calculations instead: κ 0.95, Λ 30°, t/c 0.10, CL 0.5 → 1.09697 − 0.13333 − 0.07698 =
    0.88666; the unswept Korn equation, κ 0.87, t/c 0.12, CL 0.3 → 0.72. Tolerance 1e-5."""
    assert drag.drag_divergence_mach(0.5, 0.10, 30 * DEG, 0.95) == pytest.approx(0.88666, abs=1e-5)
    assert drag.drag_divergence_mach(0.3, 0.12, 0.0, drag.KAPPA_CONVENTIONAL) == pytest.approx(0.72, abs=1e-12)
    assert drag.critical_mach(0.88666) == pytest.approx(0.88666 - 0.107722, abs=1e-6)


def test_lock_law_is_continuous_at_mcrit_and_has_slope_0_1_at_mdd():
    """Lock's law: zero at and below M_crit, continuous there (value < 1e-12 at M_crit + 1e-4) and
    dCD/dM = 0.1 at M_DD by construction of (0.1/80)^(1/3) (central difference, 1e-4 relative)."""
    args = (0.5, 0.11, 31 * DEG)
    mdd = drag.drag_divergence_mach(*args)
    mcr = drag.critical_mach(mdd)
    assert drag.wave_drag(mcr - 0.05, *args) == 0.0
    assert drag.wave_drag(mcr, *args) == 0.0
    assert drag.wave_drag(mcr + 1e-4, *args) < 1e-12
    h = 1e-6
    slope = (drag.wave_drag(mdd + h, *args) - drag.wave_drag(mdd - h, *args)) / (2 * h)
    assert slope == pytest.approx(0.1, rel=1e-4)


def test_oswald_efficiency_in_a_sane_band(baseline):
    """Nita & Scholz e for the baseline (A 8.81, λ 0.18, Λ 30.9°, d/b 0.098) lies in 0.75–0.90,
    the band of jet transports in their paper; the planform factor is ≤ 1 and highest near the
    optimum taper of an unswept wing, λ ≈ 0.45 (their Δλ at Λ = 0)."""
    g, ref = baseline.model.geometry, baseline.model.reference
    e = drag.oswald_efficiency(
        g.wing.aspect_ratio,
        g.wing.taper,
        g.wing.sweep_quarter_chord,
        drag.equivalent_diameter(g.fuselage.width, g.fuselage.height),
        ref.span,
    )
    assert 0.75 < e < 0.90
    tapers = np.linspace(0.05, 1.0, 96)
    e_theo = drag.planform_span_efficiency(10.0, tapers, 0.0)
    assert np.all(e_theo <= 1.0)
    assert tapers[np.argmax(e_theo)] == pytest.approx(0.45, abs=0.02)
    assert drag.oswald_efficiency(9, 0.3, 0.5, 6, 60, inviscid_span_efficiency=0.98) == pytest.approx(
        0.98 * drag.K_E_CD0_JET
    )


def test_induced_drag_elliptic_case():
    """CDi = CL²/(π A e): CL 0.5, A 9, e 1 → 0.25/(9π) = 0.0088419 (exact to 1e-12)."""
    assert drag.induced_drag(0.5, 9.0, 1.0) == pytest.approx(0.25 / (9 * np.pi), rel=1e-12)


def test_increments_hand_calculations(baseline):
    """Flaps, Raymer eq. 12.61 (slotted, c_f/c 0.3, S_f/S 0.6, 30°): 0.0074·0.3·0.6·20 = 0.02664;
    zero at or below 10°. A declared delta_CD0 in the file wins over the estimate; an undeclared
    landing configuration gets flaps + Roskam gear 0.020. Windmilling CD = windmill_drag/(q S)
    (consistency with the propulsion model, 1e-12). Spoilers: 1.2 (S_sp/S) sin²δ."""
    assert drag.flap_drag_increment(30 * DEG) == pytest.approx(0.02664, rel=1e-12)
    assert drag.flap_drag_increment(np.array([0.0, 10 * DEG])).tolist() == [0.0, 0.0]
    landing = baseline.model.configurations["landing"]
    assert drag.configuration_drag_increment(landing) == (0.045, True)
    estimate, declared = drag.configuration_drag_increment(landing.model_copy(update={"delta_CD0": 0.0}))
    assert not declared and estimate == pytest.approx(0.02664 + 0.020, rel=1e-12)
    q = 0.7 * 101325.0 * 0.3**2
    cd = drag.windmilling_drag_coefficient(0.3, 0.0, 3.0, 400.0)
    assert cd == pytest.approx(windmill_drag(3.0)(q, 0.3) / (q * 400.0), rel=1e-9)
    assert drag.spoiler_drag_increment(0.0, 10.0, 400.0) == 0.0
    assert drag.spoiler_drag_increment(np.pi / 2, 10.0, 400.0) == pytest.approx(1.2 * 10 / 400)


def test_overrides_replace_estimates_and_are_listed(baseline):
    """Every declared coefficient replaces its estimate exactly and is named in ``overridden``;
    the file's declared take-off delta_CD0 (0.012) is listed too."""
    ac = baseline.model
    ov = drag.DragOverrides(CD0=0.0150, oswald_efficiency=0.80, drag_divergence_mach=0.86)
    b = drag.drag_buildup(ac, 0.84, 10668.0, 0.5, overrides=ov)
    assert b.CD0 == pytest.approx(0.0150)
    assert b.CDi == pytest.approx(0.25 / (np.pi * ac.geometry.wing.aspect_ratio * 0.80))
    assert b.CD_wave == pytest.approx(20 * (0.84 - (0.86 - (0.1 / 80) ** (1 / 3))) ** 4, rel=1e-12)
    assert set(b.overridden) == {"CD0", "oswald_efficiency", "drag_divergence_mach"}
    t = drag.drag_buildup(ac, 0.25, 0.0, 1.2, configuration="takeoff")
    assert t.delta_CD0 == pytest.approx(0.012) and "delta_CD0 (takeoff, aircraft file)" in t.overridden


def test_buildup_is_vectorised_over_mach_altitude_and_cl(baseline):
    """A 3 × 4 grid of (Mach, altitude) × CL is one call; each element equals the scalar call
    (1e-12 relative)."""
    ac = baseline.model
    mach = np.array([0.5, 0.78, 0.86])[:, None]
    alt = np.array([3000.0, 9000.0, 11000.0])[:, None]
    cl = np.array([0.2, 0.4, 0.5, 0.6])[None, :]
    b = drag.drag_buildup(ac, mach, alt, cl)
    assert b.CD.shape == (3, 4)
    one = drag.drag_buildup(ac, 0.78, 9000.0, 0.5)
    assert b.CD[1, 2] == pytest.approx(float(one.CD), rel=1e-12)
