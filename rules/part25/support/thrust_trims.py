"""Trims at a given thrust, shared by the rules whose conditions state a thrust rather than a flight path
(§25.121, §25.143(h), §25.145(b), §25.147, §25.161): the critical engine, the full thrust of one engine (on an
off-standard day too), the operating engines' total thrust at a throttle setting, the trim at the flight-path angle
that thrust gives (the energy relation sin γ = (T − D)/W of Anderson, *Aircraft Performance and Design*, 1999,
eq. 5.12, the trim solving the flight-path angle at the throttle that gives the thrust) and the steady climb at a
thrust with the critical engine
inoperative (the flight-path angle solved by the trim), and the weight at which that climb has a given gradient
(the WAT limit weight search of §25.121); and the 1-g takeoff trim at V2 whose aerodynamic settings (a movable
stabiliser) a takeoff run holds (§25.107, §25.111, §25.149(e)).
"""

from __future__ import annotations

import math

import numpy as np

from certkit.atmosphere import RHO0, convert_speed, speed_of_sound
from certkit.engine.conditions import cg_limits_at, speed_as
from certkit.models.flight import throttle_for_thrust, thrust_function
from certkit.models.performance.wat import weight_for_gradient
from certkit.models.propulsion.engine import temperature_thrust_ratio
from certkit.units import G0

#: a thrust aim is kept this far inside the throttle range, where the trim's throttle iterate is free (trim.py)
_THROTTLE_INSIDE = 0.003


def critical_engine(ctx) -> str:
    """The critical engine: the outermost engine, left side first (for a symmetric turbofan layout the two
    outboard engines are equally critical; turbofans have no propeller asymmetry)."""
    engines = ctx.aircraft.propulsion.engines
    return min(engines, key=lambda e: (-abs(e.position.y), e.position.y)).name


def altitude_speed_mach(conds):
    """(pressure altitude (m), TAS (m/s), Mach) per condition: the standard day's TAS and speed of sound, so the
    Mach number of the condition's CAS on any day (what the engine models take)."""
    h = np.array([c.altitude or 0.0 for c in conds])
    tas = np.array([speed_as(c, "TAS") for c in conds])
    return h, tas, tas / speed_of_sound(h)


def operating_thrust(ctx, conds, throttle: float = 1.0, fraction: float = 1.0, inoperative: str | None = None):
    """Total thrust (N) of the operating engines at ``throttle`` × ``fraction`` per condition (its altitude
    and Mach), kept just inside the throttle range so that a trim can reach it."""
    thrust, _ = thrust_function(ctx.aircraft)
    live = [e for e in ctx.aircraft.propulsion.engines if e.name != inoperative]
    h, _, mach = altitude_speed_mach(conds)
    per_engine = lambda t: np.asarray(thrust(np.full_like(h, t), h, mach), dtype=float)  # noqa: E731
    lo, hi = per_engine(_THROTTLE_INSIDE), per_engine(1.0 - _THROTTLE_INSIDE)
    return len(live) * np.clip(fraction * per_engine(throttle), lo, hi)


def trim_at_thrust(
    ctx, conds, thrust_aim, *, kind: str = "straight", bank=0.0, inoperative: str | None = None, stabilizer=None
):
    """Trim ``conds`` (one configuration) at the flight-path angle the operating engines' total thrust
    ``thrust_aim`` (N, per condition) gives: each operating engine's throttle is set where it gives its share at the
    condition's altitude and Mach (:func:`~certkit.models.flight.throttle_for_thrust`), and the trim solves the
    flight-path angle — the steady climb or descent of sin γ = (T − D)/W (Anderson, *Aircraft Performance and
    Design*, 1999, eq. 5.12) with the trim's own drag, turn and control deflections included. An aim beyond an
    engine's full thrust flies at full thrust (the residual says by how much). ``stabilizer`` holds a movable
    stabiliser (deflection per condition, :meth:`certkit.engine.context.Context.trim`).
    Returns the TrimResult of each condition, its flight-path angle (rad) and thrust residual (T_aim − T_trim)/W."""
    n = len(conds)
    held = None if stabilizer is None else np.broadcast_to(np.asarray(stabilizer, dtype=float), (n,))
    live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != inoperative]
    weight = np.array([c.mass for c in conds]) * G0
    aim = np.broadcast_to(np.asarray(thrust_aim, dtype=float), (n,)).copy()
    bank = np.broadcast_to(np.asarray(bank, dtype=float), (n,)).copy()
    thrust, _ = thrust_function(ctx.aircraft)
    h, _, mach = altitude_speed_mach(conds)
    throttle = throttle_for_thrust(thrust, aim / len(live), h, mach)
    batch = ctx.trim(conds, kind=kind, bank=bank, throttle=throttle, inoperative=inoperative, stabilizer=held)
    needed = np.array([sum(r.thrust[e] for e in live) for r in batch.results])
    gamma = np.array([r.gamma for r in batch.results])
    return list(batch.results), gamma, (aim - needed) / weight


