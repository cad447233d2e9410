"""A compiled run takes every step's scheduled controls at once (:meth:`Schedule.over` on the grid of step times);
they must be exactly the values the schedule gives one step at a time (the Python loop's), for one time step and for
a time step per condition, including the schedules written with branches on t (Doublet, Pulse: stepped)."""

import numpy as np
import pytest

from certkit.models.dynamics.simulate import (
    CheckedManeuver,
    Doublet,
    Function,
    Hold,
    Pulse,
    Ramp,
    RudderKick,
    Step,
    simulate,
)
from certkit.models.loads.gust import one_minus_cosine
from certkit.models.loads.inputs import SinusoidHold

N = 5
AMP = np.linspace(-0.1, 0.2, N)
V = np.linspace(120.0, 250.0, N)


def schedules():
    return {
        "step": Step(0.3, AMP),
        "ramp": Ramp(0.1, 0.6, AMP),
        "hold": Hold(AMP),
        "checked": CheckedManeuver(AMP, np.linspace(1.0, 2.5, N), t0=0.05, hold=0.4),
        "kick": RudderKick(0.2, AMP, ramp=0.3, hold=0.5),
        "sinusoid hold": SinusoidHold(AMP, np.linspace(1.2, 2.0, N), np.linspace(0.0, 0.5, N)),
        "sum": Step(0.3, AMP) + Ramp(0.0, 1.0, 0.5 * AMP),
        "gust": Function(lambda t: one_minus_cosine(V * t, 30.0, AMP), time_grid=True),
        "doublet (stepped)": Doublet(0.2, 0.3, 0.05),
        "pulse (stepped)": Pulse(0.2, 0.3, AMP),
    }


@pytest.mark.parametrize("name", list(schedules()))
@pytest.mark.parametrize("per_condition", [False, True], ids=["one step", "a step per condition"])
def test_grid_values_equal_step_by_step(name, per_condition):
    s = schedules()[name]
    if per_condition and name.endswith("(stepped)"):
        pytest.skip("Doublet and Pulse take one time (Python branches on t), in the step-by-step loop as well")
    dt = np.linspace(0.008, 0.012, N) if per_condition else 0.01
    steps = np.arange(151)
    times = steps[:, None] * dt[None, :] if per_condition else (steps * dt)[:, None]
    grid = np.broadcast_to(s.over(times), (steps.size, N))
    one_by_one = np.array([np.broadcast_to(np.asarray(s(k * dt), dtype=float), (N,)) for k in steps])
    np.testing.assert_array_equal(grid, one_by_one)
    assert np.any(one_by_one != 0.0)  # the grid covers the input, not only its zeros


def test_a_compiled_run_is_the_same_with_the_grid_or_step_by_step(baseline):
    """The gust schedules evaluated on the grid give the run the step-by-step evaluation gives, bit for bit."""
    from certkit.engine.context import Context
    from certkit.models.dynamics.trim import trim
    from certkit.models.flight import ROLES, control_limits, flight_model

    ctx = Context(baseline)
    loadings = [ctx.loading(float(baseline.model.mass.MTOW) * f, 29.5, "x") for f in np.linspace(0.7, 1.0, N)]
    model = flight_model(baseline.model, ctx.aero("clean").model, loadings)
    trims = trim(model, V, np.linspace(0, 10000, N), limits=control_limits(baseline.model), roles=ROLES)
    assert model.runs_open_loop_compiled

    def gust(t):
        return 0.05 * one_minus_cosine(V * t, 40.0, np.ones(N))

    dt = np.linspace(0.008, 0.012, N)
    runs = [
        simulate(model, trims.x, trims.u, 1.0, dt, inputs={"elevator": Function(gust, time_grid=g)})
        for g in (True, False)
    ]
    np.testing.assert_array_equal(runs[0].controls, runs[1].controls)
    np.testing.assert_array_equal(runs[0].final_state, runs[1].final_state)
