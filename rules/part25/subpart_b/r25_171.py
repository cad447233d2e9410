"""§§25.171–25.175 Static longitudinal stability, and the speed ranges shared by the stability rules.

Shared helpers (used by §§25.147, 25.149, 25.177, 25.181 too): the reference stall speed VSR of a
configuration at a weight (1-g stall from the declared CLmax, §25.103(a)), the maximum allowable speed
of a configuration (VMO/MMO clean; VFE, and VLE with the gear down), and the refinement of a scheduled
condition's ``speed_point`` into a calibrated airspeed.
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from certkit.atmosphere import convert_speed
from certkit_rules.part25.subpart_b.r25_103 import reference_stall_speed

#: certkit configuration of each flight phase the stability paragraphs name
PHASES = {"takeoff": "takeoff", "cruise": "clean", "landing": "landing"}
SPEED_POINTS = ("1.13 VSR", "mid", "max allowable")


def vsr_cas(ctx, configuration: str, mass: float, h: float = 0.0) -> float:
    """Reference stall speed (m/s CAS) of ``configuration`` at ``mass`` at altitude ``h``: §25.103's VSR
    (declared, or the 1-g stall speed from the declared CLmax), as :mod:`r25_103` defines it for Subpart B."""
    eas, _ = reference_stall_speed(ctx, configuration, mass)
    return float(convert_speed(eas, "EAS", "CAS", h))


def max_allowable_cas(ctx, configuration: str, h: float = 0.0) -> float:
    """Maximum allowable speed of the configuration (m/s CAS): VMO/MMO clean; VFE of the flap setting, and
    VLE when the gear is down."""
    sp = ctx.aircraft.speeds
    cfg = ctx.aircraft.configurations[configuration]
    limits = []
    if configuration in sp.VFE:
        limits.append(float(convert_speed(sp.VFE[configuration].value, sp.VFE[configuration].kind, "CAS", h)))
    if getattr(cfg, "gear", None) == "down" and sp.VLE is not None:
        limits.append(float(convert_speed(sp.VLE.value, sp.VLE.kind, "CAS", h)))
    if not limits:
        vmo, _ = ctx.design_speed_eas("VMO", h)
        limits.append(float(convert_speed(float(vmo), "EAS", "CAS", h)))
    return min(limits)


def speed_at_point(ctx, cond, point: str, low_factor: float = 1.13) -> tuple[float, float, float]:
    """(speed, low, high) m/s CAS of ``point`` ("1.13 VSR", "mid", "max allowable") for the condition."""
    h = cond.altitude or 0.0
    low = low_factor * vsr_cas(ctx, cond.configuration, cond.mass, h)
    high = max_allowable_cas(ctx, cond.configuration, h)
    v = {"1.13 VSR": low, "mid": 0.5 * (low + high), "max allowable": high}[point]
    return v, low, high


def by_configuration(conditions) -> dict[str, list[int]]:
    """Indices of the conditions grouped by configuration (one trim batch each)."""
    groups: dict[str, list[int]] = defaultdict(list)
    for i, c in enumerate(conditions):
        groups[c.configuration].append(i)
    return groups


def static_margin(ctx, configuration: str, x_cg, mach) -> np.ndarray:
    """Stick-fixed static margin (fraction of MAC): (x_np − x_cg)/c with the neutral point
    x_np = x_ref − c·Cm_α/CL_α of the configuration's model (airplane frame, X aft)."""
    m = ctx.aero(configuration).model
    ref = m.reference
    x_np = ref.x_ref - ref.chord * m.derivative("Cm_alpha", mach) / m.derivative("CL_alpha", mach)
    return (x_np - np.asarray(x_cg)) / ref.chord


FLAP_ALTITUDE_SOURCE = ("project choice: flaps and gear are not extended above 20,000 ft (Boeing 777 FCOM limitation, "
                        "the baseline's class); flap configurations are evaluated below it")


def refine_speeds(ctx, conditions, flap_altitude_max: float, low_factor: float = 1.13, check: str = "speed range"):
    """Each condition refined to the CAS of its ``speed_point`` (the ``extra`` axis), or a not-applicable
    finding for a flap/gear configuration above ``flap_altitude_max`` (m). Returns (refined, findings)."""
    from certkit.results import Finding

    refined, findings = [], []
    for cond in conditions:
        cfg = ctx.aircraft.configurations[cond.configuration]
        extended = cond.configuration != "clean" and (getattr(cfg, "flap", 0) or getattr(cfg, "gear", "up") == "down")
        if extended and (cond.altitude or 0.0) > flap_altitude_max + 1e-6:
            findings.append(Finding.not_applicable(cond, check, f"{cond.configuration} configuration above "
                                                   f"{flap_altitude_max / 0.3048:,.0f} ft (flap altitude limit)"))
            continue
        v, _, _ = speed_at_point(ctx, cond, cond.get("speed_point", "mid"), low_factor)
        refined.append(cond.with_(speed=v, speed_kind="CAS"))
    return refined, findings