def full_thrust(ctx, conds):
    """(pressure altitude, TAS, Mach, full thrust of one engine (N), thrust model) per condition: the engine model's
    throttle 1, scaled on an off-standard day (``delta_isa_K``) by the flat-rated temperature lapse."""
    thrust, source = thrust_function(ctx.aircraft)
    h, tas, mach = altitude_speed_mach(conds)
    full = np.asarray(thrust(np.ones_like(h), h, mach), dtype=float)
    delta_isa = np.array([c.get("delta_isa_K", 0.0) for c in conds], dtype=float)
    if np.any(delta_isa):
        flat = ctx.aircraft.propulsion.flat_rating_temperature
        if flat is None:
            raise ValueError("an off-standard day needs propulsion.flat_rating_temperature")
        full = full * temperature_thrust_ratio(h, mach, delta_isa, flat)
        source += f"; temperature lapse above the flat rating {flat - 273.15:.1f} °C (Mattingly)"
    return h, tas, mach, full, source


def oei_climb(ctx, conds, thrust_fraction: float = 1.0, drag_credit=None, engine_out: bool = True):
    """Gradient (tan γ) with the critical engine inoperative at available thrust, for conditions of one
    configuration; returns (gradients, TrimBatch, info). The operating engines' throttle is held where they give
    ``thrust_fraction`` of their full thrust and the trim solves the flight-path angle (a steady climb at that
    thrust). ``drag_credit`` (ΔCD per condition) is drag that the configuration carries but the paragraph removes
    (the gear for §25.121(b)); ``engine_out=False`` gives the all-engines climb at the same thrust setting. A
    condition's ``delta_isa_K`` (off-standard day, altitude its pressure altitude) scales the full thrust by the
    flat-rated engine's temperature lapse; the trim itself is the standard day's (the reasoning is in
    :mod:`certkit.models.performance.wat`)."""
    thrust, _ = thrust_function(ctx.aircraft)
    dead = critical_engine(ctx) if engine_out else None
    live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != dead]
    h, tas, mach, full, thrust_source = full_thrust(ctx, conds)
    weight = np.array([c.mass for c in conds]) * G0
    available = len(live) * thrust_fraction * full
    throttle = throttle_for_thrust(thrust, thrust_fraction * full, h, mach)
    credit = np.zeros_like(h)
    if drag_credit is not None:
        qbar = 0.5 * RHO0 * np.array([float(convert_speed(v, "TAS", "EAS", hh)) for v, hh in zip(tas, h)]) ** 2
        credit = np.asarray(drag_credit, dtype=float) * qbar * ctx.aircraft.reference.area
    batch = ctx.trim(conds, kind="sideslip" if dead else "straight", beta=0.0, throttle=throttle, inoperative=dead)
    gamma = np.array([r.gamma if r.converged else np.nan for r in batch.results])
    needed = np.array([sum(r.thrust[n] for n in live) for r in batch.results])
    residual = (available - needed) / weight
    gamma = gamma + credit / weight  # drag the configuration carries but the segment does not (sin γ = (T − D)/W)
    info = {
        "inoperative": dead,
        "thrust_source": thrust_source,
        "available": available,
        "needed": needed,
        "credit": credit,
        "residual": residual,
        "weight": weight,
    }
    return np.tan(gamma), batch, info


