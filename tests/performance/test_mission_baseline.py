"""The baseline's missions against published 777-200ER-class figures and closed-form checks.

References and tolerances are stated per test. The mission module itself adds no drag or engine data: its
absolute accuracy is the drag build-up's (certkit.models.aero.drag) and the declared TSFC's; the bands below
are wide enough for a conceptual model and narrow enough to catch unit, integration and bookkeeping errors.
"""

import time

import numpy as np
import pytest

from certkit.engine.context import Context
from certkit.models.performance.integrators import breguet_range
from certkit.models.performance.mission import NMI, MissionFlyer, fly_missions
from certkit.units import FT, LB


@pytest.fixture(scope="module")
def base_ctx(baseline):
    ctx = Context(baseline)
    ctx.aero("clean")
    return ctx


#: the baseline's mission trim tables, shared by the tests of this module (fly_missions' tables_cache)
TABLES: dict = {}


@pytest.fixture(scope="module")
def result(base_ctx):
    return fly_missions(base_ctx.aircraft, base_ctx.aero("clean"), tables_cache=TABLES)


def phase(profile, name):
    return next(p for p in profile.phases if p.name == name)


def test_design_range_meets_the_declared_target_within_1_percent(result, baseline):
    """The calibrated baseline flies its declared design range — 7,530 nmi with 305 passengers (68,625 lb) from
    MTOW, the seed study's sized baseline [given] — within 1 % (the calibration's declared tolerance). The drag
    factor was solved for it by ``certkit calibrate``; a model change that moves the range by more than 1 % must
    be followed by a re-calibration (docs/baseline-sources.md §7a), not a wider band."""
    cal = baseline.model.calibration
    assert cal.target.range == pytest.approx(7530 * NMI) and cal.target.tolerance == 0.01
    assert result.design.payload_kg == pytest.approx(68625 * LB)
    assert result.design_range_m / NMI == pytest.approx(7530, rel=0.01)
    assert result.range_margin_m == pytest.approx(result.design_range_m - 7530 * NMI)
    assert result.calibration["drag_factor"] == cal.drag_factor


def test_design_range_against_boeing_published_figure(result):
    """Boeing quotes the 777-200ER at 7,065 nmi with 301 three-class passengers (Boeing 777 technical
    specifications; Boeing's own payload and reserve rules, not public). The declared 7,530 nmi with 305
    passengers is 6.6 % longer; the calibrated model lies within 10 % of Boeing's figure, and above it, as the
    declared target is (docs/baseline-sources.md §7a)."""
    r = result.design_range_m / NMI
    assert 7065 <= r <= 1.10 * 7065


def test_cruise_segment_against_breguet(result, base_ctx):
    """The design mission's cruise (step climbs included) against the closed-form Breguet range with the
    trimmed L/D and the TSFC at the declared drag condition (M 0.84, 35,000 ft, mid-cruise weight) over the
    same weights: within 4 % (the steps keep CL near its buffet limit, so L/D varies by a few % along the
    cruise and TSFC by ±1 % between levels)."""
    d = result.design
    w_toc = d.takeoff_weight_kg - phase(d, "takeoff").fuel_kg - phase(d, "climb").fuel_kg
    w_tod = w_toc - phase(d, "cruise").fuel_kg
    c = result.cruise_drag
    from certkit import atmosphere as isa
    from certkit.models.performance.fuel_flow import EngineFuel

    tsfc = float(EngineFuel.of(base_ctx.aircraft).tsfc(c.altitude_m, c.mach))
    v = float(isa.mach_to_tas(c.mach, c.altitude_m))
    closed = breguet_range(v, c.lift_to_drag, tsfc, w_toc, w_tod)
    assert phase(d, "cruise").distance_m == pytest.approx(closed, rel=0.04)


