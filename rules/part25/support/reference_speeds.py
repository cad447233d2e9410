"""Declared speeds, reference stall speeds and ratio checks between speeds, shared by the Subpart B rules that
compare the airplane's declared operating speeds with their regulatory minima (§§25.103, 25.107, 25.121, 25.125,
25.143 …).

VSR (§25.103) is the declared ``speeds.VSR.<configuration>`` where given (scaled with √W from the configuration's
reference weight), else the 1-g stall speed from the configuration's declared trimmed CLmax,
V = √(2W / (ρ₀ S CLmax)) (EAS; equal to CAS at sea level, where the stall is evaluated).

A ratio check is a finding for ``numerator / denominator ≥ factor`` with the ratio as value and margin (ratio less
factor; ≥ 0 complies), or ``not_evaluated`` naming the speeds that are missing. Speeds are CAS at sea level (m/s).
"""

from __future__ import annotations

import math

from certkit.atmosphere import RHO0, convert_speed
from certkit.engine.results import Finding
from certkit.models.performance.stall import stall_speed_eas
from certkit.units import G0, KN


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
    return Finding.compare(
        cond.with_(speed=speeds[numerator], speed_kind="CAS", speed_name=numerator),
        check,
        value,
        factor,
        at_least=True,
        unit="ratio",
        **{numerator: speeds[numerator], denominator: speeds[denominator]},
        **({"basis": basis} if basis else {}),
    )


#: the weight at which a declared VSR of each configuration is read (the weight the configuration is used at)
REFERENCE_WEIGHT = {"takeoff": "MTOW", "clean": "MTOW", "approach": "MLW", "landing": "MLW"}


def reference_weight(ctx, configuration: str) -> tuple[str, float]:
    """(name, kg) of the weight a configuration is used at: MLW for approach/landing, MTOW otherwise."""
    name = REFERENCE_WEIGHT.get(configuration, "MTOW")
    mass = getattr(ctx.aircraft.mass, name) or ctx.aircraft.mass.MTOW
    return name, float(mass)


def computed_stall_speed(ctx, configuration: str, mass) -> float:
    """1-g stall speed (m/s EAS) from the declared trimmed CLmax of ``configuration`` at ``mass`` (kg)."""
    clmax = ctx.clmax(configuration)
    if clmax is None:
        raise ValueError(f"configurations.{configuration}.CLmax is not declared")
    return float(stall_speed_eas(mass, ctx.aircraft.reference.area, clmax))


def reference_stall_speed(ctx, configuration: str, mass) -> tuple[float, str]:
    """VSR (m/s EAS, = CAS at sea level) of ``configuration`` at ``mass`` and where it comes from.

    A declared ``speeds.VSR.<configuration>`` is read at the configuration's reference weight and
    scaled with √(W/W_ref) (constant CL); otherwise the 1-g stall speed from CLmax is used.
    """
    declared = ctx.aircraft.speeds.VSR.get(configuration)
    if declared is not None:
        name, w_ref = reference_weight(ctx, configuration)
        v = float(convert_speed(declared.value, declared.kind, "EAS", 0.0)) * math.sqrt(mass / w_ref)
        return v, f"declared speeds.VSR.{configuration} at {name}, scaled with √W"
    return computed_stall_speed(ctx, configuration, mass), f"1-g stall speed from configurations.{configuration}.CLmax"


#: §25.207(c): stall warning begins at least 5 kn or 5 % CAS above the speed at which the stall is identified;
#: (d): at least 3 kn or 3 % CAS above VSR (in straight flight, engines idling) — whichever is greater in each
WARNING_MARGINS = ((5.0, 0.05, "§25.207(c)"), (3.0, 0.03, "§25.207(d)"))


def stall_warning_cl(ctx, configuration: str, mass) -> tuple[float, str]:
    """The trimmed 1-g lift coefficient at which stall warning begins in ``configuration`` at ``mass`` (kg), and its
    basis: the declared ``stall_warning`` (a CL, or VSW as a ratio to VSR), else the latest warning §25.207 allows,
    VSW = VSR + max(5 kn, 5 %) (the stall identified at VSR, §25.207(c), which also meets (d)'s 3 kn / 3 %);
    CL = W / (½ ρ₀ VSW² S)."""
    declared = getattr(ctx.aircraft.configurations.get(configuration), "stall_warning", None)
    if declared is not None and declared.CL is not None:
        return float(declared.CL), f"declared configurations.{configuration}.stall_warning.CL"
    vsr, basis = reference_stall_speed(ctx, configuration, mass)
    if declared is not None:
        vsw, how = declared.speed_ratio * vsr, (f"declared VSW = {declared.speed_ratio:g} VSR ({basis})")
    else:
        vsw = max(vsr + max(kn * KN, frac * vsr) for kn, frac, _ in WARNING_MARGINS)
        how = (
            f"no stall warning declared: the latest §25.207(c) allows, VSW = VSR + max(5 kn, 5 %) = {vsw / KN:.1f} kn "
            f"with the stall identified at VSR ({basis})"
        )
    return float(mass * G0 / (0.5 * RHO0 * vsw**2 * ctx.aircraft.reference.area)), how


def declared_eas(ctx, name: str, h: float) -> float:
    """A declared speed (m/s EAS at altitude ``h``)."""
    s = getattr(ctx.aircraft.speeds, name)
    return float(convert_speed(s.value_at(h), s.kind, "EAS", h))
