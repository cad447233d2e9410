"""International Standard Atmosphere (ISO 2533:1975 / ICAO Doc 7488) and airspeed conversions.

Every function takes and returns numpy arrays (or floats) in SI: geopotential altitude h (m),
temperature (K), pressure (Pa), density (kg/m³), speeds (m/s).

Layers up to 20 km: troposphere (lapse −6.5 K/km to 11 km) and the isothermal lower stratosphere
(216.65 K to 20 km), which covers every transport-airplane envelope.

Off-standard days (``delta_isa``, K): h is then the pressure altitude, the pressure is the standard one at h and
the temperature T_ISA(h) + ΔT, so ρ = p/(R T) and a = √(γ R T) — the pressure-altitude/ambient-temperature
convention of flight-manual performance charts (an ISA deviation constant with height).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TypeVar

import numpy as np
import numpy.typing as npt
from numba import njit

from certkit.units import G0

T0 = 288.15  # K
P0 = 101_325.0  # Pa
RHO0 = 1.225  # kg/m³
R_AIR = 287.05287  # J/(kg K)
GAMMA = 1.4
LAPSE = -0.0065  # K/m
H_TROPOPAUSE = 11_000.0
H_MAX = 20_000.0
A0 = float(np.sqrt(GAMMA * R_AIR * T0))  # 340.294 m/s

#: what the functions take: a float or an array of floats (SI)
Values = npt.ArrayLike
#: what they return: an array of floats (0-d for a scalar input)
FloatArray = npt.NDArray[np.float64]
#: a speed conversion f(value, h) -> value
Conversion = Callable[[Values, Values], FloatArray]


class AtmosphereRangeError(ValueError):
    """An altitude outside the modelled layers (−610 m to 20 km)."""


H_MIN = -610.0


@njit(cache=True)
def _first_out_of_range(h: FloatArray) -> int:
    """Index of the first altitude outside [H_MIN, H_MAX] (−1: none; NaN is not flagged)."""
    for i in range(h.shape[0]):
        if h[i] < H_MIN or h[i] > H_MAX:
            return i
    return -1


def _check_range(h: Values) -> None:
    """Raise :class:`AtmosphereRangeError` naming the first altitude outside the modelled layers (a compiled
    scan: the two numpy reductions it replaces cost ~10 µs a call, and the simulations call it at every step)."""
    h = np.asarray(h, dtype=float)
    i = _first_out_of_range(np.ascontiguousarray(h).reshape(-1))
    if i >= 0:
        raise AtmosphereRangeError(
            f"altitude {h.flat[i]:.0f} m is outside the standard atmosphere modelled here ({H_MIN:.0f} m to "
            f"{H_MAX:.0f} m)"
        )


_T11 = T0 + LAPSE * H_TROPOPAUSE
_EXP_TROPO = -G0 / (LAPSE * R_AIR)
_P11 = P0 * (_T11 / T0) ** _EXP_TROPO
_K_STRATO = -G0 / (R_AIR * _T11)


@njit(cache=True, inline="always")
def isa_scalar(h: float) -> tuple[float, float]:
    """(temperature K, pressure Pa) at one altitude (m), no range check: the single implementation
    of the layers, used by the array functions below and by compiled kernels."""
    if h <= H_TROPOPAUSE:
        t = T0 + LAPSE * h
        return t, P0 * (t / T0) ** _EXP_TROPO
    return _T11, _P11 * math.exp(_K_STRATO * (h - H_TROPOPAUSE))


@njit(cache=True)
def _isa_flat(h: FloatArray, which: int) -> FloatArray:
    out = np.empty(h.shape[0])
    for i in range(h.shape[0]):
        out[i] = isa_scalar(h[i])[which]
    return out


#: the layers' values at the scalar altitudes asked so far, (h, which) → value: the rules convert speeds at a few
#: altitudes thousands of times per design (each a fresh 0-d array of the compiled function's own value)
_AT_SCALAR: dict[tuple[float, int], float] = {}
_AT_SCALAR_MAX = 4096
K = TypeVar("K")  # a memo's key


def _remember(memo: dict[K, float], key: K, value: float) -> float:
    """Store ``value`` under ``key`` in one of the scalar memos, emptied when it holds :data:`_AT_SCALAR_MAX` values
    (a bound on the memory of a long study worker)."""
    if len(memo) >= _AT_SCALAR_MAX:
        memo.clear()
    memo[key] = value
    return value


def _isa(h: Values, which: int) -> FloatArray:
    if isinstance(h, float):
        value = _AT_SCALAR.get((h, which))
        if value is not None:
            return np.array(value)
    heights = np.asarray(h, dtype=float)
    _check_range(heights)
    flat: FloatArray = _isa_flat(np.ascontiguousarray(heights).reshape(-1), which)
    if isinstance(h, float):
        _remember(_AT_SCALAR, (h, which), float(flat[0]))
    return flat.reshape(heights.shape)


def temperature(h: Values, delta_isa: Values = 0.0) -> FloatArray:
    """Ambient temperature (K) at (pressure) altitude h on a day ISA + ``delta_isa`` (K)."""
    t = _isa(h, 0)
    off_standard = delta_isa != 0.0 if isinstance(delta_isa, (int, float)) else np.any(delta_isa)
    return t + np.asarray(delta_isa, dtype=float) if off_standard else t


def pressure(h: Values) -> FloatArray:
    return _isa(h, 1)


def density(h: Values, delta_isa: Values = 0.0) -> FloatArray:
    return pressure(h) / (R_AIR * temperature(h, delta_isa))


def speed_of_sound(h: Values, delta_isa: Values = 0.0) -> FloatArray:
    return np.sqrt(GAMMA * R_AIR * temperature(h, delta_isa))


def dynamic_viscosity(h: Values) -> FloatArray:
    """Sutherland's law (ISO 2533)."""
    t = temperature(h)
    return 1.458e-6 * t**1.5 / (t + 110.4)


