"""The fuel states a wing-loads rule evaluates at each weight (regulation content, no rule here).

§25.343(a): the disposable load combinations include every fuel load from zero fuel to the selected maximum fuel
load. At a condition's weight W the fuel can range from the least the weight allows (zero at or below MZFW, else
W − MZFW: the payload cannot exceed the zero-fuel weight) to the most (the tanks' capacity, ``mass.max_fuel``, or
W − OEW), the payload making up the rest at the condition's CG. The tanks are used in the reverse of their filling
order (the declared order, :func:`certkit.models.mass.loading.fuel_by_tank`): each tank's fuel is piecewise linear
in the total, with breaks where a tank group runs empty; the strip loads are linear in each tank's fuel, so their
extremes over the range lie at the range's ends and at those breaks — the states evaluated here. The airplane's
response (trim, manoeuvre, gust) is computed at the condition's own loading; the fuel state changes the wing's
mass distribution at the same weight and CG (fuel exchanged with payload), whose effect on the pitch inertia is
neglected. No structural reserve fuel (§25.343(a), (b)) is selected: the least fuel is zero at or below MZFW.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from certkit.models.loads.response import LoadEnvelope, fuel_load_units, fuel_state_peaks
from certkit.models.mass.loading import fuel_by_tank, tank_groups


def fuel_range(aircraft, mass: float) -> tuple[float, float]:
    """(least, most) fuel (kg) at weight ``mass`` within §25.343(a)'s range."""
    m = aircraft.mass
    capacity = sum(t.capacity for t in m.fuel_tanks)
    most = min(capacity, m.max_fuel if m.max_fuel else np.inf, mass - m.OEW if m.OEW else mass)
    least = max(0.0, mass - m.MZFW) if m.MZFW else 0.0
    return least, max(most, least)


def fuel_states(aircraft, mass: float) -> tuple[tuple[str, ...], np.ndarray]:
    """The fuel states at weight ``mass``: names and (M, K) kg per state and declared tank (M = 2 + number of tank
    groups, repeated states kept so that every weight has the same count)."""
    if not aircraft.mass.fuel_tanks:
        return ("no fuel tanks declared",), np.zeros((1, 0))
    least, most = fuel_range(aircraft, mass)
    breaks = np.cumsum([sum(t.capacity for t in g) for g in tank_groups(aircraft.mass.fuel_tanks)])
    totals = [least] + [float(np.clip(b, least, most)) for b in breaks] + [most]
    names = [f"least fuel in the §25.343 range, {least:,.0f} kg"]
    for g, b, total in zip(tank_groups(aircraft.mass.fuel_tanks), breaks, totals[1:-1]):
        tanks = " and ".join(t.name for t in g)
        names.append(f"{total:,.0f} kg, tanks up to {tanks} full" if least < b < most else f"{total:,.0f} kg")
    names.append(f"most fuel in the §25.343 range, {most:,.0f} kg")
    fuel = np.array([fuel_by_tank(aircraft, min(total, breaks[-1])) for total in totals])
    return tuple(names), fuel


def fuel_state_table(aircraft, masses) -> tuple[list[tuple[str, ...]], np.ndarray]:
    """:func:`fuel_states` of each weight of ``masses``: the names per condition and (n, M, K) kg."""
    unique = {float(m): None for m in masses}
    for m in unique:
        unique[m] = fuel_states(aircraft, m)
    per = [unique[float(m)] for m in masses]
    k = len(aircraft.mass.fuel_tanks)
    fuel = np.stack([np.asarray(p[1], dtype=float) for p in per]) if per else np.zeros((0, 1, k))
    return [p[0] for p in per], fuel


def fuel_tank_names(ctx) -> tuple[str, ...]:
    """The declared tanks' names, in the order of the fuel arrays."""
    return tuple(t.name for t in ctx.aircraft.mass.fuel_tanks)


def fuel_detail(names, fuel, tank_names, j: int) -> dict:
    """Finding details of fuel state ``j``: its name and each tank's fuel (kg)."""
    return {"fuel_state": names[j], "fuel_kg": {t: round(float(v), 0) for t, v in zip(tank_names, fuel[j])}}


def fuelled_wing_envelope(env: LoadEnvelope, wing_fuel_peaks) -> LoadEnvelope:
    """A copy of ``env`` whose wing peaks are the extremes over the fuel states (the times of the extremes kept from
    the wing without fuel: the fuel changes the loads' size more than their timing)."""
    if wing_fuel_peaks is None:
        return env
    return replace(env, peaks={**env.peaks, "wing": state_envelope(wing_fuel_peaks)})


def state_envelope(peaks_by_state) -> np.ndarray:
    """The extremes over the states of per-state peaks (M, n, 2, 3, S): (n, 2, 3, S), NaN states ignored."""
    return np.stack([np.fmin.reduce(peaks_by_state[:, :, 0]), np.fmax.reduce(peaks_by_state[:, :, 1])], axis=1)


def fuelled_wing(ctx, loads, sim, model, wing_hist, conditions):
    """The wing's loads along ``sim`` in each fuel state of the conditions' weights: (peaks (M, n, 2, 3, S), names per
    condition, (n, M, K) kg) — ``wing_hist`` (nt, n, 3, S) the loads without fuel, NaN where not considered."""
    names, fuel = fuel_state_table(ctx.aircraft, [c.mass for c in conditions])
    return fuel_state_peaks(wing_hist, fuel_load_units(loads, sim, model, "wing"), fuel), names, fuel
