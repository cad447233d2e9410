"""The takeoff pilot's pedals, the steered nose wheel and the ground minimum control speed (VMCG) by simulation,
against references no one here wrote.

* Pilot (AC 25-7D practice for VMCG: the engine cut without warning, no anticipation): after the failure the rudder
  stays where it was for the stated reaction time, then changes by at most the stated rate per second (exact: the
  rate limit holds to rounding, the hold to one 0.1-s step).
* Steered nose wheel: at low speed, wheels rolling without side slip, the airplane turns as a bicycle about the main
  gear: yaw rate r = V tan δ / ℓ with ℓ the wheelbase (kinematic steering, Gillespie, *Fundamentals of Vehicle
  Dynamics*, SAE 1992, §6 low-speed turning, eq. 6-1 δ = L/R); tolerance 10 % (the tyres' smooth friction law slips a
  little).
* VMCG against the closed-form rudder-moment balance: the speed at which the rudder at its stop balances the yawing
  moment of the live engine's thrust and the dead one's windmilling drag, q S b |Cn_δr| δ_max = N_thrust (airborne,
  wings level, no sideslip, the moments evaluated by the model at β = 0 and zero rates). The dynamic VMCG of the
  heaviest corner lies within 10 % of it: the pilot's 1-s reaction and the swing raise it, the main gear's side
  friction (9.75 ft behind the CG, against the engine's 32.3-ft arm) lowers it.
"""

import numpy as np
import pytest

from certkit.atmosphere import convert_speed
from certkit.models.dynamics.eom import STEERING
from certkit.models.dynamics.ground import ground_equilibrium
from certkit.models.dynamics.ground_control import engine_cut_runs, ground_minimum_control_speed
from certkit.models.dynamics.simulate import simulate
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN


def _tas(kn):
    return float(convert_speed(kn * KN, "CAS", "TAS", 0.0))


@pytest.fixture
def heavy(ctx):
    ac = ctx.aircraft
    from certkit.models.mass.loading import reference_cg

    return ac, ctx.loading(ac.mass.MTOW, reference_cg(ac), "MTOW reference")


def test_pilot_holds_for_the_reaction_time_then_moves_at_the_rate(heavy, ctx):
    ac, loading = heavy
    model = flight_model(ac, ctx.aero("takeoff").model, [loading], ground=ground_model(ac, nose_wheel="castering"))
    rate, reaction = np.radians(20.0), 1.5
    runs = engine_cut_runs(
        model, _tas(140.0), "left", reaction, rate, decay_time=1.5, lateral_limits=control_limits(ac, design=False)
    )
    sim = runs.sim
    dr = sim.controls[:, 0, sim.control_names.index("rudder")]
    k_fail = int(np.argmax(sim["V"][:, 0] >= runs.failure_speed[0]))
    t_fail = sim.t[k_fail]
    held = (sim.t >= t_fail) & (sim.t < t_fail + reaction - 0.1 - 1e-9)
    assert np.ptp(dr[held]) == pytest.approx(0.0, abs=1e-12)
    assert np.abs(np.diff(dr)).max() <= rate * 0.1 + 1e-12
    after = sim.t >= t_fail + reaction + 0.1
    assert np.abs(dr[after]).max() > np.radians(10.0)  # the pilot does push the pedal
    assert runs.recovered[0] and runs.deviation[0] < 60.0


def test_steered_nose_wheel_turns_the_airplane_as_a_bicycle(heavy, ctx):
    ac, loading = heavy
    model = flight_model(ac, ctx.aero("takeoff").model, [loading], ground=ground_model(ac, nose_wheel="steered"))
    u = np.zeros((1, len(model.control_names)))
    x0 = ground_equilibrium(model, u)
    V, delta = 8.0, np.radians(5.0)
    x0[0, 3], x0[0, 5] = V * np.cos(x0[0, 10]), V * np.sin(x0[0, 10])
    u[0, model.control_index(STEERING)] = delta
    u[0, model.throttle_slice] = 0.12  # about the thrust that keeps the speed against rolling friction
    sim = simulate(model, x0, u, 20.0, 0.05)
    lg = ac.geometry.landing_gear
    wheelbase = lg.main.x - lg.nose.x
    k = sim.t >= 15.0
    r_expected = sim["V"][k, 0] * np.tan(delta) / wheelbase
    assert sim["r"][k, 0] == pytest.approx(r_expected, rel=0.10)
    assert sim["r"][k, 0].min() > 0.0  # positive steering: nose right


