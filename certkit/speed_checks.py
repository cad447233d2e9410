"""Declared speeds and ratio checks between speeds, shared by the rules that compare the airplane's declared
operating speeds with their regulatory minima (§§25.107, 25.121, 25.125, 25.143).

A ratio check is a finding for ``numerator / denominator ≥ factor`` with the ratio as value and margin (ratio less
factor; ≥ 0 complies), or ``not_evaluated`` naming the speeds that are missing. Speeds are CAS at sea level (m/s).
"""

from __future__ import annotations

from certkit.atmosphere import convert_speed
from certkit.results import Finding


def declared_cas(ctx, name: str) -> float | None:
    """A declared speed (m/s CAS at sea level), None when absent."""
    s = getattr(ctx.aircraft.speeds, name)
    return None if s is None else float(convert_speed(s.value, s.kind, "CAS", 0.0))


def ratio_check(cond, check, speeds, numerator, denominator, factor, *, basis=""):
    """``numerator/denominator ≥ factor`` as a ratio margin, or not_evaluated naming the missing speed."""
    missing = [n for n in (numerator, denominator) if speeds.get(n) is None]
    if missing:
        return Finding.not_evaluated(cond, check, "needs " + ", ".join(f"speeds.{m}" for m in missing))
    value = speeds[numerator] / speeds[denominator]
    return Finding.compare(cond.with_(speed=speeds[numerator], speed_kind="CAS", speed_name=numerator), check, value,
                           factor, at_least=True, unit="ratio", **{numerator: speeds[numerator],
                                                                   denominator: speeds[denominator]},
                           **({"basis": basis} if basis else {}))
