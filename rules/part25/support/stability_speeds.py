"""The speed ranges shared by the stability rules §§25.171–25.181 (regulation content, no rule here): the flight
phases and their configurations, the maximum allowable speed of a configuration (VMO/MMO clean; VFE, and VLE with
the gear down), the top of the §25.173/§25.177 ranges (VFC/MFC, §25.253(b)), the refinement of a scheduled
condition's ``speed_point`` into a calibrated airspeed and the flap altitude limit.
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np
from certkit_rules.part25.support.control_speeds import vsr_cas

from certkit.atmosphere import convert_speed
from certkit.engine.registry import Criterion
from certkit.engine.results import Finding

#: certkit configuration of each flight phase the stability paragraphs name
PHASES = {"takeoff": "takeoff", "cruise": "clean", "landing": "landing"}
SPEED_POINTS = ("1.13 VSR", "mid", "max allowable")


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


VFC_FLOOR = (
    "VFC/MFC not declared: the least §25.253(b) allows, midway between VMO/MMO and VDF/MDF, with VD/MD "
    "for VDF/MDF (which may not exceed them), each Mach-limited at the altitude"
)


def stability_limit_cas(ctx, configuration: str, h: float = 0.0) -> tuple[float, str]:
    """Top of the §25.173(a) and §25.177(a), (c) speed ranges (m/s CAS) and its basis: VFE/VLE for an extended
    configuration (its maximum allowable speed); clean, VFC/MFC where declared, else :data:`VFC_FLOOR`."""
    if (
        configuration in ctx.aircraft.speeds.VFE
        or getattr(ctx.aircraft.configurations[configuration], "gear", "up") == "down"
    ):
        return max_allowable_cas(ctx, configuration, h), "VFE/VLE of the configuration"
    sp = ctx.aircraft.speeds
    if sp.VFC is not None or sp.MFC is not None:
        vfc, _ = ctx.design_speed_eas("VFC", h)
        return float(convert_speed(float(vfc), "EAS", "CAS", h)), "declared VFC/MFC"
    vmo, _ = ctx.design_speed_eas("VMO", h)
    vd, _ = ctx.design_speed_eas("VD", h)
    return float(convert_speed(0.5 * (float(vmo) + float(vd)), "EAS", "CAS", h)), VFC_FLOOR


def speed_at_point(ctx, cond, point: str, low_factor: float = 1.13) -> tuple[float, float, float]:
    """(speed, low, high) m/s CAS of ``point`` ("1.13 VSR" = the low end, "mid", "max allowable", "VFC" = the top of
    the stability ranges (:func:`stability_limit_cas`), or a multiple "1.3 VSR") for the condition."""
    h = cond.altitude or 0.0
    low = low_factor * vsr_cas(ctx, cond.configuration, cond.mass, h)
    high = max_allowable_cas(ctx, cond.configuration, h)
    if point == "VFC":
        return stability_limit_cas(ctx, cond.configuration, h)[0], low, high
    named = {"1.13 VSR": low, "mid": 0.5 * (low + high), "max allowable": high}
    v = named[point] if point in named else float(point.split()[0]) * low / low_factor  # "1.3 VSR"
    return v, low, high


def _throttle_limited(result) -> bool:
    return not result.converged and any(e.control == "throttle" for e in result.limits_exceeded)


#: a flight path within this of level (rad; 0.006°, a gradient of 0.01 %) is level: a level trim that needs full thrust
#: to within the trim's own tolerance can report "more than full throttle" while the full-thrust trim then climbs by
#: 1e-6 rad — the condition is at the level-flight ceiling, and the full-thrust trim stands for it (numerical choice)
LEVEL_PATH_TOLERANCE = 1e-4


def steady_flight_trims(ctx, conds, kind: str = "straight", beta=None):
    """Trims of ``conds`` (one configuration) in the steady flight the airplane can hold at each condition: level
    flight, or, where level flight needs more than full thrust (beyond the weight's level-flight ceiling), the steady
    descent at full thrust, or where it needs less than idle, the steady climb at idle — the flight path solved by the
    trim. A level trim that ran into a throttle stop does not say reliably which one (its iterate may end at either
    bound), so full thrust is tried first and kept where it descends, then idle where it climbs (each to within
    :data:`LEVEL_PATH_TOLERANCE` of level: at the ceiling itself the stop's trim is level flight). ``kind`` and
    ``beta`` (rad, one per condition; steady-heading sideslips) are the trim's. Returns (trim results, throttle per
    condition: None for level flight, else the stop held)."""
    # without sideslips the level trims are the plain ones other procedures ask for (one memoised batch)
    per = {} if beta is None else {"beta": np.broadcast_to(np.asarray(beta, dtype=float), (len(conds),))}
    results = list(ctx.trim(conds, kind=kind, **per).results)
    stops: list[float | None] = [None] * len(conds)
    tol = LEVEL_PATH_TOLERANCE
    for stop, keep in ((1.0, lambda r: r.gamma <= tol), (0.0, lambda r: r.gamma >= -tol)):
        rows = [i for i, r in enumerate(results) if stops[i] is None and _throttle_limited(r)]
        if not rows:
            break
        redo = ctx.trim(
            [conds[i] for i in rows], kind=kind, throttle=stop, **{k: v[rows] for k, v in per.items()}
        ).results
        for i, r in zip(rows, redo):
            if r.converged and keep(r):
                results[i], stops[i] = r, stop
    return results, stops


def flight_described(result, stop) -> str:
    """'level flight', or the steady descent/climb at a throttle stop with its flight-path angle."""
    if stop is None:
        return "level flight"
    gamma = math.degrees(result.gamma)
    path = "descent" if gamma < 0 else "climb"
    return (
        f"steady {path} at {'full' if stop >= 1.0 else 'idle'} thrust, flight path {gamma:+.2f}° (level flight "
        f"needs {'more than full' if stop >= 1.0 else 'less than idle'} thrust)"
    )


def by_configuration(conditions) -> dict[str, list[int]]:
    """Indices of the conditions grouped by configuration (one trim batch each)."""
    groups: dict[str, list[int]] = defaultdict(list)
    for i, c in enumerate(conditions):
        groups[c.configuration].append(i)
    return groups


FLAP_ALTITUDE_SOURCE = (
    "project choice: flaps and gear are not extended above 20,000 ft (Boeing 777 FCOM limitation, "
    "the baseline's class); flap configurations are evaluated below it"
)
#: the criterion of the flap altitude limit (rules that evaluate flap or gear configurations)
FLAP_ALTITUDE = Criterion(6096.0, "m", FLAP_ALTITUDE_SOURCE, "highest altitude of flap configurations")


def above_flap_altitude(ctx, cond, flap_altitude_max: float) -> str | None:
    """Why ``cond`` is not applicable — a flap or gear configuration above ``flap_altitude_max`` (m) — or None."""
    cfg = ctx.aircraft.configurations[cond.configuration]
    extended = cond.configuration != "clean" and (getattr(cfg, "flap", 0) or getattr(cfg, "gear", "up") == "down")
    if extended and (cond.altitude or 0.0) > flap_altitude_max + 1e-6:
        return f"{cond.configuration} configuration above {flap_altitude_max / 0.3048:,.0f} ft (flap altitude limit)"
    return None


def flap_altitude_findings(ctx, cond, flap_altitude_max: float, checks) -> list[Finding]:
    """Not-applicable findings (one per check of ``checks``) of a flap or gear configuration above the flap altitude
    limit (:func:`above_flap_altitude`); none where the condition applies."""
    high = above_flap_altitude(ctx, cond, flap_altitude_max)
    return [Finding.not_applicable(cond, check, high) for check in checks] if high else []


def refine_speeds(ctx, conditions, flap_altitude_max: float, low_factor: float = 1.13, check: str = "speed range"):
    """Each condition refined to the CAS of its ``speed_point`` (the ``extra`` axis), or a not-applicable
    finding for a flap/gear configuration above ``flap_altitude_max`` (m). Returns (refined, findings)."""
    refined, findings = [], []
    for cond in conditions:
        high = above_flap_altitude(ctx, cond, flap_altitude_max)
        if high:
            findings.append(Finding.not_applicable(cond, check, high))
            continue
        if cond.get("speed_point") == "VFC":
            v, basis = stability_limit_cas(ctx, cond.configuration, cond.altitude or 0.0)
            if basis.startswith("VFE/VLE"):
                findings.append(
                    Finding.not_applicable(
                        cond,
                        check,
                        f"the {cond.configuration} configuration's range ends "
                        "at its VFE/VLE, the 'max allowable' speed point",
                    )
                )
                continue
            refined.append(
                cond.with_(
                    speed=v,
                    speed_kind="CAS",
                    VFC="declared" if basis == "declared VFC/MFC" else "§25.253(b) least: (VMO + VD)/2",
                )
            )
            continue
        v, _, _ = speed_at_point(ctx, cond, cond.get("speed_point", "mid"), low_factor)
        refined.append(cond.with_(speed=v, speed_kind="CAS"))
    return refined, findings