def test_cruise_drag_condition(result):
    """Trimmed cruise at M 0.84, 35,000 ft, mid-cruise weight: CL = W/(q S) within 2 % (the tail's trim load and
    the thrust's lift component are the difference); L/D 17.7 ± 1 — the Breguet-implied mission-average L/D of the
    777-200ER (R 7,530 nmi, V 482 kt, installed TSFC 0.545 lb/lbf/h, W0/W1 643,000/398,000 lb:
    docs/baseline-sources.md §7) with the ±1 of the research recommendation."""
    c = result.cruise_drag
    from certkit import atmosphere as isa

    q = 0.7 * float(isa.pressure(c.altitude_m)) * c.mach**2
    assert c.converged
    assert c.altitude_m == pytest.approx(35000 * FT) and c.mach == 0.84
    assert c.CL == pytest.approx(c.mass_kg * 9.80665 / (q * 457.76), rel=0.02)
    assert 16.7 <= c.lift_to_drag <= 18.7


def test_nominal_block_fuel_band(result):
    """5,000 nmi with 305 passengers: block fuel inside the Breguet band of the class — landing weight × (e^x − 1),
    x = R c g / (V L/D), with L/D 17.5–19.5 and TSFC 0.52–0.56 lb/lbf/h (docs/baseline-sources.md §7), V 484 kt,
    plus 2–6 % for climb, taxi and approach — and the still-air distance solved to 0.1 nmi."""
    n = result.nominal
    assert n.distance_m / NMI == pytest.approx(5000, abs=0.1)
    w_land = n.landing_weight_kg
    lo = w_land * (np.exp(5000 * 0.52 / (484 * 19.5)) - 1) * 1.02
    hi = w_land * (np.exp(5000 * 0.56 / (484 * 17.5)) - 1) * 1.06
    assert lo <= n.block_fuel_kg <= hi
    assert 10.0 <= n.block_time_s / 3600 <= 11.5  # 5,000 nmi at 484 kt is 10.3 h, plus climb, descent and taxi


def test_payload_range_points(result, baseline):
    """Shape and corner weights of the payload–range diagram (D6-58329 §3.2 construction): maximum payload and
    design payload at MTOW, maximum fuel at MTOW, ferry with full tanks and no payload, ranges increasing."""
    m = baseline.model.mass
    pts = {p.name: p for p in result.payload_range}
    ranges = [
        pts[n].range_m for n in ("maximum payload", "design payload", "maximum fuel at MTOW", "ferry (no payload)")
    ]
    assert np.all(np.diff(ranges) > 0)
    assert pts["maximum payload"].payload_kg == pytest.approx(m.max_payload)
    assert pts["maximum fuel at MTOW"].takeoff_weight_kg == pytest.approx(m.MTOW)
    assert pts["maximum fuel at MTOW"].ramp_fuel_kg == pytest.approx(m.max_fuel)
    assert pts["ferry (no payload)"].ramp_fuel_kg == pytest.approx(m.max_fuel)
    assert pts["ferry (no payload)"].takeoff_weight_kg < m.MTOW


def test_profile_bookkeeping_and_limits(result):
    """Weights add up; the initial level at MTOW is the lowest (35,000 ft would need CL 1.3 × 0.53 > 0.65, the
    declared buffet onset); steps go up; the landing weight is below MLW; reserves are 5 % of trip fuel + the
    200 nmi alternate + 30 min hold, the alternate's fuel above the hold's (ICAO Annex 6 items)."""
    d = result.design
    assert d.initial_altitude_m == pytest.approx(31000 * FT)
    assert [s.to_altitude_m for s in d.steps] == sorted(s.to_altitude_m for s in d.steps)
    assert sum(p.fuel_kg for p in d.phases) == pytest.approx(d.block_fuel_kg)
    airborne = sum(p.fuel_kg for p in d.phases if p.name not in ("taxi_out", "taxi_in"))
    assert d.takeoff_weight_kg - airborne == pytest.approx(d.landing_weight_kg)
    assert d.landing_weight_kg - d.zero_fuel_weight_kg == pytest.approx(sum(d.reserves.values()), rel=1e-4)
    assert d.reserves["contingency"] == pytest.approx(0.05 * d.trip_fuel_kg)
    assert 0 < d.reserves["final_reserve"] < d.reserves["alternate"]
    assert d.landing_weight_kg < 460000 * LB


