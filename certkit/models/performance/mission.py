"""Mission analysis: design range, payload–range, block fuel and time, cruise drag (``certkit mission``).

Profile (still air, ISA, the ``mission:`` section of the aircraft file)
    taxi out → takeoff to 1,500 ft → climb on the CAS/Mach schedule at maximum-climb thrust → step cruise at
    the cruise Mach number → descent at idle on the same schedule to 1,500 ft → approach and landing → taxi
    in; then the reserves: contingency (a fraction of the trip fuel), a diversion to an alternate (go-around,
    climb, cruise at the alternate altitude, descent, approach) and the final reserve held at the holding
    altitude for the holding time at the minimum-fuel-flow speed. ICAO Annex 6 Part I §4.3.6.3 and EASA
    CAT.OP.MPA.150 define these reserve items; their values are the aircraft file's.

Physics (:mod:`.mission_tables`, :mod:`.integrators`, :mod:`.fuel_flow`)
    the thrust required is the level-flight trim of the flight model (α, elevator and throttle solved: the
    horizontal tail's trim load and the elevator's drag are in it, so that a tail change shows in the fuel),
    all conditions trimmed in one batch for a grid of weights and interpolated in weight; fuel flow from the
    engine model's thrust and a TSFC calibrated to the declared cruise TSFC; climb and descent by the energy
    method; cruise integrated in weight (specific air range spline, exact antiderivative). Cruise levels are
    limited by buffet (buffet load factor × CL ≤ initial-buffet CL) and thrust (a residual rate of climb at
    maximum-climb thrust); the initial level is the allowed level with the largest specific air range at the
    top of climb, and the airplane steps up when the next level is allowed and better.

Outputs (:class:`MissionResult`)
    the design range (MTOW, design payload, reserves on landing), the payload–range points (maximum payload
    at MTOW, design payload at MTOW, maximum fuel at MTOW, ferry with maximum fuel and no payload), block fuel
    and block time of the nominal mission (its still-air distance with the design payload; the takeoff weight
    is solved so that the reserves remain on landing), the trimmed cruise drag coefficient at the declared
    design cruise condition (by default the design mission's mid-cruise weight), the range constraint
    (design range − required range, ≥ 0 met) and the declared performance calibration in force (drag and
    fuel-flow factors, ``calibration:``; solved by ``certkit calibrate``, fixed for every design).

The distance of a mission is counted from brake release to touchdown: climb, cruise and descent plus the
airborne allowances (takeoff and approach) at their speed. Bad input (no ``mission:`` section, a payload above
the maximum, an OEW override that leaves no payload, fuel above the tank capacity, a takeoff weight that cannot
reach the first cruise level) raises :class:`certkit.errors.UserError` naming the field and the value; a design
that does not reach the required range is a result (a negative margin), not an error.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field

import numpy as np
from scipy.optimize import brentq

from certkit import atmosphere as isa
from certkit.errors import UserError
from certkit.models.aero.airplane import build_airplane_aero, lattice_derivatives
from certkit.models.flight import level_trims
from certkit.models.performance.integrators import LevelCruise, fly_path
from certkit.models.performance.mission_tables import MissionTables, build_tables
from certkit.units import FT

NMI = 1852.0


@dataclass
class Phase:
    name: str
    time_s: float
    fuel_kg: float
    distance_m: float


@dataclass
class StepClimb:
    weight_kg: float
    from_altitude_m: float
    to_altitude_m: float


@dataclass
class MissionProfile:
    """One flown mission (SI): weights, phases, reserves, the cruise levels flown."""

    name: str
    payload_kg: float
    zero_fuel_weight_kg: float
    takeoff_weight_kg: float
    ramp_fuel_kg: float
    landing_weight_kg: float
    distance_m: float
    trip_fuel_kg: float
    trip_time_s: float
    block_fuel_kg: float
    block_time_s: float
    initial_altitude_m: float
    mid_cruise_weight_kg: float
    phases: list[Phase]
    reserves: dict[str, float]
    steps: list[StepClimb] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


@dataclass
class PayloadRangePoint:
    name: str
    payload_kg: float
    ramp_fuel_kg: float
    takeoff_weight_kg: float
    range_m: float


@dataclass
class CruiseDrag:
    """Trimmed cruise condition: coefficients on the reference area, angles in rad."""

    altitude_m: float
    mach: float
    mass_kg: float
    CL: float
    CD: float
    lift_to_drag: float
    alpha: float
    elevator: float
    thrust_N: float
    converged: bool


@dataclass
class MissionResult:
    design: MissionProfile
    nominal: MissionProfile
    payload_range: list[PayloadRangePoint]
    cruise_drag: CruiseDrag
    range_requirement_m: float
    oew_kg: float
    notes: list[str]
    timings: dict[str, float]
    #: the declared performance calibration in force (factors, target, source); empty without one
    calibration: dict = field(default_factory=dict)

    @property
    def design_range_m(self) -> float:
        return self.design.distance_m

    @property
    def range_margin_m(self) -> float:
        return self.design.distance_m - self.range_requirement_m

    def responses(self) -> dict[str, float]:
        """The flat responses of a design record (SI)."""
        return {
            "objective.cruise_CD": self.cruise_drag.CD,
            "objective.block_fuel_kg": self.nominal.block_fuel_kg,
            "objective.block_time_s": self.nominal.block_time_s,
            "mission.design_range_m": self.design_range_m,
            "constraint.range_margin_m": self.range_margin_m,
        }

    def as_dict(self) -> dict:
        out = asdict(self)
        out.update(design_range_m=self.design_range_m, range_margin_m=self.range_margin_m, responses=self.responses())
        return out


class MissionFlyer:
    """Flies missions of one airplane (its tables trimmed once) with a given OEW."""

    def __init__(self, aircraft, tables: MissionTables, oew: float):
        self.aircraft, self.t, self.oew = aircraft, tables, oew
        self.m = m = aircraft.mission
        fuel = tables.fuel
        self.allowance = {
            name: fuel.allowance_fuel(getattr(m, name)) for name in ("taxi_out", "takeoff", "approach", "taxi_in")
        }
        s, lv = tables.schedule, tables.levels
        self.k_terminal = s.index(s.altitude[0])
        self.k_level = [s.index(h) for h in lv.altitude]
        grid = s.weights
        # descent from every level at idle, for every weight of the grid (interpolated in weight later)
        self.descent = []
        for k in self.k_level:
            idx = np.arange(k, self.k_terminal - 1, -1)
            self.descent.append(self._path(idx, grid, climb=False))
        self.reserve_grid = grid
        self.reserve_fuel, self.reserve_parts = self._reserves(grid)

    # --- path pieces --------------------------------------------------------------------------------------
    def _path(self, idx, weights, climb: bool, min_excess_power=None):
        s = self.t.schedule
        thrust = s.climb_thrust if climb else s.idle_thrust
        ff = s.climb_fuel_flow if climb else s.idle_fuel_flow
        return fly_path(
            s.altitude[idx],
            s.speed[idx],
            weights,
            lambda j, w: s.required_thrust(idx[j], w),
            thrust[idx],
            ff[idx],
            min_excess_power,
        )

    def _airborne_allowance(self, name: str) -> Phase:
        a = getattr(self.m, name)
        return Phase(name, a.time, self.allowance[name], float(isa.mach_to_tas(a.mach, 0.0)) * a.time)

    def _reserves(self, weights):
        """Alternate (go-around, climb, cruise at the alternate altitude, descent, approach) and final reserve,
        for a destination landing weight of each of ``weights``; (total, parts)."""
        m, s, fuel = self.m, self.t.schedule, self.t.fuel
        r = m.reserves
        w = np.asarray(weights, dtype=float) - self.allowance["takeoff"]
        k_alt = s.index(r.alternate_altitude)
        up = self._path(np.arange(self.k_terminal, k_alt + 1), w, climb=True)
        w_top = w - up.fuel[:, -1]
        down = self._path(np.arange(s.last_index(r.alternate_altitude), self.k_terminal - 1, -1), w_top, climb=False)
        # the descent's fuel depends little on the weight: its value at the top-of-climb weight is used
        cruise_d = np.maximum(r.alternate_distance - up.distance[:, -1] - down.distance[:, -1], 0.0)
        level = LevelCruise.from_fuel_flow(
            float(s.speed[k_alt]), s.weights, fuel.tsfc(s.altitude[k_alt], s.mach[k_alt]) * s.required[:, k_alt]
        )
        w_tod = np.array([level.weight_after(float(a), float(d)) for a, d in zip(w_top, cruise_d)])
        alternate = (np.asarray(weights) - w_tod) + down.fuel[:, -1] + self.allowance["approach"]
        hold = self._hold_fuel(np.asarray(weights) - alternate)
        return alternate + hold, {"alternate": alternate, "final_reserve": hold}

    def _hold_fuel(self, weights):
        """Fuel to hold ``hold_time`` at the minimum-fuel-flow speed, from each weight (midpoint rule, 4 steps)."""
        h = self.t.hold
        w = np.array(weights, dtype=float)
        start = w.copy()
        dt = self.m.reserves.hold_time / 4
        for _ in range(4):
            mid = w - 0.5 * dt * np.interp(w, h.weights, h.fuel_flow)
            w = w - dt * np.interp(mid, h.weights, h.fuel_flow)
        return start - w

    def _step(self, i: int, weight: float):
        """Step climb from level i to i + 1 at ``weight``: (fuel, time, distance), energy method at the cruise Mach."""
        lv = self.t.levels
        res = fly_path(
            lv.altitude[i : i + 2],
            lv.speed[i : i + 2],
            [weight],
            lambda j, w: lv.required_thrust(i + j, w),
            lv.climb_thrust[i : i + 2],
            lv.climb_fuel_flow[i : i + 2],
        )
        return float(res.fuel[0, -1]), float(res.time[0, -1]), float(res.distance[0, -1])

    # --- one mission ----------------------------------------------------------------------------------------
    def climb(self, w_release: float):
        """Climb from 1,500 ft at ``w_release − takeoff fuel``: per cruise level (reached, weight, time, fuel,
        distance) at its top of climb, the acceleration to the cruise Mach at the level included. Above the first
        cruise level the climb goes on only while it holds the residual climb rate: a level it would crawl up to
        (hours at a few feet per minute, the weight burnt on the way making the level "allowed" at the top) is
        above the airplane's thrust-limited ceiling on the way and is not reached."""
        s, lv = self.t.schedule, self.t.levels
        w0 = w_release - self.allowance["takeoff"]
        idx = np.arange(self.k_terminal, self.k_level[-1] + 1)
        above_first = s.altitude[idx] > lv.altitude[0]
        residual = np.where(above_first, self.m.residual_climb_rate, 0.0)
        path = self._path(idx, [w0], climb=True, min_excess_power=residual)
        out = []
        for i, k in enumerate(self.k_level):
            j = k - self.k_terminal
            t, f, x = (float(a[0, j]) for a in (path.time, path.fuel, path.distance))
            reached = bool(path.reached[0, j])
            w = w0 - f if reached else np.nan
            dv = float(lv.speed[i] - s.speed[k])
            if reached and dv > 1e-6:  # crossover above the level: accelerate at the level
                acc = fly_path(
                    np.full(2, lv.altitude[i]),
                    np.array([s.speed[k], lv.speed[i]]),
                    [w],
                    lambda jj, ww: lv.required_thrust(i, ww),  # noqa: B023 (called within this iteration)
                    np.full(2, lv.climb_thrust[i]),
                    np.full(2, lv.climb_fuel_flow[i]),
                )
                reached = bool(acc.reached[0, -1])
                t, f, x = t + float(acc.time[0, -1]), f + float(acc.fuel[0, -1]), x + float(acc.distance[0, -1])
                w = w0 - f
            out.append((reached, w, t, f, x))
        return out

    def initial_level(self, tocs, w_release: float) -> int:
        lv = self.t.levels
        best, best_sar = None, -np.inf
        for i, (reached, w, *_rest) in enumerate(tocs):
            if reached and w <= lv.max_weight[i]:
                sar = float(lv.cruise[i].specific_air_range(w))
                if sar > best_sar:
                    best, best_sar = i, sar
        if best is None:
            h0 = self.m.initial_altitude
            why = (
                "buffet"
                if tocs[0][0] and tocs[0][1] > lv.buffet_weight[0]
                else "thrust: the residual climb rate at maximum-climb thrust is too small"
                if tocs[0][0]
                else "thrust: the climb stalls before the level"
            )
            raise UserError(
                f"mission.initial_altitude: at a takeoff weight of {w_release:.0f} kg the airplane cannot reach "
                f"the first cruise level {h0 / FT:.0f} ft ({why}); expected a level the airplane can climb to "
                "and hold with the declared residual climb rate and buffet margin"
            )
        return best

    def _cruise_plan(self, i0: int, w_toc: float):
        """Segments (level, weight at start, weight at which it steps up or −inf) and the steps' costs."""
        lv = self.t.levels
        plan, w, i = [], w_toc, i0
        while True:
            ws = lv.step_weight[i] if i < lv.altitude.size - 1 else -np.inf
            if ws >= w:  # already light enough for the next level: step at once
                ws = w
            plan.append((i, w, ws))
            if not np.isfinite(ws):
                return plan
            f, t, x = self._step(i, ws)
            plan[-1] = (i, w, ws, (f, t, x))
            w, i = ws - f, i + 1

    def _cruise_to(self, plan, w_tod: float):
        """(distance, time, fuel burnt incl. steps, level at TOD, steps taken) from the plan's start to ``w_tod``."""
        lv = self.t.levels
        dist = tim = 0.0
        steps = []
        for seg in plan:
            i, w_start, ws = seg[:3]
            if not np.isfinite(ws) or w_tod >= ws:
                end = max(w_tod, ws) if np.isfinite(ws) else w_tod
                dist += float(lv.cruise[i].distance(w_start, end))
                tim += float(lv.cruise[i].time(w_start, end))
                return dist, tim, i, steps
            dist += float(lv.cruise[i].distance(w_start, ws))
            tim += float(lv.cruise[i].time(w_start, ws))
            f, t, x = seg[3]
            dist, tim = dist + x, tim + t
            steps.append(StepClimb(ws, float(lv.altitude[i]), float(lv.altitude[i + 1])))
            if w_tod > ws - f:  # the weight at TOD falls inside the step: end at the upper level's start
                return dist, tim, i + 1, steps
        raise AssertionError("cruise plan ends without an open segment")

    def _descent(self, i: int, w_tod: float):
        d = self.descent[i]
        grid = self.t.schedule.weights
        return tuple(float(np.interp(w_tod, grid, a[:, -1])) for a in (d.fuel, d.time, d.distance))

    def fly(self, name: str, payload: float, w_release: float) -> MissionProfile:
        """The longest mission from brake-release weight ``w_release`` with ``payload``, reserves left on landing."""
        m = self.m
        zfw = self.oew + payload
        tocs = self.climb(w_release)
        i0 = self.initial_level(tocs, w_release)
        _, w_toc, t_climb, f_climb, x_climb = tocs[i0]
        plan = self._cruise_plan(i0, w_toc)

        def landing(w_tod):
            _, _, i, _ = self._cruise_to(plan, w_tod)
            f_desc, _, _ = self._descent(i, w_tod)
            return w_tod - f_desc - self.allowance["approach"]

        def surplus(w_tod):
            w_land = landing(w_tod)
            reserve = m.reserves.contingency_fraction * (w_release - w_land) + np.interp(
                w_land, self.reserve_grid, self.reserve_fuel
            )
            return w_land - zfw - reserve

        notes = []
        if surplus(w_toc) < 0:
            w_tod = w_toc
            notes.append(f"{name}: the fuel does not cover climb, descent and reserves: no cruise")
        else:
            w_tod = brentq(surplus, zfw * 0.5, w_toc, xtol=0.01)
        x_cr, t_cr, i_end, steps = self._cruise_to(plan, w_tod)
        f_desc, t_desc, x_desc = self._descent(i_end, w_tod)
        takeoff, approach = self._airborne_allowance("takeoff"), self._airborne_allowance("approach")
        phases = [
            Phase("taxi_out", m.taxi_out.time, self.allowance["taxi_out"], 0.0),
            takeoff,
            Phase("climb", t_climb, f_climb, x_climb),
            Phase("cruise", t_cr, w_toc - w_tod, x_cr),
            Phase("descent", t_desc, f_desc, x_desc),
            approach,
            Phase("taxi_in", m.taxi_in.time, self.allowance["taxi_in"], 0.0),
        ]
        airborne = phases[1:6]
        w_land = w_tod - f_desc - self.allowance["approach"]
        trip_fuel = w_release - w_land
        reserve = {
            "contingency": m.reserves.contingency_fraction * trip_fuel,
            **{k: float(np.interp(w_land, self.reserve_grid, v)) for k, v in self.reserve_parts.items()},
        }
        ramp_fuel = w_release - zfw + self.allowance["taxi_out"]
        return MissionProfile(
            name,
            payload,
            zfw,
            w_release,
            ramp_fuel,
            w_land,
            sum(p.distance_m for p in airborne),
            trip_fuel,
            sum(p.time_s for p in airborne),
            trip_fuel + self.allowance["taxi_out"] + self.allowance["taxi_in"],
            sum(p.time_s for p in phases),
            float(self.t.levels.altitude[i0]),
            0.5 * (w_toc + w_tod),
            phases,
            reserve,
            steps,
            notes,
        )

    def fly_distance(self, name: str, payload: float, distance: float, w_max: float) -> MissionProfile:
        """The mission of ``distance`` (m) with ``payload``: the brake-release weight solved (≤ ``w_max``)."""
        zfw = self.oew + payload
        lo = zfw + self.allowance["takeoff"] + 0.02 * zfw

        def short(w):
            return self.fly(name, payload, w).distance_m - distance

        if short(w_max) < 0:
            best = self.fly(name, payload, w_max)
            raise UserError(
                f"mission.nominal_distance: {distance / NMI:.0f} nmi cannot be flown with the design payload "
                f"below {w_max:.0f} kg takeoff weight (range there {best.distance_m / NMI:.0f} nmi); "
                "expected a distance within the airplane's range"
            )
        w = brentq(short, lo, w_max, xtol=0.5)
        return self.fly(name, payload, w)