def test_vmcg_against_the_rudder_moment_balance(ctx):
    ac = ctx.aircraft
    loading = ctx.loading(ac.mass.MTOW, 94.23 * FT, "fwd_mrw")
    aero = ctx.aero("takeoff").model
    travel = control_limits(ac, design=False)
    # the static balance: rudder at its stop against the live engine's thrust and the dead one's windmilling drag
    kns = np.linspace(110.0, 170.0, 61)
    n = kns.size
    air = flight_model(ac, aero, [loading] * n, operative=np.array([[False, True]] * n))
    u = np.zeros((n, len(air.control_names)))
    u[:, air.throttle_slice] = 1.0
    x = np.zeros((n, 12))
    x[:, 2], x[:, 3] = 10.0, [_tas(k) for k in kns]
    jr = air.control_index("rudder")
    r0 = air.derivatives_euler(x, u)[:, 8]
    u[:, jr] = travel["rudder"][0]
    r_full = air.derivatives_euler(x, u)[:, 8]
    assert r0[0] < 0.0 < r_full[-1]  # the dead left engine yaws the nose left; full right rudder wins at speed
    v_static = float(np.interp(0.0, r_full, kns))
    ground = flight_model(ac, aero, [loading], ground=ground_model(ac, nose_wheel="castering"))
    found = ground_minimum_control_speed(
        ground,
        "left",
        _tas(60.0),
        _tas(155.0),
        30.0 * FT,
        1.0,
        np.radians(30.0),
        decay_time=ac.propulsion.failure_decay_time,
        lateral_limits=travel,
        elevator_limits=travel["elevator"],
    )
    vmcg = float(convert_speed(found.speed[0], "TAS", "CAS", 0.0)) / KN
    assert not (found.below[0] or found.above[0])
    assert vmcg == pytest.approx(v_static, rel=0.10)
    # the search's bracket: the deviation is beyond 30 ft just below VMCG and within it just above
    v, d = np.asarray(found.speeds[0]), np.asarray(found.deviations[0])
    assert d[v < found.speed[0]].min() > 30.0 * FT >= d[v > found.speed[0]].max()


def test_takeoff_run_steers_with_the_pedals_on_the_ground_only(heavy, ctx):
    """With pedal steering declared (7° at full pedal, the travel ±27.3°) the takeoff pilot turns the nose wheel by
    −7/27.3 of the rudder while a gear leg carries load and leaves it straight once airborne (a definition: the
    pedal-to-wheel gearing is linear)."""
    from certkit.models.dynamics.procedures import takeoff_run

    ac, loading = heavy
    model = flight_model(ac, ctx.aero("takeoff").model, [loading], ground=ground_model(ac, nose_wheel="steered"))
    travel = control_limits(ac, design=False)
    run = takeoff_run(
        model,
        _tas(155.0),
        np.radians(8.0),
        climb_speed=_tas(161.0),
        lateral="pilot",
        lateral_limits=travel,
        failed_engine="left",
        failure_speed=_tas(147.0),
        failure_decay_time=1.5,
        reaction_time=1.0,
        rudder_rate=np.radians(30.0),
        steering=np.radians(7.0),
        dt=0.1,
    )
    sim = run.sim
    dr = sim.controls[:, 0, sim.control_names.index("rudder")]
    nw = sim.controls[:, 0, sim.control_names.index(STEERING)]
    ground = run.wheel_height[:, 0] < -0.05  # a strut clearly compressed (at lift-off the load leaves first)
    air = run.wheel_height[:, 0] > 0.0
    assert np.abs(dr[ground]).max() > np.radians(10.0)
    assert nw[ground] == pytest.approx(-dr[ground] * 7.0 / 27.3, abs=np.radians(0.5))
    assert np.abs(nw[air]).max() == pytest.approx(0.0, abs=1e-12)
