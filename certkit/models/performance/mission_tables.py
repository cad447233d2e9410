"""The trimmed-flight tables the mission is flown on, computed in one batch of trims.

Every condition of the mission — the points of the climb/descent schedule, the cruise levels at the cruise Mach
number, the holding speeds — is trimmed in steady level flight (α, elevator and throttle solved, so that the
horizontal tail's trim load and the elevator drag are in the thrust required) by
:func:`certkit.models.flight.level_trims`, for every weight of a weight grid, in **one** call. The thrust required
of each condition is then a cubic spline in weight. A trim that does not converge (more than full throttle)
is filled from a fit D = a + b W² of its column's converged trims (the shape of a parabolic polar at fixed
speed and altitude) and can only be infeasible where it is used (the excess power is then negative).

Cruise levels: initial level + k × step up to the highest level (the ceiling by default), each limited by
* buffet: the 1-g lift coefficient times the buffet load factor (1.3 g: ±0.3 g, a 40° banked turn) must not
  exceed the declared initial-buffet lift coefficient (Boeing AERO, "buffet-limited maximum altitude"; the
  FMC's maneuver margin ≥ 1.2 g);
* thrust: at maximum-climb thrust the airplane must still climb at the declared residual rate (300 ft/min in
  the baseline, the thrust-limited maximum altitude of Boeing's FMC).
The step from one level to the next is taken at the weight below which the next level is allowed and its
specific air range is the larger.

Climb/descent schedule: ``low_altitude_speed`` (CAS) from 1,500 ft (the end of the takeoff path, §25.111(a))
to ``speed_limit_altitude`` (14 CFR 91.117(a): 250 KIAS below 10,000 ft), acceleration there to
``climb_speed`` (CAS), which is held until it reaches the cruise Mach number (crossover), then the Mach number.
The descent flies the same schedule at idle.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from certkit import atmosphere as isa
from certkit.models.flight import level_trims
from certkit.models.mass.loading import reference_cg
from certkit.models.performance.fuel_flow import EngineFuel
from certkit.models.performance.integrators import LevelCruise
from certkit.units import FT, G0, KN

#: the end of the takeoff path and the start of the approach allowance (§25.111(a): 1,500 ft above the surface)
TERMINAL_ALTITUDE = 1500 * FT
#: schedule points every this much altitude
SCHEDULE_STEP = 2000 * FT
#: weights of the trim grid
N_WEIGHTS = 10
#: equivalent airspeeds trimmed for the holding speed (the minimum-fuel-flow speed is interpolated between them)
HOLD_EAS = np.arange(130.0, 300.1, 17.0) * KN


def _cas_to_tas(cas, h):
    return isa.mach_to_tas(isa.cas_to_mach(cas, h), h)


def _speed_tas(speed, h):
    """A declared :class:`certkit.aircraft.quantities.Speed` as TAS at altitude ``h``."""
    return float(isa.to_tas(speed.value, speed.kind, h))


@dataclass
class Schedule:
    """Climb/descent schedule points: altitude, TAS, Mach (K,), level-flight thrust required (weights × K),
    maximum-climb and idle thrust and their fuel flows (K,)."""

    altitude: np.ndarray
    speed: np.ndarray
    mach: np.ndarray
    weights: np.ndarray
    required: np.ndarray
    climb_thrust: np.ndarray
    climb_fuel_flow: np.ndarray
    idle_thrust: np.ndarray
    idle_fuel_flow: np.ndarray

    def __post_init__(self):
        self._spline = CubicSpline(self.weights, self.required, axis=0)

    def required_thrust(self, k: int, weight) -> np.ndarray:
        return self._spline(np.asarray(weight, dtype=float))[..., k]

    def index(self, altitude: float) -> int:
        """The first schedule point at ``altitude`` (m)."""
        return int(np.flatnonzero(np.isclose(self.altitude, altitude, atol=0.01))[0])

    def last_index(self, altitude: float) -> int:
        return int(np.flatnonzero(np.isclose(self.altitude, altitude, atol=0.01))[-1])


@dataclass
class CruiseLevels:
    """Cruise levels at the cruise Mach number: altitude, TAS (L,), thrust required and CL (weights × L), the
    maximum-climb thrust (L,), the specific-air-range cruise of each level, the heaviest weight each level allows
    (buffet and thrust), the weight at which to step up from each level to the next (−inf: never)."""

    altitude: np.ndarray
    speed: np.ndarray
    mach: float
    weights: np.ndarray
    required: np.ndarray
    lift_coefficient: np.ndarray
    climb_thrust: np.ndarray
    climb_fuel_flow: np.ndarray
    cruise: list[LevelCruise]
    buffet_weight: np.ndarray
    thrust_weight: np.ndarray
    step_weight: np.ndarray

    @property
    def max_weight(self) -> np.ndarray:
        return np.minimum(self.buffet_weight, self.thrust_weight)

    def required_thrust(self, i: int, weight):
        return CubicSpline(self.weights, self.required[:, i])(weight)


@dataclass
class HoldTable:
    """Holding at ``altitude``: for each weight the minimum-fuel-flow speed (TAS, not below 1.3 V_S clean) and
    its fuel flow (kg/s)."""

    altitude: float
    weights: np.ndarray
    speed: np.ndarray
    fuel_flow: np.ndarray


@dataclass
class MissionTables:
    schedule: Schedule
    levels: CruiseLevels
    hold: HoldTable
    fuel: EngineFuel
    x_cg: float
    trims: int
    notes: list[str] = field(default_factory=list)


def _schedule_points(m, levels, alternate_altitude, ceiling) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(altitude, TAS, Mach) of the schedule points, from 1,500 ft to the highest level."""
    top = float(levels[-1])
    hs = set(np.arange(TERMINAL_ALTITUDE, top, SCHEDULE_STEP).tolist()) | {float(h) for h in levels}
    hs |= {float(alternate_altitude), float(m.speed_limit_altitude), TERMINAL_ALTITUDE}
    # crossover: the climb CAS reaches the cruise Mach number
    climb_cas = float(isa.convert_speed(m.climb_speed.value, m.climb_speed.kind, "CAS", m.speed_limit_altitude))
    f = lambda h: float(isa.cas_to_mach(climb_cas, h)) - m.cruise_mach  # noqa: E731
    if f(m.speed_limit_altitude) < 0 < f(min(ceiling, isa.H_MAX)):
        hs.add(brentq(f, m.speed_limit_altitude, min(ceiling, isa.H_MAX), xtol=0.1))
    hs = sorted(h for h in hs if TERMINAL_ALTITUDE - 1e-6 <= h <= top + 1e-6)
    alt, tas = [], []
    v_low_sl = _speed_tas(m.low_altitude_speed, m.speed_limit_altitude)
    v_high_sl = min(
        _cas_to_tas(climb_cas, m.speed_limit_altitude), isa.mach_to_tas(m.cruise_mach, m.speed_limit_altitude)
    )
    for h in hs:
        if h < m.speed_limit_altitude - 1e-6:
            alt.append(h), tas.append(_speed_tas(m.low_altitude_speed, h))
        elif abs(h - m.speed_limit_altitude) <= 1e-6:  # acceleration at the speed-limit altitude, in three steps
            for v in np.linspace(v_low_sl, v_high_sl, 4):
                alt.append(h), tas.append(float(v))
        else:
            alt.append(h), tas.append(float(min(_cas_to_tas(climb_cas, h), isa.mach_to_tas(m.cruise_mach, h))))
    alt, tas = np.array(alt), np.array(tas)
    return alt, tas, isa.tas_to_mach(tas, alt)