def clean_aero(aircraft):
    """The clean configuration's aerodynamic model (vortex lattice unless the file declares derivative tables)."""
    declared = "clean" in aircraft.aerodynamics.derivative_tables
    return build_airplane_aero(aircraft, "clean", lattice=None if declared else lattice_derivatives(aircraft))


def fuel_capacity(aircraft) -> float | None:
    m = aircraft.mass
    if m.max_fuel is not None:
        return m.max_fuel
    return sum(t.capacity for t in m.fuel_tanks) or None


def fly_missions(aircraft, aero=None, oew_kg: float | None = None, tables_cache: dict | None = None) -> MissionResult:
    """Design range, payload–range, nominal mission and cruise drag of ``aircraft`` (its ``mission:`` section),
    with the OEW overridden by ``oew_kg`` when given (the design layer's sized OEW). ``aero``: the clean
    configuration's aerodynamic model of the same aircraft to reuse (built when not given); ``tables_cache``: a dict
    the caller keeps for one aircraft, so that missions with other OEWs reuse its trim tables."""
    t0 = time.perf_counter()
    m = aircraft.mission
    if m is None:
        raise UserError(
            "the aircraft file has no mission: section (cruise Mach, levels, payload, reserves); "
            "see aircraft/lta.yaml for an example"
        )
    mass = aircraft.mass
    oew = float(mass.OEW if oew_kg is None else oew_kg)
    if not (0 < oew < mass.MZFW):
        raise UserError(f"OEW {oew:.0f} kg: expected a positive mass below MZFW ({mass.MZFW:.0f} kg)")
    max_payload = min(mass.max_payload if mass.max_payload is not None else np.inf, mass.MZFW - oew)
    if m.design_payload > max_payload * (1 + 1e-9):
        raise UserError(
            f"mission.design_payload: {m.design_payload:.0f} kg exceeds the maximum payload {max_payload:.0f} kg "
            f"(min of mass.max_payload and MZFW − OEW with OEW {oew:.0f} kg)"
        )
    capacity = fuel_capacity(aircraft)
    aero = clean_aero(aircraft) if aero is None else aero
    lo = 0.8 * (mass.OEW if oew >= 0.85 * mass.OEW else oew)  # one table for every OEW near the declared one
    cache = {} if tables_cache is None else tables_cache
    key = ("mission_tables", round(lo, 0))
    if key not in cache:
        cache[key] = build_tables(aircraft, aero, (lo, 1.05 * mass.MTOW))
    tables = cache[key]
    t1 = time.perf_counter()
    flyer = MissionFlyer(aircraft, tables, oew)
    taxi = flyer.allowance["taxi_out"]
    notes = list(tables.notes)

    def release_weight(payload, fuel_limit=True):
        w = mass.MTOW
        if fuel_limit and capacity is not None:
            w = min(w, oew + payload + capacity - taxi)
        return w

    design_w = release_weight(m.design_payload)
    if design_w < mass.MTOW:
        notes.append(f"design mission: the fuel capacity limits the takeoff weight to {design_w:.0f} kg (< MTOW)")
    design = flyer.fly("design range", m.design_payload, design_w)
    points = [
        PayloadRangePoint("maximum payload", max_payload, 0.0, 0.0, 0.0),
        PayloadRangePoint("design payload", m.design_payload, design.ramp_fuel_kg, design_w, design.distance_m),
    ]
    mp = flyer.fly("maximum payload", max_payload, release_weight(max_payload))
    points[0] = PayloadRangePoint("maximum payload", max_payload, mp.ramp_fuel_kg, mp.takeoff_weight_kg, mp.distance_m)
    if capacity is not None:
        p_full = mass.MTOW - oew - (capacity - taxi)
        if 0 < p_full < max_payload:
            f = flyer.fly("maximum fuel", p_full, mass.MTOW)
            points.append(
                PayloadRangePoint("maximum fuel at MTOW", p_full, f.ramp_fuel_kg, f.takeoff_weight_kg, f.distance_m)
            )
        ferry = flyer.fly("ferry", 0.0, release_weight(0.0))
        points.append(
            PayloadRangePoint("ferry (no payload)", 0.0, ferry.ramp_fuel_kg, ferry.takeoff_weight_kg, ferry.distance_m)
        )
    else:
        notes.append(
            "no fuel capacity declared (mass.max_fuel or fuel tanks): the fuel-limited payload–range points are not "
            "computed"
        )
    t2 = time.perf_counter()
    nominal = flyer.fly_distance("nominal", m.design_payload, m.nominal_distance, 1.05 * mass.MTOW)
    if capacity is not None and nominal.ramp_fuel_kg > capacity * (1 + 1e-6):
        raise UserError(
            f"mission.nominal_distance: {m.nominal_distance / NMI:.0f} nmi needs {nominal.ramp_fuel_kg:.0f} kg of "
            f"fuel, above the fuel capacity {capacity:.0f} kg"
        )
    if nominal.takeoff_weight_kg > mass.MTOW:
        notes.append(
            f"nominal mission: takeoff weight {nominal.takeoff_weight_kg:.0f} kg exceeds MTOW ({mass.MTOW:.0f} kg)"
        )
    for p in (design, nominal):
        if p.landing_weight_kg > mass.MLW:
            notes.append(f"{p.name}: landing weight {p.landing_weight_kg:.0f} kg exceeds MLW ({mass.MLW:.0f} kg)")
        notes += p.notes
    t3 = time.perf_counter()
    drag = cruise_drag(aircraft, aero, tables.x_cg, m.drag_condition.mass or design.mid_cruise_weight_kg)
    notes += _speed_notes(aircraft)
    t4 = time.perf_counter()
    timings = {"tables_s": t1 - t0, "range_s": t2 - t1, "nominal_s": t3 - t2, "drag_s": t4 - t3, "total_s": t4 - t0}
    return MissionResult(
        design, nominal, points, drag, m.range_requirement, oew, notes, timings, calibration_in_force(aircraft)
    )