def test_oew_increase_costs_range_as_breguet_predicts(result, base_ctx):
    """+1,000 kg of OEW at fixed takeoff weight and payload: the range falls by about V (L/D)/(c g) × ΔW/W_end
    (Breguet differentiated at the end weight), within 25 % (steps and reserves shift), and block fuel rises."""
    heavier = fly_missions(
        base_ctx.aircraft, base_ctx.aero("clean"), tables_cache=TABLES, oew_kg=base_ctx.aircraft.mass.OEW + 1000.0
    )
    c = result.cruise_drag
    from certkit import atmosphere as isa
    from certkit.models.performance.fuel_flow import EngineFuel

    tsfc = float(EngineFuel.of(base_ctx.aircraft).tsfc(c.altitude_m, c.mach))
    v = float(isa.mach_to_tas(c.mach, c.altitude_m))
    d = result.design
    w_end = d.landing_weight_kg
    expected = v * c.lift_to_drag / (tsfc * 9.80665) * 1000.0 / w_end
    loss = result.design_range_m - heavier.design_range_m
    assert loss == pytest.approx(expected, rel=0.25)
    assert heavier.nominal.block_fuel_kg > result.nominal.block_fuel_kg


def test_tail_change_shows_in_cruise_drag_and_fuel(result, baseline):
    """A 25 % larger horizontal tail (more wetted area, a different trim load): cruise CD and block fuel rise, the
    design range falls, and the declared calibration factors in force are the baseline's."""
    a = baseline.model
    ht = a.geometry.horizontal_tail.model_copy(update={"area": 1.25 * a.geometry.horizontal_tail.area})
    bigger = a.model_copy(update={"geometry": a.geometry.model_copy(update={"horizontal_tail": ht})})
    other = fly_missions(bigger)
    assert other.cruise_drag.CD > result.cruise_drag.CD
    assert other.nominal.block_fuel_kg > result.nominal.block_fuel_kg
    # the design is flown against the baseline's declared calibration, not re-calibrated: the same factors, less range
    assert other.calibration == result.calibration and other.calibration["drag_factor"] == a.calibration.drag_factor
    assert other.design_range_m < result.design_range_m


def test_one_mission_after_warm_up_is_fast(base_ctx):
    """The design study runs this thousands of times: well under 1 s once the tables are trimmed."""
    start = time.perf_counter()
    fly_missions(
        base_ctx.aircraft, base_ctx.aero("clean"), tables_cache=TABLES, oew_kg=base_ctx.aircraft.mass.OEW + 10.0
    )
    assert time.perf_counter() - start < 1.0


def test_no_level_is_reached_by_crawling_above_the_thrust_ceiling(result, base_ctx):
    """Above the first cruise level the climb holds at least the declared residual climb rate (300 ft/min, the
    thrust-limited ceiling of the levels): from 85–105 % of MTOW every level the climb reaches is reached within
    an hour of brake release. (Climbing on at any positive excess power, the 43,000-ft level was reached from 85 %
    of MTOW after a climb burning 57 t — hours at a few feet per minute, the fuel burnt on the way making the level
    "allowed" at the top; on a study design the nominal mission then had no cruise at all and 8 t more block
    fuel.)"""
    aircraft = base_ctx.aircraft
    tables = next(iter(TABLES.values()))
    flyer = MissionFlyer(aircraft, tables, aircraft.mass.OEW)
    for w in np.linspace(0.85, 1.05, 9) * aircraft.mass.MTOW:
        tocs = flyer.climb(w)
        assert tocs[0][0]  # the first level is reached at every weight
        for reached, _, time_s, *_ in tocs:
            assert not reached or time_s < 3600.0
