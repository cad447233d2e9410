"""Closed-loop runs whose laws the compiled loop can step (:mod:`certkit.models.dynamics.controlled_run`: the takeoff
pilot, the heading and wings-level holds, the attitude hold, the engine failure, the screen-height and engine-cut stop
criteria) must give the Python loop's run: the same grid, the same stop steps and reasons, the records, controls and
final state within round-off (1e-9 of each history's scale: the laws' transcendental functions are libm's in the
kernel and numpy's SIMD ones in Python, which may differ in the last bit), the laws' and criteria's end states and the
model's engines left alike. Several rows per batch, so rows stop at different steps and fail at different times."""

import numpy as np
import pytest

import certkit.models.dynamics.simulate as simulate_module
from certkit.atmosphere import convert_speed
from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.ground_control import engine_cut_runs
from certkit.models.dynamics.procedures import takeoff_run
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import KN


def _tas(kn):
    value = np.asarray(convert_speed(np.asarray(kn, dtype=float) * KN, "CAS", "TAS", 0.0), dtype=float)
    return float(value) if value.ndim == 0 else value


@pytest.fixture
def models(ctx):
    """A fresh batch model per call: ``weights`` (fractions of MTOW) at the reference CG, nose wheel ``nose``."""
    from certkit.models.mass.loading import reference_cg

    ac = ctx.aircraft

    def make(nose="steered", weights=(0.7, 0.85, 1.0)):
        loadings = [ctx.loading(ac.mass.MTOW * f, reference_cg(ac), "") for f in weights]
        return flight_model(ac, ctx.aero("takeoff").model, loadings, ground=ground_model(ac, nose_wheel=nose))

    return ac, make


def _both(monkeypatch, run):
    """``run()`` through the compiled loop (checked to be taken by every closed-loop run), then through the Python
    loop."""
    calls, offered = [], []
    kernel, blocks = pilot_kernel.integrate_controlled, simulate_module.controlled_blocks

    def counted(*args):
        calls.append(1)
        return kernel(*args)

    def checked(*args):
        offered.append(blocks(*args))
        return offered[-1]

    with monkeypatch.context() as m:
        m.setattr(pilot_kernel, "integrate_controlled", counted)
        m.setattr(simulate_module, "controlled_blocks", checked)
        compiled = run()
    assert calls and len(calls) == len(offered) and all(b is not None for b in offered), "not every run compiled"
    with monkeypatch.context() as m:
        m.setattr(simulate_module, "controlled_blocks", lambda *a: None)
        loop = run()
    return compiled, loop


def _assert_same_sim(compiled, loop):
    np.testing.assert_array_equal(compiled.t, loop.t)
    assert compiled.stop_reason == loop.stop_reason
    np.testing.assert_array_equal(compiled.stop_time, loop.stop_time)
    for key, ref in loop.history.items():
        np.testing.assert_allclose(
            compiled.history[key], ref, rtol=1e-9, atol=1e-9 * max(1.0, float(np.abs(ref).max())), err_msg=key
        )
    np.testing.assert_allclose(compiled.controls, loop.controls, rtol=1e-9, atol=1e-11)
    np.testing.assert_allclose(compiled.final_state, loop.final_state, rtol=1e-9, atol=1e-9)


def _assert_same_fields(a, b, names):
    for name in names:
        x, y = np.asarray(getattr(a, name)), np.asarray(getattr(b, name))
        if x.dtype == bool:
            np.testing.assert_array_equal(x, y, err_msg=name)
        else:
            np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-9, err_msg=name)


TAKEOFF_FIELDS = (
    "reached",
    "v_lof",
    "x_lof",
    "v_screen",
    "x_screen",
    "t_screen",
    "elevator_min",
    "elevator_max",
    "climb_gradient",
    "pitch_on_ground_max",
    "pitch_rate_max",
    "lateral_on_ground_max",
    "x_screen_crossing",
)


@pytest.mark.parametrize(
    "case",
    [
        dict(lateral="pilot", failed_engine="left", failure_decay_time=1.5, reaction_time=1.0, steering=7.0),
        dict(lateral="pilot", failed_engine="right", reaction_time=0.5, rudder_rate=20.0),
        dict(lateral="heading", climb_out=4.0, bank_airborne=np.radians(3.0)),
        dict(lateral="wings level", failed_engine="left", failure_decay_time=2.0),
    ],
    ids=["pilot, spool-down, steering", "pilot, windmilling at once", "heading hold, climb-out", "wings level"],
)
def test_compiled_takeoff_equals_the_python_loop(models, monkeypatch, case):
    ac, make = models
    case = dict(case)
    for key in ("steering", "rudder_rate"):
        if key in case:
            case[key] = np.radians(case[key])
    if "failed_engine" in case:
        case["failure_speed"] = _tas([140.0, 147.0, 152.0])  # a failure time per row
    holder = {}

    def run():
        model = make("steered" if "steering" in case else "castering")
        holder.setdefault("models", []).append(model)
        return takeoff_run(
            model,
            _tas(155.0),
            np.radians(8.0),
            climb_speed=_tas(161.0),
            lateral_limits=control_limits(ac, design=False),
            dt=0.05,
            **case,
        )

    compiled, loop = _both(monkeypatch, run)
    assert compiled.reached.any()
    _assert_same_sim(compiled.sim, loop.sim)
    _assert_same_fields(compiled, loop, TAKEOFF_FIELDS)
    m1, m2 = holder["models"]
    np.testing.assert_array_equal(m1.operative, m2.operative)  # the engines as the failure left them
    np.testing.assert_allclose(m1.failed_thrust_fraction, m2.failed_thrust_fraction, rtol=1e-12, atol=0.0)
    if "failed_engine" in case:
        assert not m1.operative.all()


