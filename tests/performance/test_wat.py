"""Off-standard days: the atmosphere with an ISA deviation, the flat-rated thrust lapse, the envelope's corners.

References (none written here):
* ISO 2533:1975 / ICAO Doc 7488 standard atmosphere tables: speed of sound 332.53 m/s at 2,000 m (T = 275.15 K),
  340.29 m/s at sea level (288.15 K); pressure 79,495 Pa at 2,000 m;
* FAA Pilot's Handbook of Aeronautical Knowledge (FAA-H-8083-25B, ch. 11, density altitude): density altitude rises
  about 120 ft per °C above standard temperature;
* IFALPA position paper "Take-off performance considering inversions": an engine at or near its flat-rating
  temperature loses 8–12 % of its thrust for a 10 K rise; below the flat-rating temperature thrust is constant
  (the definition of flat rating, e.g. the engine TCDS's "flat rating ambient temperature");
* ISA lapse 1.98 °C per 1,000 ft (6.5 K/km): at 8,400 ft ISA is 15 − 16.6 = −1.6 °C.
"""

import numpy as np
import pytest

from certkit import atmosphere as isa
from certkit.aircraft.model import TakeoffLandingEnvelope
from certkit.models.performance.wat import envelope_corners, hot_limit, weight_for_gradient
from certkit.models.propulsion.engine import temperature_thrust_ratio
from certkit.models.reference_condition import altitude_of_density

FT = 0.3048
FLAT = 303.15  # 30 °C, ISA+15: GE90 takeoff flat rating (FAA TCDS E00049EN)


def test_speed_of_sound_follows_the_temperature_of_the_day():
    """ISO 2533 tables: a = 332.53 m/s where T = 275.15 K, 340.29 m/s where T = 288.15 K (±0.01 m/s)."""
    assert float(isa.speed_of_sound(0.0, -13.0)) == pytest.approx(332.53, abs=0.01)
    assert float(isa.speed_of_sound(2000.0, 13.0)) == pytest.approx(340.29, abs=0.01)


def test_density_is_the_standard_pressure_over_the_day_temperature():
    """Pressure altitude 2,000 m on ISA+13: p = 79,495 Pa (table), T = 288.15 K, ρ = p/(R T) = 0.9611 kg/m³ (0.05 %)."""
    assert float(isa.density(2000.0, 13.0)) == pytest.approx(79_495.0 / (287.05287 * 288.15), rel=5e-4)
    assert float(isa.pressure(2000.0)) == pytest.approx(79_495.0, rel=1e-4)


@pytest.mark.parametrize("hp_ft, dt", [(0, 15), (5000, 20), (2000, -10)])
def test_density_altitude_rule_of_thumb(hp_ft, dt):
    """PHAK: density altitude ≈ pressure altitude + 120 ft/°C × deviation; a rule of thumb, so within 8 %."""
    h_rho = altitude_of_density(float(isa.density(hp_ft * FT, dt))) / FT
    assert (h_rho - hp_ft) / dt == pytest.approx(120.0, rel=0.08)


def test_standard_day_is_unchanged():
    h = np.array([0.0, 3000.0, 11_000.0])
    assert np.array_equal(isa.density(h), isa.density(h, 0.0))
    assert np.array_equal(isa.temperature(h, np.zeros(3)), isa.temperature(h))


def test_thrust_is_flat_below_the_flat_rating_temperature():
    """Static sea level: the same thrust from −40 °C to 30 °C (ratio 1 within 1e-12); just above 30 °C it falls."""
    dts = np.array([-55.0, -20.0, 0.0, 10.0, 14.9])
    assert np.allclose(temperature_thrust_ratio(0.0, 0.0, dts, FLAT), 1.0, atol=1e-12)
    assert float(temperature_thrust_ratio(0.0, 0.0, 16.0, FLAT)) < 1.0


def test_thrust_lapse_above_the_flat_rating_matches_the_published_band():
    """Climb-out (M 0.3): 10 K above the break loses 8–12 % (IFALPA); Mattingly's law gives about 8 %."""
    mach = 0.3
    t_break = FLAT / (1 + 0.2 * mach**2)  # the ambient temperature where θ0 = TR at this Mach number
    dt_break = t_break - isa.T0
    r0, r10 = (float(temperature_thrust_ratio(0.0, mach, dt_break + d, FLAT)) for d in (0.0, 10.0))
    assert r0 == pytest.approx(1.0, abs=1e-12)
    loss = 1.0 - r10 / r0
    assert 0.08 <= loss <= 0.12, loss


def test_envelope_corners_hand_values():
    """−1,000…8,400 ft, −40…50 °C, ISA+40 line: at 8,400 ft the hot limit is −1.6 + 40 = 38.4 °C (ISA lapse
    1.98 °C/1,000 ft), at sea level 50 °C (the ISA+40 line, 55 °C, is above it); sea level is added."""
    env = TakeoffLandingEnvelope(
        pressure_altitude_min="-1000 ft",
        pressure_altitude_max="8400 ft",
        temperature_min="-40 degC",
        temperature_max="50 degC",
        isa_deviation_max="40 delta_degC",
    )
    assert hot_limit(env, 8400 * FT) - 273.15 == pytest.approx(-1.6 + 40.0, abs=0.05)
    assert hot_limit(env, 0.0) == pytest.approx(323.15)
    corners = envelope_corners(env)
    alts = sorted({round(c.pressure_altitude / FT) for c in corners})
    assert alts == [-1000, 0, 3700, 8400]
    assert len(corners) == 4 * 3  # cold, standard, hot at each
    hot_high = max(corners, key=lambda c: (c.pressure_altitude, c.temperature))
    assert hot_high.delta_isa == pytest.approx(40.0)


def test_weight_for_gradient_is_exact_for_constant_lift_coefficient():
    """A climb with D/W fixed (the speed ∝ √W) and thrust fixed: γ = T/W − D/W. From W = 1,000 kN, T = 120 kN,
    D/W = 0.09 (γ = 0.03) the weight for γ = 0.024 is T/(0.024 + 0.09) = 1,052.6 kN."""
    assert float(weight_for_gradient(1000e3, 120e3, 0.03, 0.024)) == pytest.approx(120e3 / 0.114, rel=1e-12)


def test_envelope_without_flat_rating_and_inverted_range_are_reported_together(tmp_path):
    """Both problems, with their YAML paths and lines, in one InputError."""
    from certkit.aircraft import load_aircraft
    from certkit.errors import InputError

    from ..conftest import BASELINE

    text = BASELINE.read_text()
    line = next(x for x in text.splitlines() if x.strip().startswith("flat_rating_temperature:"))
    text = text.replace(line + "\n", "").replace("pressure_altitude_max: 8400 ft", "pressure_altitude_max: -2000 ft")
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(InputError) as err:
        load_aircraft(path)
    message = str(err.value)
    assert (
        "propulsion.flat_rating_temperature" in message and "takeoff_landing_envelope.pressure_altitude_max" in message
    )
