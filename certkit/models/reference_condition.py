"""The aircraft file's ``flight_condition`` in SI: altitude (ISA, from the density when that is given), true
airspeed, Mach number, density, dynamic pressure and g."""

from __future__ import annotations

from dataclasses import dataclass

from scipy.optimize import brentq

from certkit import atmosphere as isa
from certkit.units import G0


@dataclass(frozen=True)
class ReferenceCondition:
    altitude: float
    tas: float
    mach: float
    density: float
    gravity: float

    @property
    def dynamic_pressure(self) -> float:
        return 0.5 * self.density * self.tas**2


def altitude_of_density(rho: float) -> float:
    """The ISA altitude (m, −600 m … 20 km) whose density is ``rho`` (kg/m³); ValueError outside."""
    lo, hi = -600.0, 20_000.0
    f = lambda h: float(isa.density(h)) - rho  # noqa: E731
    if f(lo) < 0 or f(hi) > 0:
        raise ValueError(
            f"density {rho:.4g} kg/m³ lies outside the ISA atmosphere of certkit (−600 m to 20 km: "
            f"{float(isa.density(hi)):.4g} to {float(isa.density(lo)):.4g} kg/m³)"
        )
    return brentq(f, lo, hi, xtol=1e-6)


def declared_speed_at(fc, h: float) -> float:
    """True airspeed (m/s) of the flight condition's speed (or Mach number) at altitude ``h``."""
    if fc.mach is not None:
        return float(isa.mach_to_tas(fc.mach, h))
    return float(isa.to_tas(fc.speed.value, fc.speed.kind, h))


def reference_condition(aircraft) -> ReferenceCondition | None:
    """The declared flight condition, or None without a ``flight_condition`` section."""
    fc = aircraft.flight_condition
    if fc is None:
        return None
    h = fc.altitude if fc.altitude is not None else altitude_of_density(fc.density)
    tas = declared_speed_at(fc, h)
    rho = fc.density if fc.density is not None else float(isa.density(h))
    return ReferenceCondition(float(h), tas, tas / float(isa.speed_of_sound(h)), float(rho), fc.gravity)


def gravity(aircraft) -> float:
    """g of the equations of motion: the flight condition's, else standard gravity."""
    fc = aircraft.flight_condition
    return G0 if fc is None else fc.gravity
