"""Structural checks shared by the loads rules of Subpart C (regulation content, no rule here): the factor of safety
(§25.303), the limit/ultimate comparison of a condition's loads with the declared capability (§25.305), the
control-system stops the loads manoeuvres deflect to (or the deflection a §25.397 pilot force holds), the design
speeds a manoeuvre starts from and the §25.337 limit manoeuvring load factor at a speed."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from certkit.atmosphere import RHO0, speed_of_sound
from certkit.engine.conditions import speed_as
from certkit.engine.registry import Criterion
from certkit.engine.results import Finding
from certkit.engine.results_json import RoundedRows
from certkit.models.control_force import control_force_model
from certkit.models.flight import control_limits
from certkit.models.loads.capability import worst_margin, worst_state
from certkit.models.loads.model import QUANTITIES
from certkit.units import LBF

NO_CAPABILITY = "no structural capability declared"
SAFETY = {"ultimate_factor": Criterion(1.5, "", "14 CFR 25.303", "factor of safety: ultimate load = 1.5 × limit load")}


def control_stops(ctx, control: str) -> tuple[float, float]:
    """(min, max) rad of ``control``'s control-system stops (``travel`` in the aircraft file). The loads manoeuvres
    of §§25.331(c), 25.349 and 25.351 deflect to them unless a §25.397 pilot-force limit is reached first; trim and
    controllability margins keep the narrower ``design_limits``."""
    return control_limits(ctx.aircraft, design=False)[control]


def entry_speeds(ctx, h: float, names) -> dict[str, float]:
    """EAS (m/s) of the named design speeds at altitude h, each limited by its Mach counterpart; VA
    need not exceed VC (§25.335(c)), so it is capped at the Mach-limited VC."""
    out = {}
    vc = ctx.design_speed_eas_at("VC", h)
    for name in names:
        v = ctx.design_speed_eas_at(name, h)
        out[name] = min(v, vc) if name == "VA" else v
    return out


def station_summary(loads_peaks: np.ndarray, stations) -> RoundedRows:
    """Finding details, computed when written: max/min of shear (kN), bending and torsion (kN·m) at each station of
    the peaks (2, 3, S)."""
    return RoundedRows(_summary_keys(tuple(stations)), np.array(loads_peaks, dtype=float), _station_rows, 1)


def _station_rows(peaks: np.ndarray) -> np.ndarray:
    """(N, 2, 3, S) min/max peaks → (N, 3 S, 2) rows of (max, min) in kN, station by station, quantity by quantity."""
    max_min = peaks[:, 1::-1] / 1e3
    return max_min.transpose(0, 3, 2, 1).reshape(peaks.shape[0], -1, 2)


@lru_cache(maxsize=64)
def _summary_keys(stations: tuple) -> tuple:
    """The :func:`station_summary` keys, station by station."""
    return tuple(
        f"{station} {quantity} max/min (kN{'·m' if q else ''})"
        for station in stations
        for q, quantity in enumerate(QUANTITIES)
    )


def capability_finding(
    cond,
    check: str,
    surface: str,
    peaks: np.ndarray,
    stations,
    capabilities,
    ultimate_factor,
    *,
    found_margin=None,
    **details,
) -> Finding:
    """One finding per condition: the smallest margin of the limit and ultimate loads against the
    capabilities (§25.303, §25.305), or not evaluated without a capability (the loads as details); ``found_margin``:
    that margin when the caller has it already (:func:`critical_state_finding`)."""
    worst = found_margin
    if worst is None and capabilities:
        worst = worst_margin(capabilities, surface, stations, peaks, ultimate_factor)
    if worst is None:
        reason = f"{NO_CAPABILITY} for the {surface.replace('_', ' ')} stations" if capabilities else NO_CAPABILITY
        finding = Finding.not_evaluated(cond, check, reason, **details)
    else:
        m, cap = worst
        unit = "N" if cap.quantity == "shear" else "N·m"
        finding = Finding.compare(
            cond,
            f"{check}: {m.check} {cap.quantity} at {cap.station} ({m.sense})",
            m.load,
            m.allowable,
            at_least=False,
            unit=unit,
            **details,
        )
    finding.written_details = station_summary(peaks, stations)
    return finding


def critical_state_finding(
    cond,
    check: str,
    surface: str,
    peaks_by_state: np.ndarray,
    stations,
    capabilities,
    ultimate_factor,
    state_details,
    **details,
) -> Finding:
    """:func:`capability_finding` of the state (e.g. the fuel state) with the smallest normalised margin among
    ``peaks_by_state`` (M, 2, 3, S); ``state_details(j)`` → the details naming state j. Without a capability, the
    loads reported are the envelope over the states (and no state is named)."""
    peaks_by_state = np.asarray(peaks_by_state, dtype=float)
    if len(peaks_by_state) == 1:
        return capability_finding(
            cond,
            check,
            surface,
            peaks_by_state[0],
            stations,
            capabilities,
            ultimate_factor,
            **details,
            **state_details(0),
        )
    found = worst_state(capabilities, surface, stations, peaks_by_state, ultimate_factor) if capabilities else None
    if found is None:
        envelope = np.stack([np.fmin.reduce(peaks_by_state[:, 0]), np.fmax.reduce(peaks_by_state[:, 1])])
        return capability_finding(cond, check, surface, envelope, stations, capabilities, ultimate_factor, **details)
    best, margin = found
    return capability_finding(
        cond,
        check,
        surface,
        peaks_by_state[best],
        stations,
        capabilities,
        ultimate_factor,
        found_margin=margin,
        **details,
        **state_details(best),
    )


def beyond_mach_range(loads, mach: float) -> str | None:
    """The reason a condition at Mach ``mach`` is not evaluated when it lies beyond the Mach breakpoints of the strip
    loads model ``loads`` (the airplane's aerodynamic tables share them): its loads and lift would be extrapolated
    (held at the last breakpoint) — None within the range."""
    top = loads["wing"].top_mach
    if mach <= top + 1e-3:
        return None
    return (
        f"M {mach:.3f} is beyond the aerodynamic and strip loads model's Mach range (up to M {top:.2f}): its lift "
        f"and loads would be extrapolated, not computed"
    )


def set_aside_finding(cond, check: str, reason: str, peaks=None, stations=(), **details) -> Finding:
    """A not-evaluated finding with ``reason`` that still reports the loads computed (``peaks`` (2, 3, S) or, per state,
    (M, 2, 3, S): their envelope) as :func:`capability_finding` does."""
    finding = Finding.not_evaluated(cond, check, reason, **details)
    if peaks is not None:
        peaks = np.asarray(peaks, dtype=float)
        if peaks.ndim == 4:
            peaks = np.stack([np.fmin.reduce(peaks[:, 0]), np.fmax.reduce(peaks[:, 1])])
        finding.written_details = station_summary(peaks, stations)
    return finding


def condition_mach(cond) -> float:
    """Flight Mach number of a condition (its speed and altitude, standard atmosphere)."""
    return float(speed_as(cond, "TAS") / float(speed_of_sound(cond.altitude or 0.0)))


def maneuver_limit_load_factor(ctx, v_eas: float, h: float, positive: bool) -> float:
    """The §25.337 limit manoeuvring load factor of the declared envelope at EAS ``v_eas`` and altitude ``h``:
    the positive factor up to VD; the negative factor up to VC, varying linearly to zero at VD (§25.337(c),
    VC and VD Mach-limited at the altitude)."""
    lf = ctx.aircraft.envelope.limit_load_factors
    if positive:
        return float(lf.positive)
    v = entry_speeds(ctx, h, ["VC", "VD"])
    vc, vd = v["VC"], v["VD"]
    if v_eas <= vc or vd <= vc:
        return float(lf.negative)
    return float(lf.negative) * max(vd - v_eas, 0.0) / (vd - vc)


def force_limited_deflection(ctx, control: str, conditions, trim, stop, force_limit_lbf):
    """The deflection a sudden cockpit input reaches from each trimmed condition: the control-system stop ``stop``
    (rad, scalar or per condition; its sign gives the direction) or, with a force model of ``control`` declared
    (:mod:`certkit.models.control_force`), the deflection the limit pilot force ``force_limit_lbf`` holds from the
    trim ``trim`` (rad), whichever is smaller in magnitude. The local angle of attack is the trim's at the instant
    of the input, so its hinge-moment term cancels against the trim's; q̄ from each condition's EAS.
    Returns (deflection, force_limited flags) — the flags None without a model."""
    trim = np.asarray(trim, dtype=float)
    stop = np.broadcast_to(np.asarray(stop, dtype=float), trim.shape)
    model = control_force_model(ctx.aircraft, control)
    if model is None:
        return stop.copy(), None
    qbar = 0.5 * RHO0 * np.array([speed_as(c, "EAS") for c in conditions]) ** 2
    force = np.sign(stop - trim) * np.asarray(force_limit_lbf, dtype=float) * LBF
    at_force = model.deflection_at_force(force, qbar, 0.0, trim=(trim, 0.0))
    limited = np.abs(at_force - trim) < np.abs(stop - trim)
    return np.where(limited, at_force, stop), limited