def scaled_speed(cond, mass: float) -> float:
    """The condition's CAS at ``mass`` at the same multiple of the stall speed (∝ √W)."""
    return cond.speed * math.sqrt(mass / cond.mass)


def at_mass(ctx, cond, mass: float, lightest: float, speed_at):
    """``cond`` at another mass, between ``lightest`` (kg) and its own: the speed ``speed_at(cond, mass)`` of that
    weight, the CG kept inside the envelope."""
    mass = float(min(max(mass, lightest), cond.mass)) if math.isfinite(mass) else lightest
    fwd, aft = cg_limits_at(ctx.aircraft, min(mass, max(v.mass for v in ctx.aircraft.cg_envelope.vertices)))
    return cond.with_(mass=mass, x_cg=min(max(cond.x_cg, fwd), aft), speed=speed_at(cond, mass))


def wat_limit_search(
    ctx,
    conds,
    grads,
    available,
    required: float,
    speed_at,
    lightest: float,
    *,
    thrust_fraction,
    drag_credit,
    iterations: int,
    tolerance: float,
) -> list[tuple]:
    """The weight at which the engine-out climb of each condition (gradient ``grads`` and thrust ``available`` (N) at
    its own weight) has the gradient ``required``: two constant-CL steps (:func:`weight_for_gradient`), then secant
    steps through the last two trims, the weight kept between ``lightest`` and the condition's; at most
    ``iterations`` trims of all conditions at once, ending when every gradient is within ``tolerance``. Per condition:
    (condition at the last weight tried, its gradient, its trim, the constant-CL weight estimate there (kg, ≥ 0))."""
    weight = np.array([c.mass for c in conds]) * G0
    history = [(weight / G0, grads)]
    cur = [
        at_mass(ctx, b, m, lightest, speed_at)
        for b, m in zip(conds, weight_for_gradient(weight, available, grads, required) / G0)
    ]
    for k in range(iterations):
        grads, batch, info = oei_climb(ctx, cur, thrust_fraction, np.full(len(cur), drag_credit))
        if k == iterations - 1 or np.all(np.abs(grads - required) < tolerance):
            break
        history.append((np.array([c.mass for c in cur]), grads))
        if len(history) < 3:
            new = weight_for_gradient(info["weight"], info["available"], grads, required) / G0
        else:
            (m0, g0), (m1, g1) = history[-2:]
            slope = np.where(m1 != m0, (g1 - g0) / np.where(m1 != m0, m1 - m0, 1.0), 0.0)
            new = np.where(slope != 0.0, m1 + (required - g1) / np.where(slope != 0.0, slope, 1.0), m1)
        cur = [at_mass(ctx, b, m, lightest, speed_at) for b, m in zip(conds, new)]
    with np.errstate(divide="ignore", invalid="ignore"):
        estimate = weight_for_gradient(info["weight"], info["available"], grads, required) / G0
    estimate = np.where(np.isfinite(estimate) & (estimate > 0.0), estimate, 0.0)
    return [(c, float(g), r, float(e)) for c, g, r, e in zip(cur, grads, batch.results, estimate)]


def takeoff_trim(ctx, conditions):
    """The 1-g trims at V2, sea level, of ``conditions`` (takeoff configuration) and the aerodynamic controls they set
    besides the pilot's (e.g. a movable stabiliser), held at those values through a takeoff run: control → (n,)."""
    sp = ctx.aircraft.speeds
    at_v2 = [c.with_(altitude=0.0, speed=sp.V2.value, speed_kind=sp.V2.kind, speed_name="V2") for c in conditions]
    trims = ctx.trim(at_v2)
    pilot = {"elevator", "aileron", "rudder"}
    names = sorted(
        {k for r in trims.results for k in r.controls} & (set(ctx.aero("takeoff").model.control_names) - pilot)
    )
    return trims, {k: np.array([r.controls.get(k, 0.0) if r.converged else 0.0 for r in trims.results]) for k in names}
