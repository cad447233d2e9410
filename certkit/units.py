"""Unit conversion at the boundary (pint). Inside certkit every number is SI.

``to_si("4927.3 ft^2", "area")`` → 457.76 (m²); a bare number is taken as already SI.
Conversion happens when the aircraft file is read and when a report is written, never in a loop.
"""

from __future__ import annotations

from functools import lru_cache

import pint



def _registry() -> pint.UnitRegistry:
    """pint's registry, its parsed definitions cached in the user's cache folder (a tenth of the start-up
    time); without a writable cache folder, parsed afresh."""
    try:
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=":auto:")
    except OSError:
        return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


ureg = _registry()
ureg.define("knot_ = knot = kn = kt = kts")  # aliases used on flight decks

#: dimension name → (SI unit, pint dimensionality)
DIMENSIONS: dict[str, str] = {
    "length": "m",
    "area": "m**2",
    "mass": "kg",
    "force": "N",
    "speed": "m/s",
    "angle": "rad",
    "time": "s",
    "pressure": "Pa",
    "temperature": "K",
    "inertia": "kg*m**2",
    "moment": "N*m",
    "mass_flow": "kg/s",
    "acceleration": "m/s**2",
    "gearing": "rad/m",  # control gearing: surface angle per metre of cockpit travel
    "stiffness": "N/m",  # feel-spring gradient: force per metre of cockpit travel
    "density": "kg/m**3",
    "areal_density": "kg/m**2",  # mass per unit planform area (structural sizing)
    "angular_rate": "rad/s",
    "mass_per_energy": "kg/J",  # actuator mass per unit work capacity (stall force × stroke)

    "specific_fuel_consumption": "kg/N/s",  # thrust-specific fuel consumption ("0.52 lb/lbf/h")
    "dimensionless": "",
}


class UnitError(ValueError):
    """A quantity whose unit is unknown or of the wrong dimension."""


@lru_cache(maxsize=None)
def _si_unit(dimension: str) -> pint.Unit:
    if dimension not in DIMENSIONS:
        raise KeyError(f"unknown dimension {dimension!r}")
    return ureg.Unit(DIMENSIONS[dimension])


@lru_cache(maxsize=4096)
def _parse_string(text: str, dimension: str) -> float:
    try:
        q = ureg.Quantity(text)
    except Exception as exc:  # pint raises several exception types for malformed text
        raise UnitError(f"cannot read {text!r} as a quantity ({exc.__class__.__name__})") from None
    unit = _si_unit(dimension)
    if not isinstance(q, pint.Quantity):
        q = ureg.Quantity(float(q), "")
    if q.dimensionality != unit.dimensionality:
        expected = DIMENSIONS[dimension] or "no unit"
        raise UnitError(f"{text!r} is not a {dimension} (expected a unit convertible to {expected})")
    return float(q.to(unit).magnitude)


def to_si(value: object, dimension: str) -> float:
    """Convert ``value`` (a number in SI, or a string with a unit) to a float in SI units."""
    if isinstance(value, bool):
        raise UnitError(f"{value!r} is not a {dimension}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        return _parse_string(value.strip(), dimension)
    raise UnitError(f"{value!r} is not a number or a string with a unit")


def from_si(value: float, unit: str) -> float:
    """Convert an SI value to ``unit`` (for reports): ``from_si(174.9, "kn")``."""
    q = ureg.Quantity(value, _base_of(unit))
    return float(q.to(unit).magnitude)


@lru_cache(maxsize=None)
def _base_of(unit: str) -> pint.Unit:
    dim = ureg.Unit(unit).dimensionality
    for name in DIMENSIONS:
        if _si_unit(name).dimensionality == dim:
            return _si_unit(name)
    raise UnitError(f"no SI unit known for {unit!r}")


# Constants (SI) used across models.
G0 = 9.80665  # standard gravity, m/s²  (ISO 2533)
FT = 0.3048
LB = 0.45359237
LBF = LB * G0
KN = 1852.0 / 3600.0
NMI = 1852.0
"""international nautical mile (m)"""