def _fill_failed(weights, values, ok):
    """Failed trims of each column replaced by the least-squares fit a + b W² of its converged ones."""
    out = values.copy()
    for j in range(values.shape[1]):
        good = ok[:, j]
        if good.all():
            continue
        if good.sum() >= 2:
            A = np.stack([np.ones(good.sum()), weights[good] ** 2], axis=1)
            coef = np.linalg.lstsq(A, values[good, j], rcond=None)[0]
            out[~good, j] = coef[0] + coef[1] * weights[~good] ** 2
        else:
            out[:, j] = np.nan
    return out


def cruise_levels(m, ceiling) -> np.ndarray:
    top = m.max_altitude if m.max_altitude is not None else ceiling
    n = int(np.floor((top - m.initial_altitude) / m.altitude_step + 1e-9)) + 1
    return m.initial_altitude + m.altitude_step * np.arange(max(n, 1))


def build_tables(aircraft, aero, weight_range: tuple[float, float]) -> MissionTables:
    """Trim every mission condition for ``N_WEIGHTS`` weights spanning ``weight_range`` (kg) in one batch
    (``aero``: the clean configuration's :class:`certkit.models.aero.airplane.AirplaneAero`)."""
    m = aircraft.mission
    fuel = EngineFuel.of(aircraft)
    ceiling = aircraft.envelope.ceiling
    levels = cruise_levels(m, ceiling)
    x_cg = m.cruise_cg if m.cruise_cg is not None else reference_cg(aircraft)
    weights = np.linspace(weight_range[0], weight_range[1], N_WEIGHTS)
    sched_h, sched_v, sched_m = _schedule_points(m, levels, m.reserves.alternate_altitude, ceiling)
    level_v = isa.mach_to_tas(m.cruise_mach, levels)
    hold_h = m.reserves.hold_altitude
    hold_v = isa.eas_to_tas(HOLD_EAS, hold_h)
    per_weight = (
        [(h, v) for h, v in zip(sched_h, sched_v)]
        + [(h, v) for h, v in zip(levels, level_v)]
        + [(hold_h, v) for v in hold_v]
    )
    conds = [(float(w), float(h), float(v)) for w in weights for h, v in per_weight]
    batch = level_trims(
        aircraft, aero, [c[0] for c in conds], x_cg, [c[1] for c in conds], [c[2] for c in conds], "mission"
    )
    _, out = batch.model.derivatives_euler(batch.x, batch.u, with_outputs=True)
    shape = (N_WEIGHTS, len(per_weight))
    thrust = out.thrust.sum(axis=1).reshape(shape)
    cl = np.asarray(out.CL).reshape(shape)
    ok = np.array(
        [r.converged and not any(e.control == "throttle" for e in r.limits_exceeded) for r in batch.results]
    ).reshape(shape)
    thrust = _fill_failed(weights, thrust, ok)
    notes = list(fuel.notes)
    if not ok.all():
        notes.append(
            f"{int((~ok).sum())} of {ok.size} mission trims need more than full throttle (heavy, high): "
            "their thrust required is extrapolated and those conditions are infeasible"
        )
    K, L = sched_h.size, levels.size
    sched_req, level_req, hold_req = thrust[:, :K], thrust[:, K : K + L], thrust[:, K + L :]

    climb_thr = fuel.thrust(m.climb_throttle, sched_h, sched_m)
    idle_thr = fuel.thrust(0.0, sched_h, sched_m)
    schedule = Schedule(
        sched_h,
        sched_v,
        sched_m,
        weights,
        sched_req,
        climb_thr,
        fuel.fuel_flow(climb_thr, sched_h, sched_m),
        idle_thr,
        fuel.fuel_flow(idle_thr, sched_h, sched_m),
    )
    levels_table = _levels(m, aircraft, fuel, levels, level_v, weights, level_req, cl[:, K : K + L])
    hold = _hold(aircraft, fuel, hold_h, hold_v, weights, hold_req)
    return MissionTables(schedule, levels_table, hold, fuel, float(x_cg), len(conds), notes)