@pytest.mark.parametrize("decay", [1.5, None], ids=["spool-down", "windmilling at once"])
def test_compiled_engine_cuts_equal_the_python_loop(models, monkeypatch, decay):
    """The VMCG runs: the attitude hold, the pedals waiting for the pilot's reaction, the failure and the engine-cut
    stop criterion (rows recovered or lifted off, the swing arrested or not, at different steps)."""
    ac, make = models

    def run():
        return engine_cut_runs(
            make("castering", (0.7, 0.7, 0.85, 1.0)),
            _tas([175.0, 185.0, 150.0, 135.0]),
            "left",
            1.0,
            np.radians(20.0),
            decay_time=decay,
            lateral_limits=control_limits(ac, design=False),
        )

    compiled, loop = _both(monkeypatch, run)
    assert len(set(compiled.sim.stop_time)) > 1  # the rows end at different steps
    assert compiled.recovered.any() and (compiled.airborne & ~compiled.arrested).any()
    assert compiled.arrested.any() or decay is None  # with the spool-down the lightest row lifts off swinging back
    _assert_same_sim(compiled.sim, loop.sim)
    _assert_same_fields(
        compiled,
        loop,
        ("deviation", "recovered", "heading_swing", "rudder_peak", "recovery_time", "airborne", "arrested"),
    )


def test_a_law_already_stepped_or_changed_is_left_to_the_python_loop(models):
    """A law past its first step (its state no longer the kernel's start) and a subclass that changes a law's
    equations without a block of its own are not compiled."""
    from certkit.models.dynamics.controlled_run import controlled_blocks
    from certkit.models.dynamics.controllers import EngineFailure, HeadingHold, WingsLevel

    ac, make = models
    model = make()
    u = np.zeros((model.n, len(model.control_names)))
    assert controlled_blocks(model, [HeadingHold(model, u)], []) is not None
    stepped = HeadingHold(model, u)
    stepped.psi0 = np.zeros(model.n)
    assert controlled_blocks(model, [stepped], []) is None

    class Reversed(WingsLevel):
        def update(self, t, x, out, u, dt):
            return -super().update(t, x, out, u, dt)

    assert controlled_blocks(model, [Reversed(model, u)], []) is None
    assert controlled_blocks(model, [WingsLevel(model, u), HeadingHold(model, u)], []) is None  # two lateral laws
    other = make()
    assert controlled_blocks(model, [EngineFailure(model, "left", 50.0)], []) is not None
    assert controlled_blocks(model, [EngineFailure(other, "left", 50.0)], []) is None  # fails another model's engine


def test_compiled_approach_and_landing_equals_the_python_loop(ctx, monkeypatch):
    """The total-energy approach, its flare and the wings-level hold to the touchdown criterion, three conditions
    (the landing weight at two CGs and a lighter one, VREF and 10 kn more) stopping at different steps."""
    from certkit.engine.conditions import ConditionSpace, DesignWeight
    from certkit.models.dynamics.procedures import approach_and_landing
    from certkit.units import FT

    ac = ctx.aircraft
    conds = ConditionSpace(loading=DesignWeight("MLW", ("forward", "aft")), configurations=("landing",)).expand(ac)
    conds = [c.with_(altitude=150 * FT, speed=s * KN, speed_kind="CAS") for c, s in zip(conds * 2, (136, 146, 140))]
    tb = ctx.trim(conds[:3], gamma=np.radians(-3.0))
    assert tb.converged.all()
    loadings = [ctx.loading(c.mass, c.x_cg) for c in conds[:3]]

    def run():
        m = flight_model(ac, ctx.aero("landing").model, loadings, ground=ground_model(ac))
        return approach_and_landing(m, tb.x, tb.u, elevator_limits=control_limits(ac, design=False)["elevator"])

    compiled, loop = _both(monkeypatch, run)
    assert compiled.touched_down.all() and len(set(compiled.sim.stop_time)) > 1
    _assert_same_sim(compiled.sim, loop.sim)
    _assert_same_fields(compiled, loop, ("touched_down", "sink_rate", "speed", "elevator_min", "elevator_max"))


def test_compiled_yaw_manoeuvre_equals_the_python_loop(ctx, monkeypatch):
    """§25.351's runs: a scheduled rudder ramp with the aileron's roll hold until the sideslip settles (rows settling
    at different steps), then the rudder returned (a schedule per row) with the hold's integral carried on."""
    from certkit_rules.part25.support.loads_conditions import trimmed_batch

    from certkit.engine.conditions import CgCorners, ConditionSpace
    from certkit.models.loads.yaw import simulate_yaw

    cond = ConditionSpace(loading=CgCorners(), configurations=("clean",), altitudes=None).expand(ctx.aircraft)[0]
    batch = trimmed_batch(ctx, [cond.with_(speed=s * KN, speed_kind="EAS") for s in (250.0, 272.0, 300.0)])

    def run():
        return simulate_yaw(batch.model, batch.x, batch.u, np.radians([-10.0, -8.0, -6.0]), t_max=30.0)

    compiled, loop = _both(monkeypatch, run)
    assert compiled.settled.any() and len(set(compiled.held.stop_time)) > 1
    _assert_same_sim(compiled.held, loop.held)
    _assert_same_sim(compiled.returned, loop.returned)
    _assert_same_fields(compiled, loop, ("t_overswing", "t_steady", "settled", "beta_band", "u_steady"))
