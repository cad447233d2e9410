"""Thrust and fuel flow of the installed engines for the mission analysis.

Thrust: the flight model's engine (:func:`certkit.models.flight.thrust_function` — the declared deck, or the
parametric high-bypass turbofan scaled to the declared static thrust), per engine, times the number of engines.

Fuel flow: thrust × TSFC, with the TSFC variation with Mach number and altitude of Mattingly (*Aircraft Engine
Design*, 2nd ed., AIAA 2002, §2.3.2, high-bypass turbofan): TSFC ∝ (0.4 + 0.45 M) √θ. Mattingly's constant
describes a 1980s engine; ``mission.tsfc`` declares the cruise TSFC of the real engine at one Mach number and
altitude, and the whole TSFC model is scaled by one factor so that it gives that value there (the shape in Mach
and altitude is kept). Without a declaration the factor is 1 and the result says so. TSFC is taken independent
of the throttle setting (part-power TSFC rises somewhat at low settings: idle descent and taxi fuel are
therefore estimates on the low side). A declared deck's fuel-flow table is not used here. The declared performance
calibration's ``fuel_flow_factor`` (installation losses: customer bleed and power off-take, which an uninstalled
cycle TSFC leaves out) multiplies the result.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from certkit import atmosphere as isa
from certkit.models.flight import thrust_function
from certkit.units import G0


def mattingly_tsfc(h, mach) -> np.ndarray:
    """Mattingly's high-bypass turbofan TSFC, kg/(N s): (0.4 + 0.45 M) √θ per hour (lb/lbf/h)."""
    theta = isa.temperature(h) / isa.T0
    return (0.4 + 0.45 * np.asarray(mach, dtype=float)) * np.sqrt(theta) / 3600.0 / G0


@dataclass
class EngineFuel:
    """All engines of the airplane: ``thrust(throttle, h, mach)`` (N, all engines), ``tsfc(h, mach)``
    (kg/(N s)) and ``fuel_flow(thrust, h, mach)`` (kg/s)."""

    engine_thrust: object  # thrust(throttle, h, mach) -> N of one engine
    engines: int
    factor: float = 1.0
    notes: list[str] = field(default_factory=list)

    @classmethod
    def of(cls, aircraft) -> "EngineFuel":
        thrust, source = thrust_function(aircraft)
        n = len(aircraft.propulsion.engines)
        cal = aircraft.mission.tsfc if aircraft.mission is not None else None
        installed = getattr(aircraft, "calibration", None)
        loss = 1.0 if installed is None else float(installed.fuel_flow_factor)
        extra = (
            []
            if loss == 1.0
            else [
                f"fuel flow × {loss:.4f}: installation losses of the declared performance calibration "
                f"({installed.fuel_flow_source or installed.source})"
            ]
        )
        if cal is None:
            return cls(
                thrust,
                n,
                loss,
                [
                    f"thrust: {source}; TSFC: Mattingly's high-bypass model, not calibrated (declare mission.tsfc)",
                    *extra,
                ],
            )
        factor = float(cal.value / mattingly_tsfc(cal.altitude, cal.mach))
        return cls(
            thrust,
            n,
            factor * loss,
            [
                f"thrust: {source}; TSFC: Mattingly's Mach/altitude variation scaled by {factor:.3f} to "
                f"{cal.value * 3600 * G0:.3f} lb/lbf/h at M {cal.mach:.2f}, {cal.altitude / 0.3048:.0f} ft "
                f"({cal.source})",
                *extra,
            ],
        )

    def thrust(self, throttle, h, mach) -> np.ndarray:
        return self.engines * np.asarray(self.engine_thrust(throttle, h, mach), dtype=float)

    def tsfc(self, h, mach) -> np.ndarray:
        return self.factor * mattingly_tsfc(h, mach)

    def fuel_flow(self, thrust, h, mach) -> np.ndarray:
        return self.tsfc(h, mach) * np.asarray(thrust, dtype=float)

    def allowance_fuel(self, allowance) -> float:
        """Fuel (kg) of an :class:`certkit.aircraft.model.EngineAllowance`: its time at its throttle and Mach,
        sea level, standard day, all engines."""
        t = self.thrust(allowance.throttle, 0.0, allowance.mach)
        return float(self.fuel_flow(t, 0.0, allowance.mach) * allowance.time)
