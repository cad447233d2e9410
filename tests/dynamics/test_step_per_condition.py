"""A time step per condition (certkit.models.dynamics.simulate.simulate with an (n,) ``dt``, as the gust runs use
it) integrates each condition exactly as a run of its own at that step: same times, same histories (to rounding),
with the scheduled input seen at each condition's own time."""

import numpy as np

from certkit.models.aero.derivative_model import StabilityDerivativeModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.simulate import Function, simulate
from certkit.models.loads.gust import gust_aero, one_minus_cosine


def model_and_state(n):
    ref = AeroReference(400.0, 60.0, 7.0, 30.0, 0.0)
    base = StabilityDerivativeModel(ref, {"CL_alpha": 5.0, "Cm_alpha": -1.2, "Cm_q": -20.0, "CL0": 0.3})
    aero = gust_aero(base, np.array([0.0, 1.0]), np.array([5.0, 5.0]), np.array([-1.5, -1.5]), np.zeros(2), np.zeros(2))
    model = AircraftModel(
        aero, np.full(n, 200_000.0), np.tile([30.0, 0.0, 0.0], (n, 1)), np.tile(np.diag([1e7, 2e7, 3e7]), (n, 1, 1))
    )
    V = np.array([150.0, 240.0])[:n]
    x0 = np.zeros((n, 12))
    x0[:, 2], x0[:, 3], x0[:, 10] = 3000.0, V, 0.02
    return model, x0, V


def test_per_condition_step_equals_separate_runs():
    model, x0, V = model_and_state(2)
    H = 30.0
    dt = 2 * H / V / 20  # each condition's gust length in 20 steps

    def gust(t):
        return one_minus_cosine(V * t, H, 5.0 / V)

    both = simulate(model, x0, np.zeros((2, 2)), 40 * dt, dt, inputs={"gust_wing": Function(gust)})
    assert both.t.shape == (41, 2)
    for i in range(2):

        def own(t, i=i):
            return np.array([one_minus_cosine(V[i] * t, H, 5.0 / V[i])])

        single, _, _ = model_and_state(1)
        alone = simulate(
            single, x0[i : i + 1], np.zeros((1, 2)), 40 * dt[i], float(dt[i]), inputs={"gust_wing": Function(own)}
        )
        np.testing.assert_allclose(both.t[:, i], alone.t, rtol=1e-12)
        for key in ("n_z", "q", "alpha", "theta"):
            np.testing.assert_allclose(both[key][:, i], alone[key][:, 0], rtol=1e-9, atol=1e-12)
