"""Control checks shared by the Subpart B climb and controllability rules (regulation content, no rule here): each trim
control's deflection against its design limit and the trim's details as reported (§25.121, §25.143, §25.145, §25.147,
§25.161), and the rudder pedal force that holds a trim against a limit (§25.147(a), §25.149(d))."""

from __future__ import annotations

import math

from certkit.engine.results import Finding
from certkit.models.control_force import trim_state
from certkit.units import LBF

_NO_FORCE = (
    "no control-force model in the aircraft file (control_forces.rudder: hinge moments and gearing, or "
    "artificial feel): the rudder pedal force is not computed"
)
#: the trim controls checked against their design limits and reported in a trim's details
CONTROLS = ("elevator", "aileron", "rudder")


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
    return Finding.compare(
        cond,
        check,
        abs(force),
        limit_lbf,
        at_least=False,
        unit="lbf",
        pedal="left" if force >= 0 else "right",
        rudder_deg=round(math.degrees(d[0]), 3),
        fin_alpha_deg=round(math.degrees(a[0]), 3),
        force_model=rudder.kind,
        **details,
    )


def control_findings(cond, prefix: str, result, limits) -> list[Finding]:
    """Each trim control (elevator, aileron, rudder) against its design limit on the side it is deflected:
    margin = limit − |deflection| (deg); the trim's own message when it is beyond."""
    out = []
    for name in CONTROLS:
        if name not in result.controls or name not in limits:
            continue
        d = result.controls[name]
        lo, hi = limits[name]
        message = next((m.message for m in result.limits_exceeded if m.control == name), "")
        hint = next((m.hint for m in result.limits_exceeded if m.control == name), "")
        extra = {"hint": hint} if hint else {}
        if d >= 0:
            f = Finding.compare(
                cond,
                f"{prefix} {name} within design limit",
                math.degrees(d),
                math.degrees(hi),
                at_least=False,
                unit="deg",
                reason=message,
                **extra,
            )
        else:
            f = Finding.compare(
                cond,
                f"{prefix} {name} within design limit",
                math.degrees(d),
                math.degrees(lo),
                at_least=True,
                unit="deg",
                reason=message,
                **extra,
            )
        out.append(f)
    return out


def trim_details(result) -> dict:
    """A trim's angles and controls (deg, 3 decimals), throttles (4 decimals) and stabiliser, as a finding's details."""
    return {
        "alpha_deg": round(math.degrees(result.alpha), 3),
        "bank_deg": round(math.degrees(result.phi), 3),
        "beta_deg": round(math.degrees(result.beta), 3),
        **{f"{k}_deg": round(math.degrees(v), 3) for k, v in result.controls.items() if k in CONTROLS},
        **{k: round(v, 4) for k, v in result.controls.items() if k.startswith("throttle")},
        **({} if result.stabilizer is None else {"stabilizer_deg": round(math.degrees(result.stabilizer), 3)}),
    }