def density_ratio(h: Values) -> FloatArray:
    return density(h) / RHO0


# --- airspeed conversions -------------------------------------------------------------------


def eas_to_tas(eas: Values, h: Values) -> FloatArray:
    return np.asarray(eas, dtype=float) / np.sqrt(density_ratio(h))


def tas_to_eas(tas: Values, h: Values) -> FloatArray:
    return np.asarray(tas, dtype=float) * np.sqrt(density_ratio(h))


def tas_to_mach(tas: Values, h: Values) -> FloatArray:
    return np.asarray(tas, dtype=float) / speed_of_sound(h)


def mach_to_tas(mach: Values, h: Values) -> FloatArray:
    return np.asarray(mach, dtype=float) * speed_of_sound(h)


def _impact_pressure_from_mach(mach: Values, p: FloatArray) -> FloatArray:
    """Subsonic isentropic impact pressure; Rayleigh pitot formula above Mach 1."""
    m = np.asarray(mach, dtype=float)
    sub = p * ((1.0 + 0.2 * m**2) ** 3.5 - 1.0)
    sup = p * (166.92158 * m**7 / np.maximum(7.0 * m**2 - 1.0, 1e-9) ** 2.5 - 1.0)
    return np.where(m <= 1.0, sub, sup)


def mach_to_cas(mach: Values, h: Values) -> FloatArray:
    """Calibrated airspeed: the sea-level speed giving the same impact pressure."""
    qc = _impact_pressure_from_mach(mach, pressure(h))
    return A0 * np.sqrt(5.0 * ((qc / P0 + 1.0) ** (2.0 / 7.0) - 1.0))


def cas_to_mach(cas: Values, h: Values) -> FloatArray:
    qc = P0 * ((1.0 + 0.2 * (np.asarray(cas, dtype=float) / A0) ** 2) ** 3.5 - 1.0)
    p = pressure(h)
    mach = np.sqrt(5.0 * ((qc / p + 1.0) ** (2.0 / 7.0) - 1.0))
    if np.any(mach > 1.0):  # solve the Rayleigh formula by fixed point (converges in a few steps)
        for _ in range(30):
            m_sup = 0.88128485 * np.sqrt((qc / p + 1.0) * np.maximum(1.0 - 1.0 / (7.0 * mach**2), 0.0) ** 2.5)
            mach = np.where(mach > 1.0, m_sup, mach)
    return mach


#: kind → (speed to TAS, TAS to speed), each f(value, h)
_CONVERSIONS: dict[str, tuple[Conversion, Conversion]] = {
    "TAS": (lambda v, h: np.asarray(v, dtype=float) + 0.0 * np.asarray(h, dtype=float),) * 2,
    "EAS": (eas_to_tas, tas_to_eas),
    "CAS": (lambda v, h: mach_to_tas(cas_to_mach(v, h), h), lambda v, h: mach_to_cas(tas_to_mach(v, h), h)),
    "MACH": (mach_to_tas, tas_to_mach),
}


def _conversion(kind: str, direction: int) -> Conversion:
    try:
        return _CONVERSIONS[kind.upper()][direction]
    except KeyError:
        raise ValueError(f"unknown speed kind {kind!r} (EAS, CAS, TAS or MACH)") from None


def to_tas(speed: Values, kind: str, h: Values) -> FloatArray:
    """Convert a speed of ``kind`` (EAS, CAS, TAS or MACH) at altitude ``h`` to true airspeed."""
    return _conversion(kind, 0)(speed, h)


def from_tas(tas: Values, kind: str, h: Values) -> FloatArray:
    """Convert true airspeed to a speed of ``kind`` (EAS, CAS, TAS or MACH) at altitude ``h``."""
    return _conversion(kind, 1)(tas, h)


#: the conversions of scalar speeds asked so far, (speed, from, to, h, their signs) → value: a design converts about
#: 2,600 scalar speeds, a few hundred distinct (the same design speeds at the same altitudes, condition after condition)
_SPEEDS: dict[tuple[float, str, str, float, float, float], float] = {}


def convert_speed(speed: Values, from_kind: str, to_kind: str, h: Values) -> FloatArray:
    """``speed`` of ``from_kind`` (EAS, CAS, TAS or MACH) as ``to_kind`` at altitude ``h``; a scalar's conversion is
    remembered (the same value, a fresh 0-d array each time; the signs of zeros in the key)."""
    if not (isinstance(speed, float) and isinstance(h, float)):
        return from_tas(to_tas(speed, from_kind, h), to_kind, h)
    key = (speed, from_kind, to_kind, h, math.copysign(1.0, speed), math.copysign(1.0, h))
    value = _SPEEDS.get(key)
    if value is None:
        value = _remember(_SPEEDS, key, float(from_tas(to_tas(speed, from_kind, h), to_kind, h)))
    return np.array(value)
