"""Engine deck interpolation and range checks; parametric turbofan lapse."""

import numpy as np
import pytest

from certkit.models.propulsion.engine import DeckRangeError, EngineDeck, ParametricTurbofan, windmill_drag


def _deck(**kw):
    alt = np.array([0.0, 5000.0, 10000.0])
    mach = np.array([0.0, 0.4, 0.8])
    thr = np.array([0.0, 1.0])
    A, M, T = np.meshgrid(alt, mach, thr, indexing="ij")
    thrust = 1.0e5 * (1 - A / 2e4) * (1 - 0.3 * M) * (0.05 + 0.95 * T)
    return EngineDeck(alt, mach, thr, thrust, fuel_flow=thrust * 1.6e-5, **kw)


def test_deck_interpolates_linearly():
    """A table linear in each variable is reproduced exactly in between breakpoints (trilinear
    interpolation; tolerance 1e-9 relative)."""
    d = _deck()
    h, m, t = 2500.0, 0.2, 0.5
    expected = 1.0e5 * (1 - h / 2e4) * (1 - 0.3 * m) * (0.05 + 0.95 * t)
    assert d.thrust(t, h, m) == pytest.approx(expected, rel=1e-9)
    assert d.fuel_flow(t, h, m) == pytest.approx(expected * 1.6e-5, rel=1e-9)


def test_deck_extrapolation_is_an_error_naming_the_point():
    d = _deck()
    with pytest.raises(DeckRangeError, match=r"altitude 12000 m, Mach 0\.500"):
        d.thrust(np.array([1.0, 1.0]), np.array([1000.0, 12000.0]), np.array([0.3, 0.5]))


def test_deck_extrapolation_when_allowed():
    d = _deck(allow_extrapolation=True)
    assert np.isfinite(d.thrust(1.0, 12000.0, 0.5))


def test_turbofan_lapse():
    """Mattingly's high-bypass lapse: 1 at sea-level static; at 11 km, M 0.8 it is
    δ0 (1 − 0.49√0.8) with δ0 = 0.2234·1.524 = 0.3404 → 0.191 (hand calculation from the
    formula; tolerance 1 %). Thrust falls with altitude and with Mach at sea level."""
    e = ParametricTurbofan(static_thrust=1.2e5)
    assert e.thrust(1.0, 0.0, 0.0) == pytest.approx(1.2e5, rel=1e-9)
    assert e.lapse(11000.0, 0.8) == pytest.approx(
        0.2234 * (1 + 0.2 * 0.64) ** 3.5 * (1 - 0.49 * np.sqrt(0.8)), rel=0.01
    )
    assert e.thrust(1.0, 0.0, 0.3) < e.thrust(1.0, 0.0, 0.0)
    assert e.fuel_flow(1.0, 0.0, 0.0) == pytest.approx(1.2e5 * 0.4 / 3600 / 9.80665, rel=1e-9)


def test_windmill_drag_positive_and_scales_with_q():
    d = windmill_drag(2.0)
    assert d(10_000.0, 0.3) > 0
    assert d(20_000.0, 0.3) == pytest.approx(2 * d(10_000.0, 0.3))
