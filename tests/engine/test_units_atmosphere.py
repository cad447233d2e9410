"""Units at the boundary and the ISA (references: ISO 2533:1975 defining values)."""

import numpy as np
import pytest

from certkit import atmosphere as isa
from certkit.units import UnitError, from_si, to_si


def test_quantities_convert_to_si():
    """Exact conversion factors (NIST SP 811): 1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N, 1 kn = 1852/3600 m/s."""
    assert to_si("4927.3 ft^2", "area") == pytest.approx(4927.3 * 0.3048**2, rel=1e-12)
    assert to_si("97300 lbf", "force") == pytest.approx(97300 * 4.4482216152605, rel=1e-12)
    assert to_si("340 kn", "speed") == pytest.approx(340 * 1852 / 3600, rel=1e-12)
    assert to_si("43000 ft", "length") == pytest.approx(13106.4, rel=1e-12)
    assert to_si(12.5, "length") == 12.5
    assert from_si(174.9111111, "kn") == pytest.approx(340.0, rel=1e-6)


@pytest.mark.parametrize("text,dim", [("10 kg", "force"), ("3 furlongs per bogus", "length"), ("abc", "area")])
def test_wrong_units_are_rejected(text, dim):
    with pytest.raises(UnitError):
        to_si(text, dim)


def test_isa_defining_values():
    """ISO 2533: sea level 288.15 K / 101325 Pa / 1.225 kg/m³; tropopause (11 km geopotential) 216.65 K and
    22632.06 Pa; 20 km 5474.89 Pa. Tolerance 1e-5 relative (table digits)."""
    h = np.array([0.0, 11000.0, 20000.0])
    assert isa.temperature(h) == pytest.approx([288.15, 216.65, 216.65], rel=1e-9)
    assert isa.pressure(h) == pytest.approx([101325.0, 22632.06, 5474.89], rel=1e-5)
    assert isa.density(0.0) == pytest.approx(1.225, rel=1e-4)
    assert isa.speed_of_sound(0.0) == pytest.approx(340.294, rel=1e-5)


def test_airspeed_conversions_are_consistent():
    """CAS = TAS = EAS at sea level; EAS = TAS·√σ; CAS ≥ EAS at altitude (compressibility); round trips."""
    v = np.array([60.0, 150.0, 250.0])
    for kind in ("EAS", "CAS"):
        assert isa.convert_speed(v, kind, "TAS", 0.0) == pytest.approx(v, rel=1e-7)
    h = 10668.0
    tas = isa.to_tas(v, "EAS", h)
    assert tas == pytest.approx(v / np.sqrt(isa.density(h) / isa.RHO0))
    assert np.all(isa.convert_speed(v, "EAS", "CAS", h) > v)
    for kind in ("EAS", "CAS", "MACH"):
        assert isa.from_tas(isa.to_tas(v / 300 if kind == "MACH" else v, kind, h), kind, h) == pytest.approx(
            v / 300 if kind == "MACH" else v, rel=1e-7
        )
    assert isa.cas_to_mach(isa.mach_to_cas(1.3, h), h) == pytest.approx(1.3, rel=1e-6)


def test_altitude_outside_the_model_is_an_error():
    with pytest.raises(isa.AtmosphereRangeError, match="outside"):
        isa.density(25000.0)


def test_a_scalar_altitude_gives_the_array_value_and_a_fresh_array():
    """The layers' values at a scalar altitude are remembered: the same bits as an array of altitudes (first and
    repeated asks, float and numpy scalars alike), a new 0-d array each time (a caller's in-place change does not reach
    the next), and an altitude outside the layers still an error at every ask."""
    heights = np.array([-600.0, 0.0, 1234.5, 10999.9, 11000.0, 15432.1, 20000.0])
    for h in heights:
        for f in (isa.temperature, isa.pressure, isa.density, isa.speed_of_sound):
            first, again, scalar = f(float(h)), f(float(h)), f(np.float64(h))
            assert first.shape == () and first.dtype == np.float64
            assert first.tobytes() == again.tobytes() == scalar.tobytes() == f(np.array([h]))[0].tobytes()
    t = isa.temperature(5000.0)
    t += 100.0
    assert isa.temperature(5000.0) == isa.temperature(np.array([5000.0]))[0]
    for _ in range(2):
        with pytest.raises(isa.AtmosphereRangeError, match="outside"):
            isa.pressure(20001.0)


def test_a_remembered_scalar_conversion_is_the_computed_one():
    """convert_speed remembers the conversions of scalar speeds: the second ask returns the value the conversion
    computes (TAS through every kind, both ways), bit for bit, signed zeros apart, as a fresh 0-d array."""
    import itertools

    from certkit.atmosphere import convert_speed, from_tas, to_tas

    rng = np.random.default_rng(5)
    kinds = ("EAS", "CAS", "TAS", "MACH")
    for fk, tk in itertools.product(kinds, kinds):
        for _ in range(40):
            h = float(rng.choice([0.0, -0.0, rng.uniform(-500, 15000)]))
            v = float(rng.uniform(0.1, 0.95)) if fk == "MACH" else float(rng.choice([0.0, -0.0, rng.uniform(30, 300)]))
            computed = np.asarray(from_tas(to_tas(v, fk, h), tk, h))
            first, second = convert_speed(v, fk, tk, h), convert_speed(v, fk, tk, h)
            assert first is not second and second.shape == computed.shape == ()
            assert first.tobytes() == second.tobytes() == computed.tobytes(), (fk, tk, v, h)


def test_design_speeds_at_one_altitude(ctx):
    """The baseline's VC (272 kn EAS, MC 0.87) as a float at one altitude: 272 kn at sea level; MC limits it above
    about 37,000 ft: at 40,000 ft EAS = M a √σ with the ISA table's a = 295.07 m/s and σ = 0.2462 there (ICAO Doc
    7488; 2 × 10⁻⁴ relative, the table's digits); the same float again from the context's memo, and the arrays of
    ``design_speed_eas`` agree."""
    assert ctx.design_speed_eas_at("VC", 0.0) == pytest.approx(272 * 1852 / 3600, rel=1e-12)
    h = 40000 * 0.3048
    vc = ctx.design_speed_eas_at("VC", h)
    assert vc == pytest.approx(0.87 * 295.07 * 0.2462**0.5, rel=2e-4)
    assert ctx.design_speed_eas_at("VC", h) is vc
    speed, limited = ctx.design_speed_eas("VC", h)
    assert float(speed) == vc and bool(limited)
