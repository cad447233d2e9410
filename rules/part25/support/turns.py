"""The details of a coordinated-turn trim, shared by §25.143(h) and §25.147(c) (regulation content, no rule here): the
trim's angles and controls, the load factor n = cos γ / cos φ and the lift coefficient it needs over CLmax."""

from __future__ import annotations

import math

from certkit_rules.part25.support.control_checks import trim_details

from certkit.atmosphere import RHO0, convert_speed
from certkit.engine.conditions import speed_as
from certkit.units import G0


def turn_details(ctx, cond, result, gamma: float, bank: float) -> dict:
    """Trim angles and controls, load factor n = cos γ / cos φ and the lift coefficient it needs over CLmax."""
    n = math.cos(gamma) / math.cos(bank)
    veas = float(convert_speed(speed_as(cond, "TAS"), "TAS", "EAS", cond.altitude or 0.0))
    cl = n * cond.mass * G0 / (0.5 * RHO0 * veas**2 * ctx.aircraft.reference.area)
    out = dict(
        trim_details(result), flight_path_deg=round(math.degrees(gamma), 3), load_factor=round(n, 4), CL=round(cl, 4)
    )
    clmax = ctx.clmax(cond.configuration, speed_as(cond, "MACH"))
    if clmax:
        out["CL_over_CLmax"] = round(cl / clmax, 4)
    return out
