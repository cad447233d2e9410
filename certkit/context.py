"""The Context: the aircraft and its shared models, built lazily and memoised.

Two rules that need the same model evaluation (a trim, a stall speed, an aerodynamic model of a
configuration) compute it once per run and process. Rules compute through the Context; models
know nothing of regulations.
"""

from __future__ import annotations

from typing import Callable, Hashable, TypeVar

import numpy as np

from certkit.aircraft import Aircraft, LoadedAircraft
from certkit.atmosphere import convert_speed

T = TypeVar("T")

#: the Mach number that limits each design speed at altitude
MACH_OF = {"VC": "MC", "VD": "MD", "VMO": "MMO"}


class Context:
    def __init__(self, loaded: LoadedAircraft):
        self.loaded = loaded
        self.aircraft: Aircraft = loaded.model
        self._memo: dict[Hashable, object] = {}
        self.notes: list[str] = []
        self.hits = 0
        self.misses = 0

    def memo(self, key: Hashable, compute: Callable[[], T]) -> T:
        """Return the cached value of ``key``, computing it once."""
        try:
            value = self._memo[key]
            self.hits += 1
            return value  # type: ignore[return-value]
        except KeyError:
            self.misses += 1
            value = self._memo[key] = compute()
            return value

    def lookup(self, dotted: str) -> object:
        """The aircraft-file value at ``speeds.VMC`` / ``configurations.landing.CLmax`` (None if absent)."""
        node: object = self.aircraft
        for part in dotted.split("."):
            if node is None:
                return None
            if isinstance(node, dict):
                node = node.get(part)
            else:
                node = getattr(node, part, None)
        if isinstance(node, (dict, list)) and not node:
            return None
        return node

    def missing(self, paths: tuple[str, ...]) -> list[str]:
        return [p for p in paths if self.lookup(p) is None]

    # --- shared models (each lazily built and memoised) ---------------------------------

    def aero(self, configuration: str):
        """The aerodynamic model of ``configuration`` (:mod:`certkit.models.aero.airplane`), built once;
        the vortex lattice is shared by every configuration."""
        from certkit.models.aero.airplane import build_airplane_aero, lattice_derivatives

        def build():
            declared = configuration in self.aircraft.aerodynamics.derivative_tables
            lattice = None if declared else self.memo("lattice_derivatives", lambda: lattice_derivatives(self.aircraft))
            return build_airplane_aero(self.aircraft, configuration, lattice=lattice)

        return self.memo(("aero", configuration), build)

    def clmax(self, configuration: str) -> float | None:
        cfg = self.aircraft.configurations.get(configuration)
        return None if cfg is None else cfg.CLmax

    def wing_lift_slope(self, mach: float) -> float:
        """Wing lift-curve slope per radian (DATCOM/Polhamus; see :mod:`certkit.models.aero.planform`)."""
        from certkit.models.aero.planform import lift_curve_slope, sweep_at

        w = self.aircraft.geometry.wing
        key = ("wing_lift_slope", round(float(mach), 4))
        return self.memo(key, lambda: lift_curve_slope(
            w.aspect_ratio, sweep_at(0.5, w.sweep_quarter_chord, w.aspect_ratio, w.taper), float(mach)))

    def design_speed_eas(self, name: str, altitude) -> tuple[np.ndarray, np.ndarray]:
        """Declared design speed ``name`` (VC, VD, VMO, VB, VA …) as EAS (m/s) at ``altitude``, limited by
        its Mach counterpart (MC, MD, MMO) where declared; returns (speed, mach_limited)."""
        h = np.asarray(altitude, dtype=float)
        speed = getattr(self.aircraft.speeds, name)
        mach = getattr(self.aircraft.speeds, MACH_OF.get(name, ""), None)
        eas = np.full(h.shape, np.inf) if speed is None else convert_speed(speed.value, speed.kind, "EAS", h)
        eas_m = np.full(h.shape, np.inf) if mach is None else convert_speed(mach, "MACH", "EAS", h)
        if speed is None and mach is None:
            raise ValueError(f"speeds.{name} is not declared")
        return np.minimum(eas, eas_m), eas_m < eas
