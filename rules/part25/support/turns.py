"""The details of a coordinated-turn trim, shared by §25.143(h) and §25.147(c) (regulation content, no rule here): the
trim's angles and controls, the load factor n = cos γ / cos φ and the lift coefficient it needs over CLmax; and the
least lift any steady flight at a condition needs, which judges a flight that cannot be trimmed (§25.143(h),
§25.121)."""

from __future__ import annotations

import math

from certkit_rules.part25.support.control_checks import trim_details

from certkit.atmosphere import RHO0, convert_speed
from certkit.engine.conditions import speed_as
from certkit.units import G0

#: no steady flight the rules trim flies a path steeper than this (rad; the approaches 3°, the climbs a few degrees):
#: a numerical bound, so that the lift a flight needs is known without its trim (:func:`least_lift_coefficient`)
STEEPEST_PATH = math.radians(10.0)


def lift_coefficient(ctx, cond, load_factor: float) -> float:
    """The lift coefficient that carries ``load_factor`` × the condition's weight at its speed (n W / q̄ S)."""
    veas = float(convert_speed(speed_as(cond, "TAS"), "TAS", "EAS", cond.altitude or 0.0))
    return load_factor * cond.mass * G0 / (0.5 * RHO0 * veas**2 * ctx.aircraft.reference.area)


def least_lift_coefficient(ctx, cond, bank: float = 0.0) -> float:
    """The least lift coefficient any steady flight at the condition's speed and weight, banked ``bank`` (rad), needs
    on a path no steeper than :data:`STEEPEST_PATH`: beyond the stall warning or CLmax, no trim of it can help."""
    return lift_coefficient(ctx, cond, math.cos(STEEPEST_PATH) / math.cos(bank))


def turn_details(ctx, cond, result, gamma: float, bank: float) -> dict:
    """Trim angles and controls, load factor n = cos γ / cos φ and the lift coefficient it needs over CLmax."""
    n = math.cos(gamma) / math.cos(bank)
    cl = lift_coefficient(ctx, cond, n)
    out = dict(
        trim_details(result), flight_path_deg=round(math.degrees(gamma), 3), load_factor=round(n, 4), CL=round(cl, 4)
    )
    clmax = ctx.clmax(cond.configuration, speed_as(cond, "MACH"))
    if clmax:
        out["CL_over_CLmax"] = round(cl / clmax, 4)
    return out
