"""High-lift estimates against hand calculations of Raymer (6th ed.) eqs 12.15, 12.21, 12.22."""

import math

import pytest

from certkit.aircraft.model import HighLiftDevice
from certkit.models.aero import high_lift as hl
from certkit.models.aero import planform


def test_flapped_area_ratio_closed_forms(baseline):
    """Untapered wing: the area ratio equals the span fraction; tapered: ∫c dy by hand."""
    wing = baseline.model.geometry.wing
    rect = wing.model_copy(update={"taper": 1.0})
    dev = HighLiftDevice(span_start=0.2, span_end=0.7, chord_ratio=0.3)
    assert hl.flapped_area_ratio(rect, dev) == pytest.approx(0.5)
    lam = wing.taper  # ∫_a^b (1-(1-λ)η) dη / ((1+λ)/2)
    a, b = 0.2, 0.7
    hand = ((b - a) - 0.5 * (1 - lam) * (b * b - a * a)) / (0.5 * (1 + lam))
    assert hl.flapped_area_ratio(wing, dev) == pytest.approx(hand, rel=1e-12)


def test_delta_clmax_and_zero_lift_shift_by_hand(baseline):
    """Baseline slotted flap at the landing setting (its landing configuration's 30°): ΔCLmax = 0.9·1.3·(S_f/S)·cos
    Λ_hinge, Δα0 = −15°·(S_f/S)·cos Λ_hinge, ΔCL0 = −CLα·Δα0 (Raymer eqs 12.21, 12.22); at the takeoff setting (its
    takeoff configuration's 15°) Raymer's −10° 2-D change and 70 % of the landing Δc_lmax (his 60–80 %); flaps 20
    (approach) between them, two thirds of the way from 15° to 30° nearer the takeoff value: −10° − 5°·(5/15)."""
    wing = baseline.model.geometry.wing
    flaps = wing.flaps
    ratio = hl.flapped_area_ratio(wing, flaps)
    hinge = planform.sweep_at(1 - flaps.chord_ratio, wing.sweep_quarter_chord, wing.aspect_ratio, wing.taper)
    settings = hl.FlapSettings.of(baseline.model.configurations)
    assert (math.degrees(settings.takeoff), math.degrees(settings.landing)) == pytest.approx((15.0, 30.0))
    landing_clmax = 0.9 * 1.3 * ratio * math.cos(hinge)
    assert hl.delta_clmax(wing, flaps, settings.share(math.radians(30), 0.7)) == pytest.approx(landing_clmax, rel=1e-12)
    assert hl.delta_clmax(wing, flaps, settings.share(math.radians(15), 0.7)) == pytest.approx(0.7 * landing_clmax)
    for flap_deg, shift_2d_deg in ((30, -15.0), (40, -15.0), (15, -10.0), (20, -10.0 - 5.0 / 3.0), (7.5, -5.0)):
        d_cl, _ = hl.lift_and_moment_increment(wing, flaps, math.radians(flap_deg), 5.0, 29.64, 8.37, settings)
        assert d_cl == pytest.approx(-5.0 * math.radians(shift_2d_deg) * ratio * math.cos(hinge), rel=1e-12), flap_deg
    d_cl, d_cm = hl.lift_and_moment_increment(wing, flaps, math.radians(30), 5.0, 29.64, 8.37, settings)
    assert d_cm < 0  # flap load aft of the reference point: nose down
    assert hl.lift_and_moment_increment(wing, flaps, 0.0, 5.0, 29.64, 8.37, settings) == (0.0, 0.0)


def test_without_a_takeoff_setting_the_increment_scales_with_the_deflection(baseline):
    """An aircraft file with no takeoff configuration (or one flapped as for landing) has no takeoff setting: the
    increments grow in proportion to the deflection up to the landing setting (40° without a landing configuration)."""
    configurations = dict(baseline.model.configurations)
    del configurations["takeoff"]
    settings = hl.FlapSettings.of(configurations)
    assert settings.takeoff is None and settings.share(math.radians(15), 0.7) == pytest.approx(0.5)
    assert hl.FlapSettings.of({}).share(math.radians(20), 0.7) == pytest.approx(0.5)


def test_clean_clmax_estimate(baseline):
    """0.9·c_lmax·cos Λ: t/c 0.11 → c_lmax 1.5 (interpolated), Λ 30.94°."""
    wing = baseline.model.geometry.wing
    assert hl.clean_clmax(wing) == pytest.approx(0.9 * 1.5 * math.cos(math.radians(30.94)), rel=1e-3)


def test_undeclared_clmax_is_estimated_and_noted(tmp_path):
    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context

    from ..conftest import BASELINE

    f = tmp_path / "a.yaml"
    f.write_text(BASELINE.read_text().replace("    CLmax: 2.25 ", "    # CLmax removed "))
    aero = Context(load_aircraft(f)).aero("landing")
    assert any("CLmax" in n and "estimated" in n for n in aero.notes)
    assert aero.model.stall is not None
