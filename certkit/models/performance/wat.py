"""Weight–altitude–temperature (WAT) evaluation of steady climbs: the ambient corners of a takeoff and landing
envelope, and the weight at which a climb gradient reaches a required value.

Off-standard days need no change to the trims. At a given calibrated airspeed and pressure altitude the Mach number
follows from the impact and static pressures alone, and q̄ = ½ρV² = ½γ p M² (γ = 1.4), so the aerodynamic forces of
a steady trim at (CAS, pressure altitude) are the same on every day; the temperature changes the true airspeed
(hence the rate of climb, not the gradient sin γ = (T − D)/W, Anderson, *Aircraft Performance and Design*, 1999,
eq. 5.12) and the engines' thrust. A climb on a day ISA + ΔT is therefore the standard-day trim at the same pressure
altitude and CAS with the thrust of that day (:func:`certkit.models.propulsion.engine.temperature_thrust_ratio`).
Not modelled: the Reynolds-number change of skin friction (ν grows about 1 % per 2 K: a few tenths of a percent of
the drag).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit import atmosphere as isa


@dataclass(frozen=True)
class Ambient:
    """A pressure altitude (m) and an ambient temperature (K)."""

    pressure_altitude: float
    temperature: float

    @property
    def delta_isa(self) -> float:
        return self.temperature - float(isa.temperature(self.pressure_altitude))

    def label(self) -> str:
        return (
            f"{self.pressure_altitude / 0.3048:,.0f} ft, {self.temperature - 273.15:+.1f} °C "
            f"(ISA{self.delta_isa:+.1f} K)"
        )


def hot_limit(env, h: float) -> float:
    """The envelope's hottest temperature (K) at pressure altitude ``h``: temperature_max, or the ISA-deviation line
    where that is lower."""
    t = env.temperature_max
    if env.isa_deviation_max is not None:
        t = min(t, float(isa.temperature(h)) + env.isa_deviation_max)
    return t


def envelope_corners(env) -> list[Ambient]:
    """The corners to evaluate: ``altitude_points`` pressure altitudes evenly over the envelope (and sea level when
    inside it), each at the coldest temperature, ISA (when inside the range) and the hot limit."""
    alts = np.linspace(env.pressure_altitude_min, env.pressure_altitude_max, env.altitude_points)
    if env.pressure_altitude_min < 0.0 < env.pressure_altitude_max:
        alts = np.append(alts, 0.0)
    out = []
    for h in sorted(set(float(a) for a in alts)):
        hot = hot_limit(env, h)
        temps = {env.temperature_min, hot}
        standard = float(isa.temperature(h))
        if env.temperature_min < standard < hot:
            temps.add(standard)
        out += [Ambient(h, t) for t in sorted(temps) if t <= hot]
    return out


def weight_for_gradient(weight, thrust, gradient, required):
    """The weight at which a steady climb's gradient would be ``required``, from one climb at ``weight`` (N) with
    ``thrust`` (N, operating engines) and ``gradient``: with the speed scaled as √W (the speed schedule at a fixed
    multiple of the stall speed) CL and so D/W stay fixed, and γ = T/W − D/W gives W' = T / (required + T/W − γ).
    Exact for a thrust independent of speed; a few repetitions absorb the rest (Mach, the thrust lapse)."""
    weight, thrust = np.asarray(weight, dtype=float), np.asarray(thrust, dtype=float)
    return thrust / (required + thrust / weight - np.asarray(gradient, dtype=float))