def calibration_in_force(aircraft) -> dict:
    """The declared performance calibration as plain data (SI), for the report and the design record."""
    cal = getattr(aircraft, "calibration", None)
    if cal is None:
        return {}
    out = {
        "drag_factor": cal.drag_factor,
        "fuel_flow_factor": cal.fuel_flow_factor,
        "fuel_flow_source": cal.fuel_flow_source,
        "source": cal.source,
    }
    if cal.target is not None:
        out["target"] = {
            "range_m": cal.target.range,
            "payload_kg": cal.target.payload,
            "tolerance": cal.target.tolerance,
            "source": cal.target.source,
        }
    return out


def cruise_drag(aircraft, aero, x_cg: float, mass_kg: float) -> CruiseDrag:
    """The trimmed level-flight drag coefficient at the declared design cruise condition and ``mass_kg``."""
    m = aircraft.mission
    h = m.drag_condition.altitude
    batch = level_trims(
        aircraft, aero, [mass_kg], x_cg, [float(h)], [float(isa.mach_to_tas(m.cruise_mach, h))], "mission"
    )
    _, out = batch.model.derivatives_euler(batch.x, batch.u, with_outputs=True)
    r = batch.results[0]
    cl, cd = float(out.CL[0]), float(out.CD[0])
    return CruiseDrag(
        float(h),
        m.cruise_mach,
        float(mass_kg),
        cl,
        cd,
        cl / cd,
        r.alpha,
        r.controls.get("elevator", np.nan),
        float(out.thrust[0].sum()),
        r.ok,
    )


