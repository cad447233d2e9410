"""Control-force checks shared by the Subpart B controllability rules (regulation content, no rule here): the rudder
pedal force that holds a trim against a limit (§25.147(a), §25.149(d))."""

from __future__ import annotations

import math

from certkit.models.control_force import trim_state
from certkit.results import Finding
from certkit.units import LBF

_NO_FORCE = ("no control-force model in the aircraft file (control_forces.rudder: hinge moments and gearing, or "
             "artificial feel): the rudder pedal force is not computed")


def pedal_force_finding(ctx, rudder, cond, result, limit_lbf, check=None, **details):
    """Pedal force (lbf) that holds ``result``'s rudder with the rudder trim at neutral, against ``limit_lbf``;
    not evaluated without a rudder force model or a converged trim."""
    check = check or f"(a) rudder pedal force ≤ {limit_lbf:g} lbf"
    if rudder is None:
        return Finding.not_evaluated(cond, check, _NO_FORCE, **details)
    if not result.converged:
        return Finding.not_evaluated(cond, check, "the trim did not converge: no rudder deflection to hold", **details)
    q, a, d = trim_state(ctx.aircraft, "rudder", [result])
    force = float(rudder.force(q, a, d)[0] / LBF)
    return Finding.compare(cond, check, abs(force), limit_lbf, at_least=False, unit="lbf",
                           pedal="left" if force >= 0 else "right", rudder_deg=round(math.degrees(d[0]), 3),
                           fin_alpha_deg=round(math.degrees(a[0]), 3), force_model=rudder.kind, **details)
