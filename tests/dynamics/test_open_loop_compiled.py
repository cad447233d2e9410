"""A fixed-step run whose controls are all scheduled (no controllers, no stop criteria) runs in one compiled loop
(:func:`certkit.models.dynamics.kernel.integrate_open_loop`); it must give the Python loop's run: the same grid and
controls, the states and outputs within round-off (1e-9 of each history's scale), one time step or one per
condition."""

import numpy as np
import pytest

from certkit.models.dynamics.simulate import Function, simulate
from certkit.models.dynamics.trim import trim
from certkit.models.flight import ROLES, control_limits, flight_model


@pytest.fixture(scope="module")
def batch(baseline):
    from certkit.context import Context

    ctx = Context(baseline)
    n = 6
    loadings = [ctx.loading(float(baseline.model.mass.MTOW) * f, 29.5, "x") for f in np.linspace(0.7, 1.0, n)]
    model = flight_model(baseline.model, ctx.aero("clean").model, loadings)
    trims = trim(model, np.linspace(150, 250, n), np.linspace(0, 10000, n), limits=control_limits(baseline.model),
                 roles=ROLES)
    return model, trims, {"elevator": Function(lambda t: 0.02 * np.sin(t) * np.ones(n))}


@pytest.mark.parametrize("dt", [0.01, np.linspace(0.008, 0.012, 6)], ids=["one step", "a step per condition"])
def test_compiled_run_equals_the_python_loop(batch, dt):
    model, trims, inputs = batch
    assert model._turbofan is not None  # the baseline's engines are parametric turbofans: the compiled path runs
    compiled = simulate(model, trims.x, trims.u, 3.0, dt, inputs=inputs)
    saved, model._turbofan = model._turbofan, None
    try:
        loop = simulate(model, trims.x, trims.u, 3.0, dt, inputs=inputs)
    finally:
        model._turbofan = saved
    np.testing.assert_array_equal(compiled.t, loop.t)
    np.testing.assert_array_equal(compiled.controls, loop.controls)
    for key, ref in loop.history.items():
        np.testing.assert_allclose(compiled.history[key], ref, rtol=1e-9, atol=1e-9 * max(1.0, float(np.abs(ref).max())),
                                   err_msg=key)
    np.testing.assert_allclose(compiled.final_state, loop.final_state, rtol=1e-9, atol=1e-9)