def _speed_notes(aircraft) -> list[str]:
    """Where the mission's speeds exceed the declared VMO/MMO (the mission flies them as declared)."""
    m, sp = aircraft.mission, aircraft.speeds
    notes = []
    if sp.MMO is not None and m.cruise_mach > sp.MMO:
        notes.append(f"cruise Mach {m.cruise_mach:.3f} exceeds MMO {sp.MMO:.3f}")
    if sp.VMO is not None:
        h = m.initial_altitude
        eas = float(isa.convert_speed(m.cruise_mach, "MACH", "EAS", h))
        vmo = float(isa.convert_speed(sp.VMO.value, sp.VMO.kind, "EAS", h))
        if eas > vmo:
            notes.append(
                f"M {m.cruise_mach:.2f} at {h / FT:.0f} ft is {eas / 0.514444:.0f} KEAS, above the declared VMO "
                f"({vmo / 0.514444:.0f} KEAS): the mission flies the declared schedule regardless"
            )
        climb = float(isa.convert_speed(m.climb_speed.value, m.climb_speed.kind, "EAS", m.speed_limit_altitude))
        if climb > float(isa.convert_speed(sp.VMO.value, sp.VMO.kind, "EAS", m.speed_limit_altitude)):
            notes.append(
                f"the climb speed exceeds the declared VMO above {m.speed_limit_altitude / FT:.0f} ft: flown as "
                "declared"
            )
    return notes


__all__ = [
    "fly_missions",
    "calibration_in_force",
    "MissionResult",
    "MissionProfile",
    "PayloadRangePoint",
    "CruiseDrag",
    "Phase",
    "StepClimb",
    "MissionFlyer",
    "cruise_drag",
    "NMI",
]
