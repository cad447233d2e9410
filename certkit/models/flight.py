"""The flight model of an aircraft file: aerodynamics + loading + engines → equations of motion.

Builds :class:`certkit.models.dynamics.eom.AircraftModel` for a batch of loading conditions in one
configuration, with each engine at its position (so an inoperative engine gives its asymmetric
yawing moment and windmilling drag), thrust from the declared deck or, without one, the parametric
turbofan scaled to the declared static thrust. Control limits come from the geometry's control
surfaces: the design limits (``design_limits``) by default, the mechanical travel otherwise.
"""

from __future__ import annotations

import numpy as np

from certkit.models.dynamics.eom import AircraftModel, Engine
from certkit.models.propulsion.engine import EngineDeck, ParametricTurbofan, windmill_drag

#: the aero control that moves each trim axis
ROLES = {"pitch": "elevator", "roll": "aileron", "yaw": "rudder"}


def thrust_function(aircraft):
    """``thrust(throttle, h, mach) -> N`` of one engine: the declared deck or the parametric turbofan."""
    p = aircraft.propulsion
    if p.deck is not None:
        d = p.deck
        deck = EngineDeck(d.altitude, d.mach, d.throttle, np.array(d.thrust, dtype=float),
                          None if d.fuel_flow is None else np.array(d.fuel_flow, dtype=float),
                          allow_extrapolation=d.allow_extrapolation, name="propulsion.deck")
        return deck.thrust, "declared engine deck"
    engine = ParametricTurbofan(p.static_thrust)
    return engine.thrust, "parametric high-bypass turbofan scaled to the declared static thrust (Mattingly lapse)"


def engines(aircraft) -> list[Engine]:
    thrust, _ = thrust_function(aircraft)
    g = aircraft.geometry
    inlet = 0.85 * g.nacelle.diameter if g is not None and g.nacelle is not None else None
    drag = windmill_drag(inlet) if inlet else None
    out = []
    for e in aircraft.propulsion.engines:
        ct, st = np.cos(e.thrust_angle), np.sin(e.thrust_angle)
        direction = (ct * np.cos(e.toe_angle), ct * np.sin(e.toe_angle), -st)  # body axes, thrust line tilted up by thrust_angle
        out.append(Engine(e.name, thrust, (e.position.x, e.position.y, e.position.z), direction, drag))
    return out


def control_limits(aircraft, design: bool = True) -> dict[str, tuple[float, float]]:
    """(min, max) in radians of every control surface, design limits where declared."""
    limits: dict[str, tuple[float, float]] = {"throttle": (0.0, 1.0)}
    g = aircraft.geometry
    if g is None:
        return limits
    for surface in (g.wing, g.horizontal_tail, g.vertical_tail):
        for name, c in surface.controls.items():
            lim = c.design_limits if (design and c.design_limits is not None) else c.travel
            limits[name] = (lim.min, lim.max)
    return limits


def flight_model(aircraft, aero_model, loadings, operative=None) -> AircraftModel:
    """Equations of motion for the loadings (:class:`certkit.models.mass.loading.Loading`) of one batch."""
    mass = np.array([ld.properties.mass for ld in loadings])
    cg = np.array([ld.properties.cg for ld in loadings])
    inertia = np.array([ld.properties.inertia for ld in loadings])
    return AircraftModel(aero_model, mass, cg, inertia, engines(aircraft), operative=operative)