def _levels(m, aircraft, fuel, levels, speed, weights, required, cl) -> CruiseLevels:
    mach = m.cruise_mach
    climb_thr = fuel.thrust(m.climb_throttle, levels, mach)
    ff_climb = fuel.fuel_flow(climb_thr, levels, mach)
    tsfc = fuel.tsfc(levels, mach)
    fine = np.linspace(weights[0], weights[-1], 4 * weights.size)
    spl = CubicSpline(weights, required, axis=0)
    req_fine = spl(fine)
    cruise = [LevelCruise.from_fuel_flow(float(speed[i]), fine, tsfc[i] * req_fine[:, i]) for i in range(levels.size)]
    q = 0.5 * isa.GAMMA * isa.pressure(levels) * mach**2
    area = aircraft.reference.area
    buffet_w = m.buffet_onset_CL / m.buffet_load_factor * q * area / G0
    thrust_w = np.empty(levels.size)
    for i in range(levels.size):
        roc = lambda w, i=i: (climb_thr[i] - spl(w)[i]) * speed[i] / (w * G0) - m.residual_climb_rate  # noqa: E731
        vals = np.array([roc(w) for w in fine])
        if vals[0] < 0:
            thrust_w[i] = -np.inf
        elif vals[-1] >= 0:
            thrust_w[i] = np.inf
        else:
            j = int(np.argmax(vals < 0))
            thrust_w[i] = brentq(roc, fine[j - 1], fine[j], xtol=1.0)
    max_w = np.minimum(buffet_w, thrust_w)
    step = np.full(levels.size, -np.inf)
    for i in range(levels.size - 1):
        diff = lambda w, i=i: float(cruise[i + 1].specific_air_range(w) - cruise[i].specific_air_range(w))  # noqa: E731
        better = np.array([diff(w) >= 0 for w in fine])
        allowed = fine <= max_w[i + 1]
        good = better & allowed
        # the heaviest weight from which on (all lighter weights) the next level is allowed and better
        if not good[0]:
            continue
        j = int(np.argmin(good)) if not good.all() else fine.size
        w_hi = fine[j - 1] if j < fine.size else fine[-1]
        if j < fine.size and not better[j] and allowed[j]:
            w_hi = brentq(diff, fine[j - 1], fine[j], xtol=1.0)
        elif j < fine.size:
            w_hi = min(max_w[i + 1], fine[j])
        step[i] = w_hi
    return CruiseLevels(
        levels, speed, mach, weights, required, cl, climb_thr, ff_climb, cruise, buffet_w, thrust_w, step
    )


def _hold(aircraft, fuel, h, tas, weights, required) -> HoldTable:
    """Minimum fuel flow over the trimmed holding speeds (cubic in speed), not below 1.3 V_S clean."""
    mach = isa.tas_to_mach(tas, h)
    ff = fuel.fuel_flow(required, h, mach[None, :])
    fine = np.linspace(tas[0], tas[-1], 200)
    clmax = aircraft.configurations["clean"].CLmax or 1.4
    speeds, flows = np.empty(weights.size), np.empty(weights.size)
    for i, w in enumerate(weights):
        vs = isa.eas_to_tas(np.sqrt(2 * w * G0 / (isa.RHO0 * aircraft.reference.area * clmax)), h)
        f = CubicSpline(tas, ff[i])(fine)
        f = np.where(fine >= 1.3 * vs, f, np.inf)
        j = int(np.argmin(f))
        speeds[i], flows[i] = fine[j], f[j]
    return HoldTable(float(h), weights, speeds, flows)
